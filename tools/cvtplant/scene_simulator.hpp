#pragma once
// A scene's simulator for the subcommands (docs/architecture.md#scene-dispatch):
// the scene dispatch of lib/ (every plant, AllRomPlants) in the scalar type
// the command asks for.
#include <string>
#include <utility>

#include "commands.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scene/all_plants.hpp"

namespace cvtcli {

// Throws the UsageError with_scene_simulator would, without running anything
// (so a command can refuse before it prints).
inline void check_scene_simulator(const cvt::Scene& s, cvt::ScalarKind scalar, const std::string& what = "") {
  cvt::SceneIssue issue;
  switch (scalar) {
    case cvt::ScalarKind::f32: issue = cvt::check_scene_plant<cvt::AllRomPlants<float>>(s); break;
    case cvt::ScalarKind::q16_16: issue = cvt::check_scene_plant<cvt::AllRomPlants<cvt::q16_16>>(s); break;
    case cvt::ScalarKind::f64:
    default: issue = cvt::check_scene_plant<cvt::AllRomPlants<double>>(s); break;
  }
  if (!issue.ok) throw UsageError{what + std::string(issue.field) + ": " + issue.message};
}

// fn(cvt::IRomSimulator<T>& sim) with the scene's plant built in scalar
// `scalar` with `cfg` and reset to the scene's start. A scene the plants
// cannot run (invalid, or a feature the scalar type has no plant for) is a
// UsageError naming the field; `what` prefixes the message (e.g. the flag
// that chose the scalar).
template <class Fn>
decltype(auto) with_scene_simulator(const cvt::Scene& s, cvt::ScalarKind scalar, const cvt::RomSimConfig& cfg,
                                    Fn&& fn, const std::string& what = "") {
  auto run = [&](auto tag) -> decltype(auto) {
    using T = decltype(tag);
    cvt::SceneSimulator<cvt::AllRomPlants<T>> holder;
    const cvt::SceneIssue issue = holder.load(s, cfg);
    if (!issue.ok) throw UsageError{what + std::string(issue.field) + ": " + issue.message};
    return fn(holder.sim());
  };
  switch (scalar) {
    case cvt::ScalarKind::f32: return run(float{});
    case cvt::ScalarKind::q16_16: return run(cvt::q16_16{});
    case cvt::ScalarKind::f64:
    default: return run(double{});
  }
}

}  // namespace cvtcli
