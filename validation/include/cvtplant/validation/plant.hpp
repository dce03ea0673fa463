#pragma once
// The real-time plant on the validation's sample grid (docs/validation.md#method).
#include <functional>
#include <vector>

#include "cvtplant/scene/scene.hpp"
#include "cvtplant/validation/series.hpp"

namespace cvt::validation {

// The plant in double through the scene dispatch, every frame whose time is
// a multiple of sample_s. Throws InputError if the scene does not load,
// RunError naming the time and the fault if the plant faults.
Series plant_run(const cvt::Scene& s, double sample_s);

// The inputs of one frame of a plant a caller drives (a measured log,
// docs/validation.md#measured-csv): held over the frame that starts at the
// time they are asked for. clamp2_N is the driven clamping command (NaN:
// the scene's set-up value RomParams::driven_clamp_N).
struct FrameInputs {
  double tau_in_Nm = 0, tau_load_Nm = 0, clamp1_N = 0, clamp2_N = 0;
};

// The plant of scene s (its features, parameters and initial state; its
// input profiles unused) driven for `frames` frames by drive(t_s), sampled
// after each frame and at t = 0: every one, or those whose keep[i] is
// non-zero (keep: frames + 1 entries; a long log keeps only the frames
// around its rows). Throws as plant_run.
Series plant_run_driven(const cvt::Scene& s, long frames, const std::function<FrameInputs(double t_s)>& drive,
                        const std::vector<char>* keep = nullptr);

}  // namespace cvt::validation
