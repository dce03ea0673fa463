#pragma once
// The real-time plant on the validation's sample grid (docs/validation.md#method).
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// The plant in double through the scene dispatch, every frame whose time is
// a multiple of sample_s. Throws InputError if the scene does not load,
// RunError naming the time and the fault if the plant faults.
Series plant_run(const cvt::Scene& s, double sample_s);

}  // namespace cvt::validation
