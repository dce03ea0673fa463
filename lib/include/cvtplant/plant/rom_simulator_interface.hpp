#pragma once
// The size-erased simulator interface (docs/architecture.md#scene-dispatch).
//
// A plant's feature mask is a template argument (RomSimulator<T, F> carries
// only the states and code of its features), but a scene chooses its
// features at run time. IRomSimulator<T> is what a caller holds instead: the
// frame stepper of one scalar type T, whatever its features, as ETL's
// ivector<T> stands for every vector<T, N>. ErasedRomSimulator<T, F> is the
// one implementation; scene/plant_set.hpp builds the right one for a scene
// into storage the caller owns. No heap, no RTTI: virtual calls only, a
// protected non-virtual destructor (nothing is ever deleted through the
// interface) and trivially destructible implementations.
//
// Besides the frame stepper, the interface exposes the plant itself on a
// state vector the caller owns (derivative, Jacobian, one integrator step),
// which is what the analysis toolkit needs for Lyapunov spectra. Vectors are
// plain arrays of state_count() values in the plant's units (RomUnits);
// matrices are state_count() x state_count(), column-major (Eigen's order).
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#include "cvtplant/plant/rom_layout.hpp"
#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/plant/rom_step.hpp"

namespace cvt {

// Most states any plant has (every feature on).
inline constexpr int kRomMaxStates = rom_state_index(rom_feature::all).count;

template <class T>
class IRomSimulator {
 public:
  using Scalar = T;
  using Acc = RomAcc<T>;

  // --- the frame stepper (RomSimulator) ---
  virtual std::uint32_t features() const = 0;
  virtual int state_count() const = 0;
  virtual void reset(const RomInitial& x0, const RomInputs<T>& u0) = 0;
  virtual RomFault step_frame(const RomInputs<T>& u) = 0;
  virtual RomOutputs<T> outputs() const = 0;
  virtual const EnergyLedger<Acc>& energy() const = 0;
  virtual RomFault fault() const = 0;
  virtual long frames() const = 0;
  // The state in the plant's units; state_si() in SI (displacements in m).
  virtual void state(T* x) const = 0;
  virtual void state_si(double* x) const = 0;
  // Places the plant (tests, harnesses); the next frame starts from x.
  virtual void set_state(const T* x) = 0;
  // Wedging: the driven clamping command and force [N], and the frames taken
  // with the end stop's finer steps (docs/rom.md#driven-clamping, #end-stop).
  virtual void set_driven_clamp_command(double f_N) = 0;
  virtual double driven_clamp_N() const = 0;
  virtual long stop_refined_frames() const = 0;

  // --- the plant on a caller's state, with the inputs of set_inputs ---
  virtual void set_inputs(const RomInputs<T>& u) = 0;
  virtual void initial_state(const RomInitial& x0, T* x) const = 0;
  virtual void derivative(const T* x, T* dxdt) const = 0;
  virtual void jacobian(const T* x, T* J) const = 0;
  virtual RomOutputs<T> outputs_at(const T* x) const = 0;
  // One integrator step of h (plant time units) with method m, W with the
  // friction slope floor as the simulator's configuration says, then the
  // polygon phase wrapped (docs/rom.md#slope-floor, #polygon).
  virtual void advance(T* x, const T& h, Method m) const = 0;

 protected:
  IRomSimulator() = default;
  IRomSimulator(const IRomSimulator&) = default;
  IRomSimulator& operator=(const IRomSimulator&) = default;
  ~IRomSimulator() = default;
};

// RomSimulator<T, F> behind the interface. `final`, so a caller that holds
// the concrete type calls it directly.
template <class T, std::uint32_t F, std::uint32_t D = 0>
class ErasedRomSimulator final : public IRomSimulator<T> {
 public:
  using Sim = RomSimulator<T, F, D>;
  using Plant = typename Sim::Plant;
  using State = typename Plant::State;
  using Jacobian = typename Plant::Jacobian;
  using Acc = RomAcc<T>;
  static constexpr int kStates = Plant::kStates;

  // `features`: F and the bits of D the scene asks for.
  ErasedRomSimulator(const RomParams& p, const RomSimConfig& c, std::uint32_t features = F)
      : sim_(p, c, features), cfg_(c) {}

  std::uint32_t features() const override { return sim_.features(); }
  int state_count() const override { return kStates; }
  void reset(const RomInitial& x0, const RomInputs<T>& u0) override { sim_.reset(x0, u0); }
  RomFault step_frame(const RomInputs<T>& u) override { return sim_.step_frame(u); }
  RomOutputs<T> outputs() const override { return sim_.outputs(); }
  const EnergyLedger<Acc>& energy() const override { return sim_.energy(); }
  RomFault fault() const override { return sim_.fault(); }
  long frames() const override { return sim_.frames(); }
  void state(T* x) const override { map(x) = sim_.state(); }
  void state_si(double* x) const override {
    Eigen::Map<Eigen::Matrix<double, kStates, 1>> out(x);
    out = sim_.state_si();
  }
  void set_state(const T* x) override { sim_.mutable_state() = cmap(x); }
  void set_driven_clamp_command(double f_N) override { sim_.set_driven_clamp_command(f_N); }
  double driven_clamp_N() const override { return sim_.driven_clamp_N(); }
  long stop_refined_frames() const override { return sim_.stop_refined_frames(); }

  void set_inputs(const RomInputs<T>& u) override { sim_.mutable_plant().inputs = u; }
  void initial_state(const RomInitial& x0, T* x) const override { map(x) = sim_.plant().initial_state(x0); }
  void derivative(const T* x, T* dxdt) const override {
    const State xs = cmap(x);
    State d;
    sim_.plant().derivative(xs, d);
    map(dxdt) = d;
  }
  void jacobian(const T* x, T* J) const override {
    const State xs = cmap(x);
    Jacobian Jm;
    sim_.plant().jacobian(xs, Jm);
    Eigen::Map<Jacobian> out(J);
    out = Jm;
  }
  RomOutputs<T> outputs_at(const T* x) const override { return sim_.plant().outputs(State(cmap(x))); }
  void advance(T* x, const T& h, Method m) const override {
    State xs = cmap(x);
    rom_step(m, sim_.plant(), xs, h, cfg_.w_slope_floor);
    sim_.plant().wrap(xs);
    map(x) = xs;
  }

  // The concrete simulator, for callers that know F.
  Sim& concrete() { return sim_; }
  const Sim& concrete() const { return sim_; }

 private:
  static Eigen::Map<State> map(T* x) { return Eigen::Map<State>(x); }
  static Eigen::Map<const State> cmap(const T* x) { return Eigen::Map<const State>(x); }

  Sim sim_;
  RomSimConfig cfg_;
};

}  // namespace cvt
