#pragma once
// What `lyapunov`, `analyze trajectory` and `analyze sweep` accept as a
// scene (docs/cli.md#lyapunov): a model of the analysis toolkit (lorenz,
// rossler, the seed oscillators, henon, logistic, seed-case1/2), else a plant
// scene, built-in or a TOML file, with constant inputs.
#include <memory>
#include <string>

#include "cvtplant/analysis/systems.hpp"

namespace cvtcli {

// Throws UsageError naming what was tried.
std::shared_ptr<const cvt::analysis::Model> resolve_model(const std::string& name_or_path);

}  // namespace cvtcli
