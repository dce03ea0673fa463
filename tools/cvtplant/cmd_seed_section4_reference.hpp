#pragma once
// `cvtplant analyze seed-section4 --reference --case 1|2 [--steady W1,...]`:
// the seed's section-4 pipeline on the multibody reference
// (docs/seed-section4.md), registered as options of `analyze seed-section4`
// beside its ROM-scene form.
#include <CLI/CLI.hpp>

#include <memory>

namespace cvtcli {

struct Section4Reference;

// Adds --reference and the options of the reference's form to the
// subcommand; the options it shares with the scene form (--out-dir,
// --signals, --t-end, --t-transient, --tau, --m, --json, --max-steps,
// --max-memory-mb) are read from it after parsing.
std::shared_ptr<Section4Reference> add_section4_reference(CLI::App* seed_section4);
bool section4_reference_selected(const Section4Reference& r);
// The subcommand's body when --reference is given.
int run_section4_reference(const Section4Reference& r);

}  // namespace cvtcli
