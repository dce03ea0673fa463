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

// The reference's inputs for a plant scene, or why it cannot run that scene
// (a reason in `why_not`). The scene's friction law, inertias and half
// sheave angle are copied; its torque profiles, road load and start speeds
// (a start at speed, docs/mbd.md#start-at-speed) become the reference's; its
// sheaves are reference_sheaves(s, c). Clamped sheaves
// (docs/mbd.md#clamped-sheaves) are pushed by the scene's clamping profile;
// fixed sheaves are the seed's pulleys, whose axial force is an output.
// Refused: held pulleys, initial lump states, a start with one pulley at
// rest, sine profiles, clamping below 100 N (clamped).
std::optional<cvt::mbd::MbdParams> reference_params(const cvt::Scene& s, SheaveChoice c, std::string& why_not);

}  // namespace cvt::validation
