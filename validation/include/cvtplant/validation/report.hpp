#pragma once
// What `cvtplant validate` writes per scene (docs/cli.md#validate): the
// overlay CSV of both models and its stacked-panel PNG.
#include <cstdio>
#include <string>

#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// One row per common sample: t, then plant and reference side by side for
// each quantity (speeds, ratio where |omega2| >= 1 rad/s, F_ax1, torque on
// the driver, driver slip, the whole driver wrap's slip). The caller opens
// and closes f (write errors are the caller's to check).
void write_overlay_csv(std::FILE* f, const Series& plant, const Series& reference);

// The PNG of the overlay CSV `csv`, through the gnuplot script dir/name.gp:
// stacked panels, one per unit, with a dotted line at compared_s when the
// comparison ends before t_end_s. Throws cvt::analysis::InputError if the
// script cannot be written or gnuplot fails.
void write_overlay_png(const std::string& dir, const std::string& name, const std::string& csv,
                       const std::string& png, double compared_s, double t_end_s);

}  // namespace cvt::validation
