#pragma once
// A plant scene as the multibody reference's inputs (docs/validation.md#method):
// the single place that maps a scene to the reference.
#include <optional>
#include <string>

#include "cvtplant/mbd/params.hpp"
#include "cvtplant/scene/scene.hpp"

namespace cvt::validation {

// `--sheaves scene|clamped|fixed` of validate and calibrate: each scene's own
// sheaves, or one mode for all.
enum class SheaveChoice { scene, clamped, fixed };
inline constexpr const char* kSheaveChoiceNames[] = {"scene", "clamped", "fixed"};
// The choice of a name of kSheaveChoiceNames; throws InputError otherwise.
SheaveChoice sheave_choice(const std::string& name);
const char* sheave_mode_name(cvt::mbd::SheaveMode m);  // "fixed", "clamped"

// The reference's sheaves for a scene: with `scene`, fixed where the plant's
// driver sheave is fixed (the tension feature with `fixed_sheaves`: its
// axial force is then the chain's, as on the reference's fixed pulleys),
// else clamped (the plant's axial force is its clamping input).
cvt::mbd::SheaveMode reference_sheaves(const cvt::Scene& s, SheaveChoice c);

// The reference's inputs for a plant scene against the named parameter set
// (docs/validation.md#parameter-sets), or why it cannot run that scene (a
// reason in `why_not`). Its torque profiles, road load and start speeds (a
// start at speed, docs/mbd.md#start-at-speed) become the reference's; its
// sheaves are reference_sheaves(s, c). Clamped sheaves
// (docs/mbd.md#clamped-sheaves) are pushed by the scene's clamping profile
// (the driven one, with wedging, by its driven clamping); fixed sheaves are
// the seed's pulleys, whose axial force is an output.
//  - seed: Table 1's chain and pulleys; the scene's friction law, inertias
//    and half sheave angle are copied.
//  - production (docs/mbd-production.md): the set's chain, friction and
//    sheaves; the scene's inertias are copied (the driveline's, not the
//    chain's); the chain starts at the plant's initial radial offset
//    (`initial.radius_offset_m`, on the driver radius), the driver sheave
//    locked there until the release. Clamped sheaves only.
// Refused: held pulleys, initial lump states (and a radial offset on the
// seed set), a start with one pulley at rest, sine profiles, clamping below
// 100 N (clamped), fixed sheaves on the production set.
std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice c,
                                                    cvt::mbd::ParameterSet set, std::string& why_not);
// The seed set's (the built-in scenes').
std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice c, std::string& why_not);

// The tolerance of the reference's start-up for a set (docs/mbd.md#start-up):
// the seed's 1e-8, the production set's 1e-6 (its stiff chain costs about 6x
// the steps at 1e-8), as `cvtplant mbd --set` runs them.
double settle_rtol(cvt::mbd::ParameterSet set);

// The parameter set of a name (cvt::mbd::parameter_set_by_name); throws
// InputError naming the known sets otherwise.
cvt::mbd::ParameterSet parameter_set(const std::string& name);

}  // namespace cvt::validation
