// One scene of `cvtplant validate` (docs/validation.md#method).
#include "cvtplant/validation/scene_check.hpp"

#include <algorithm>

#include "cvtplant/validation/plant.hpp"

namespace cvt::validation {

double run_length_s(const cvt::Scene& s, const RunSettings& st) {
  return st.t_end_s > 0 ? std::min(st.t_end_s, s.t_end_s) : s.t_end_s;
}

std::optional<ReferenceSetup> reference_setup(const cvt::Scene& s, const RunSettings& st, std::string& why_not) {
  auto params = reference_params(s, st.sheaves, st.set, why_not);
  if (!params) return std::nullopt;
  ReferenceSetup out{std::move(*params), {}};
  out.run.t_end_s = run_length_s(s, st);
  out.run.rtol = st.rtol;
  out.run.sample_s = s.frame_s;
  out.run.max_steps = st.max_steps;
  out.run.settle_rtol = settle_rtol(st.set);
  return out;
}

SceneResult check_scene(const std::string& name, const cvt::Scene& scene, const cvt::Scene& plant_scene,
                        const RunSettings& st, const cvt::mbd::ProgressSink& on_progress) {
  SceneResult r;
  r.name = name;
  const auto setup = reference_setup(scene, st, r.skipped);
  if (!setup) return r;
  r.t_end_s = setup->run.t_end_s;
  cvt::Scene plant = plant_scene;
  plant.t_end_s = r.t_end_s;
  r.ref = reference_run(setup->params, setup->run, st.cache_dir, on_progress);
  r.plant = plant_run(plant, plant.frame_s);
  // A reference that stopped early is compared up to there.
  r.cmp = compare(r.plant, r.ref.series, std::min(r.plant.size(), r.ref.series.size()));
  r.clamped = setup->params.sheaves == cvt::mbd::SheaveMode::clamped;
  if (r.clamped)
    for (int j = 0; j < 2; ++j) r.stop_s[j] = first_at_stop_s(r.ref, j, setup->params.sheave_stop_m);
  return r;
}

}  // namespace cvt::validation
