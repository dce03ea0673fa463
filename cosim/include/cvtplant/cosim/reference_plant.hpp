#pragma once
// The multibody reference as the plant behind the SIL bridge
// (docs/sil.md#reference-plant): the members cvt::sil::BasicBridge asks of
// its plant, on cvt::mbd::Stepper. A scene becomes the reference's inputs
// through the validation module's mapping (cvt::validation::reference_params,
// the one the open-loop comparison uses); the clamping commands reach the
// sheaves through the real-time plant's actuators (the scene's lag and
// saturation); the reference's outputs go on the bus in the real-time plant's
// signals. A fault of the reference (ledger, torn chain, runaway, step cap,
// solver, an impossible state, a refused input) is the plant's fault state
// and PlantDiag.plant_fault. Host only: heap, exceptions and SUNDIALS.
#include <cstdint>
#include <memory>
#include <string>

#include "cvtplant/can/messages.hpp"
#include "cvtplant/mbd/stepper.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/plant/rom_params.hpp"
#include "cvtplant/scene/scene.hpp"
#include "cvtplant/sil/scene_plant.hpp"

namespace cvt::cosim {

// A test hook (docs/sil.md#plant-faults): the reference reports `kind` at the
// first frame that ends at or after `at_s`, as if it had failed there.
struct InjectedFault {
  cvt::mbd::StepFault kind = cvt::mbd::StepFault::none;
  double at_s = 0;
};

struct ReferenceOptions {
  cvt::mbd::StepperOptions stepper;  // tolerance, ledger bound, step cap per frame
  // Where release states are kept between processes ("": in this process
  // only). The start-up (settle, spin-up, hold: seconds of CPU) runs once
  // per scene and parameter set.
  std::string release_cache_dir;
  InjectedFault inject;
  // Frames the real-time check steps (docs/sil.md#reference-realtime).
  int probe_frames = 200;
};

// PlantDiag.plant_fault for the reference's fault kinds.
cvt::can::PlantFault plant_fault_code(cvt::mbd::StepFault f);

// "ledger" -> StepFault::ledger (the names of cvt::mbd::step_fault_name);
// throws std::invalid_argument for another name.
cvt::mbd::StepFault step_fault_by_name(const std::string& name);

class ReferencePlant {
 public:
  explicit ReferencePlant(ReferenceOptions o = {});
  ~ReferencePlant();
  ReferencePlant(const ReferencePlant&) = delete;
  ReferencePlant& operator=(const ReferencePlant&) = delete;

  // The scene's reference inputs (cvt::validation::reference_params, each
  // scene's own sheaves); false, the previous scene kept and the reason in
  // load_refusal(), for a scene the reference cannot run or whose frame is
  // not a whole number of microseconds.
  bool load(const cvt::Scene& s);
  // The scene's release state (from this process's or the disk's cache, else
  // the start-up), the actuators at the scene's clamping at t = 0.
  void reset();
  // One frame with the inputs held (the bridge's RomInputs: the driver's
  // clamping command, torques); the driven clamping is set_driven_clamp_command's.
  void step(const cvt::RomInputs<double>& u);

  cvt::RomOutputs<double> outputs() const;
  const cvt::mbd::StepOutputs& reference_outputs() const;
  bool faulted() const { return fault_ != cvt::mbd::StepFault::none; }
  cvt::can::PlantFault fault_code() const { return plant_fault_code(fault_); }
  const char* fault_detail() const { return cvt::mbd::step_fault_name(fault_); }
  const char* fault_message() const { return fault_message_.c_str(); }
  const char* load_refusal() const { return load_refusal_.c_str(); }
  long frames() const { return frames_; }
  std::int64_t frame_ns() const { return frame_ns_; }
  bool loaded() const { return scene_ != nullptr; }
  const cvt::Scene* scene() const { return scene_; }
  bool variable_ratio() const;

  // docs/sil.md#reference-published: the same formulas as the real-time
  // plant's, on the reference's friction, half angle, pitch line and stops.
  cvt::sil::PublishedParams published() const;
  // The driven pulley's axial force: the chain's bolt forces on it.
  double driven_axial_N() const;
  // A movable sheave on a ratio stop: the driver's closing stop or the
  // driven's opening stop is overdrive, the other two underdrive.
  cvt::sil::EndStops end_stops() const;
  void set_driven_clamp_command(double f_N) { driven_cmd_N_ = f_N; }
  double driven_clamp_N() const { return actuator_N_[1]; }  // the driven actuator's force
  double driver_clamp_N() const { return actuator_N_[0]; }
  long stop_refined_frames() const { return 0; }
  // Frames since reset() that ended with no bolt compressed in a wrap, so
  // that its running radius (and the ratio, the slip) was held.
  long lifted_frames() const { return lifted_frames_; }

  // Real time (docs/sil.md#reference-realtime): a probe of the scene's first
  // probe_frames frames from its release on another stepper; keeps time when
  // 99 % of them took at most half a frame of CPU. Measured once per scene.
  bool keeps_time();
  const char* realtime_refusal() const;

  // CPU seconds this thread spent in step() since reset(), and in the last
  // reset() (the start-up when the release state was not cached).
  double step_cpu_s() const { return step_cpu_s_; }
  double reset_cpu_s() const { return reset_cpu_s_; }
  bool release_from_cache() const { return release_from_cache_; }
  const ReferenceOptions& options() const { return opt_; }

 private:
  struct Loaded;
  void fail(cvt::mbd::StepFault f, const std::string& what);
  // The options a stepper of the loaded scene runs with: the caller's, at
  // the scene's frame and its parameter set's start-up tolerance.
  cvt::mbd::StepperOptions stepper_options() const;
  // Keeps each wrap's running radius where it is defined; false when a wrap
  // has none this frame.
  bool hold_radii();

  ReferenceOptions opt_;
  const cvt::Scene* scene_ = nullptr;
  std::unique_ptr<Loaded> cur_;
  std::unique_ptr<cvt::mbd::Stepper> stepper_;
  std::int64_t frame_ns_ = 1000000;
  long frames_ = 0;
  double actuator_N_[2] = {0, 0};
  double driven_cmd_N_ = 0;
  // The running radii last defined (docs/sil.md#reference-outputs): a wrap
  // with no bolt compressed has none, the bus carries the last one.
  double held_radius_m_[2] = {0, 0};
  long lifted_frames_ = 0;
  cvt::mbd::StepFault fault_ = cvt::mbd::StepFault::none;
  std::string fault_message_, load_refusal_;
  double step_cpu_s_ = 0, reset_cpu_s_ = 0;
  bool release_from_cache_ = false;
};

}  // namespace cvt::cosim
