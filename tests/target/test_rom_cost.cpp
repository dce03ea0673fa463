// Cost of one 1 ms frame of the reduced-order plant on the Cortex-M4F, in
// float (the M4F's hardware type), for every row of the cost table
// (bench/cost_cases.hpp; docs/rom.md#cost). Prints
//     ICOUNT rom_frame float <label> <instructions>
// which bench/rom-cost-table.sh collects. A frame is RomSimulator::step_frame:
// the scene's substeps of ROS2 (Jacobian, LU, two right-hand sides each), the
// friction evaluation shared by them and the energy ledger, and the watchdog.
#include "cvtplant/plant/rom_step.hpp"
#include "cvtplant/port/icount.hpp"
#include "cost_cases.hpp"
#include "harness.hpp"

using namespace cvt;
using cvt::port::console;

namespace {

// The real-time goal of the default scene (seed-case1 at the real-time
// default, one ROS2 step per frame, with the energy ledger and the
// watchdog): 2,500 instructions per frame (docs/rom.md#cost says where they
// go). Instruction counts under icount are exact for a given compiler, so
// the goal is asserted; it is 3 % above what the frame takes now (2,427 on
// this image, Debian's arm-none-eabi-gcc 12.2, -O2), about what the code
// around the measured call moves it by (inlining: tens of instructions).
constexpr std::uint32_t kGoalDefaultScene = 2500;
// Without the energy ledger (the scene's choice, docs/rom.md#cost): 2,057
// here, bound 4 % above; in linearly implicit Euler 1,358.
constexpr std::uint32_t kBoundNoLedgerScene = 2140;
// The variable-ratio (wedging) plant's goal, off the end stops and on them.
constexpr std::uint32_t kGoalVariableRatio = 10000;
// Every feature of the variable-ratio plant at once (axial, driven clamping,
// wedging, tension, road load; docs/rom.md#tension-radial) off the end stops.
constexpr std::uint32_t kGoalFullComposition = 5000;

// Instructions of one frame of row c in scalar T, printed as an ICOUNT line.
template <class T, std::uint32_t F>
std::uint32_t frame_icount(const rom_cost::Case& c, const char* scalar, std::uint32_t reps) {
  rom_cost::Frame<T, F> fr(c);
  CHECK(fr.sim.fault() == RomFault::none);
  const RomSimulator<T, F> start = fr.sim;
  RomSimulator<T, F>& sim = fr.sim;
  const RomInputs<T> u = fr.next;
  RomFault fault = RomFault::none;
  // The copy restores the same start state for every call; it is measured
  // on its own and taken off.
  auto frame = [&] {
    sim = start;
    fault = sim.step_frame(u);
  };
  auto copy_only = [&] { sim = start; };
  const std::uint32_t with_frame = cvt::port::icount_per_call(frame, reps);
  const std::uint32_t copy = cvt::port::icount_per_call(copy_only, reps);
  const std::uint32_t n = with_frame > copy ? with_frame - copy : 0;
  // A faulted frame returns early and would be counted as cheap.
  CHECK(fault == RomFault::none);
  CHECK_GT(n, 0u);
  console() << "ICOUNT rom_frame " << scalar << ' ' << c.label << ' ' << n << '\n';
  return n;
}

struct CountFrames {
  std::uint32_t seed_case1 = 0;
  std::uint32_t core = 0, all_x4 = 0, core_x4 = 0, seed_case1_wedging = 0;
  std::uint32_t ratio_control = 0, on_stop = 0;
  std::uint32_t seed_case1_no_ledger = 0, seed_case1_lean = 0, ratio_control_no_ledger = 0;
  std::uint32_t seed_case1_tension = 0, seed_case1_axial_tension = 0;
  std::uint32_t ripple = 0, ripple_off = 0;
  std::uint32_t full = 0, full_no_ledger = 0, full_on_stop = 0, full_ripple = 0;

  template <std::uint32_t F>
  void visit(const rom_cost::Case& c) {
    const std::uint32_t n = frame_icount<float, F>(c, "float", 200);
    if (str_is(c.label, "scene/seed-case1")) seed_case1 = n;
    if (str_is(c.label, "feature/core")) core = n;
    if (str_is(c.label, "feature/core-x4")) core_x4 = n;
    if (str_is(c.label, "feature/all-but-wedging-x4")) all_x4 = n;
    if (str_is(c.label, "feature/seed-case1+wedging")) seed_case1_wedging = n;
    if (str_is(c.label, "scene/ratio-control")) ratio_control = n;
    if (str_is(c.label, "scene/clamp-step+wedging-on-stop")) on_stop = n;
    if (str_is(c.label, "scene/seed-case1/no-ledger")) seed_case1_no_ledger = n;
    if (str_is(c.label, "scene/seed-case1/no-ledger/lin-impl-euler")) seed_case1_lean = n;
    if (str_is(c.label, "scene/ratio-control/no-ledger")) ratio_control_no_ledger = n;
    if (str_is(c.label, "scene/seed-case1-tension")) seed_case1_tension = n;
    if (str_is(c.label, "feature/seed-case1+tension")) seed_case1_axial_tension = n;
    if (str_is(c.label, "scene/seed-case1-ripple")) ripple = n;
    if (str_is(c.label, "scene/seed-case1-ripple/off")) ripple_off = n;
    if (str_is(c.label, "scene/ratio-control-tension")) full = n;
    if (str_is(c.label, "scene/ratio-control-tension/no-ledger")) full_no_ledger = n;
    if (str_is(c.label, "scene/clamp-step+wedging+tension-on-stop")) full_on_stop = n;
    if (str_is(c.label, "scene/ratio-control-tension/ripple-x4")) full_ripple = n;
  }

  static bool str_is(const char* a, const char* b) { return cvt::target::str_equal(a, b); }
};

}  // namespace

CVT_TARGET_TEST(rom_frame_instruction_counts_float) {
  CountFrames counts;
  rom_cost::for_each_case(counts);
  console() << "ICOUNT rom_frame_goal float scene/seed-case1 " << counts.seed_case1 << " goal " << kGoalDefaultScene
            << '\n';
  CHECK_LE(counts.seed_case1, kGoalDefaultScene);
  CHECK_LE(counts.seed_case1_no_ledger, kBoundNoLedgerScene);
  CHECK_LT(counts.seed_case1_lean, counts.seed_case1_no_ledger);
  // Four substeps cost more than twice one (the frame overhead is small), and
  // all features cost more than none: the counts measure the plant at all.
  CHECK_GT(counts.core_x4, 2 * counts.core);
  CHECK_GT(counts.all_x4, counts.core_x4);
  // Wedging adds two states, a vector friction and a 6x6 core (docs/rom.md#wedging).
  CHECK_GT(counts.seed_case1_wedging, counts.seed_case1);
  // The variable-ratio plant of ratio control over CAN (docs/rom.md#cost):
  // its goal is 10,000 instructions per frame, met by the analytic Jacobian,
  // the 6x6 block solve and the contact shared with the ledger (4,587 on the
  // M4F image with the production-like CVT's lumps, docs/rom.md#production-lumps;
  // 4,444 on the M7's with the seed chain's). The count is exact for one binary, but the
  // code around the measured call (this file's lambdas, inlining) moves it by
  // tens of instructions, so the band is 4 % above the M4F's count and 2 %
  // below the M7's: a change of the plant's work shows, a rebuild of this
  // file does not.
  CHECK_LE(counts.ratio_control, kGoalVariableRatio);
  CHECK_GT(counts.ratio_control, 4350u);
  CHECK_LT(counts.ratio_control, 4750u);
  // A frame on the end stop is taken in stop_substeps = 2 steps of one W
  // (docs/rom.md#end-stop): the second substep without a Jacobian and a
  // factorisation, 1.53 times a frame off the stop on this image (7,254).
  CHECK_LE(counts.on_stop, kGoalVariableRatio);
  CHECK_GT(counts.on_stop, 14u * counts.ratio_control / 10u);
  CHECK_LT(counts.on_stop, 17u * counts.ratio_control / 10u);
  // The scene's choices (docs/rom.md#cost): the ledger is about a seventh of
  // the frame, and linearly implicit Euler saves a solve and a right-hand side.
  CHECK_LT(counts.seed_case1_no_ledger, counts.seed_case1 - counts.seed_case1 / 20u);
  CHECK_LT(counts.ratio_control_no_ledger, counts.ratio_control - counts.ratio_control / 20u);
  // The chain's tension state (docs/rom.md#tension): the seed case on fixed
  // sheaves, the default scene's successor, 2,378 on this image (no actuator
  // states, so below seed-case1), within the same goal; with the clamping
  // actuator 2,770, 14 % over seed-case1 (one division, the creep and
  // axial-force chain rule), bound 4 % above.
  CHECK_LE(counts.seed_case1_tension, kGoalDefaultScene);
  CHECK_LE(counts.seed_case1_axial_tension, 2880u);
  CHECK_GT(counts.seed_case1_axial_tension, counts.seed_case1);
  // The link-passing ripple (docs/rom.md#link-ripple): a cosine and a sine
  // per contact evaluation over the same plant with the ripple off.
  CHECK_GT(counts.ripple, counts.ripple_off);
  // The full composition (docs/rom.md#tension-radial, #cost): 5,000 off the
  // end stops, 10,000 on them, with the energy ledger.
  console() << "ICOUNT rom_frame_goal float scene/ratio-control-tension " << counts.full << " goal "
            << kGoalFullComposition << '\n';
  CHECK_LE(counts.full, kGoalFullComposition);
  CHECK_GT(counts.full, counts.ratio_control);
  CHECK_LT(counts.full_no_ledger, counts.full);
  CHECK_LE(counts.full_on_stop, kGoalVariableRatio);
  CHECK_GT(counts.full_on_stop, counts.full);
  // The link ripple with its 4 substeps (docs/rom.md#link-ripple) is beyond
  // the goal by design: its cost is stated in docs/rom.md#cost.
  CHECK_GT(counts.full_ripple, counts.full);
}

// The default scene in q16.16, for FPU-less targets: every product is a
// 32x32->64-bit multiply and every division a call to __aeabi_ldivmod.
CVT_TARGET_TEST(rom_frame_instruction_count_fixed) {
  const std::uint32_t n =
      frame_icount<q16_16, rom_feature::axial>(rom_cost::Case{"scene/seed-case1", "seed-case1", 0}, "q16_16", 20);
  CHECK_GT(n, 10000u);
}

// Where a frame's instructions go (docs/rom.md#cost): the parts of one ROS2
// substep and of the energy ledger, seed-case1 after 1 s, float. Printed as
//     ICOUNT rom_part float <part> <instructions>
CVT_TARGET_TEST(rom_frame_breakdown_float) {
  constexpr std::uint32_t F = rom_feature::axial;
  using Plant = CvtRom<float, F>;
  rom_cost::Frame<float, F> fr(rom_cost::Case{"scene/seed-case1", "seed-case1", 0});
  const Plant& plant = fr.sim.plant();
  const Plant::State x = fr.sim.state();
  const float h = fr.sim.substep();
  const float a = 1.70710678118654752440f * h;
  Plant::State f;
  Plant::Jacobian J;
  RomWSolver<float, F> w;
  Plant::Contact c = plant.contact(x);
  plant.jacobian(x, c, J, true);
  plant.derivative(x, f);
  w.factor(J, a);
  volatile float sink = 0;
  auto contact = [&] {
    c = plant.contact(x);
    sink = c.lump1.phi;
  };
  auto jacobian = [&] {
    plant.jacobian_entries(x, c, J, true);
    sink = J(3, 3);
  };
  auto derivative_shared = [&] {
    plant.derivative(x, c, f);
    sink = f(3);
  };
  auto derivative = [&] {
    plant.derivative(x, f);
    sink = f(3);
  };
  auto factor = [&] {
    w.factor(J, a);
    sink = a;
  };
  auto solve = [&] { sink = w.solve(f)(3); };
  // Every term, so that none is left out as unused.
  auto power = [&] {
    const RomPower<float> p = plant.power(x, c);
    sink = p.input_W + p.actuator_W + p.load_W + p.friction_loss_W + p.damping_loss_W;
  };
  auto substep = [&] {
    Plant::State y = x;
    rom_step_implicit(Method::ros2, plant, y, h, c, true);
    sink = y(3);
  };
  auto dense_substep = [&] {
    Plant::State y = x;
    step(Method::ros2, plant, y, h);
    sink = y(3);
  };
  struct Part {
    const char* name;
    std::uint32_t n;
  };
  const Part parts[] = {
      {"contact", cvt::port::icount_per_call(contact, 200)},
      {"jacobian", cvt::port::icount_per_call(jacobian, 200)},
      {"w_factor", cvt::port::icount_per_call(factor, 200)},
      {"w_solve", cvt::port::icount_per_call(solve, 200)},
      {"derivative_shared", cvt::port::icount_per_call(derivative_shared, 200)},
      {"derivative", cvt::port::icount_per_call(derivative, 200)},
      {"ledger_power", cvt::port::icount_per_call(power, 200)},
      {"ros2_substep", cvt::port::icount_per_call(substep, 200)},
      {"ros2_substep_dense_lu", cvt::port::icount_per_call(dense_substep, 200)},
  };
  for (const Part& p : parts) console() << "ICOUNT rom_part float " << p.name << ' ' << p.n << '\n';
  // A ROS2 substep from an evaluated contact is one Jacobian, one
  // factorisation, two solves, the right-hand side at x from the contact and
  // a full one at the stage point, plus the vector updates.
  const std::uint32_t sum = parts[1].n + parts[2].n + 2 * parts[3].n + parts[4].n + parts[5].n;
  CHECK_GE(parts[7].n, sum);
  CHECK_LE(parts[7].n, sum + 600u);
  // Sharing the friction evaluation is what makes the shared right-hand side cheap.
  CHECK_LT(parts[4].n, parts[5].n);
  // The block elimination is what keeps the axial plant affordable.
  CHECK_LT(parts[7].n, parts[8].n);
}

// Where a variable-ratio frame's instructions go (docs/rom.md#cost): the
// plant of ratio control over CAN after 1 s, float. Printed as
//     ICOUNT rom_part_wedging float <part> <instructions>
CVT_TARGET_TEST(rom_frame_breakdown_wedging_float) {
  constexpr std::uint32_t F = rom_feature::axial | rom_feature::road_load | rom_feature::wedging;
  using Plant = CvtRom<float, F>;
  rom_cost::Frame<float, F> fr(rom_cost::Case{"scene/ratio-control", "ratio-control", 0});
  const Plant& plant = fr.sim.plant();
  const Plant::State x = fr.sim.state();
  const float h = fr.sim.substep();
  const float a = 1.70710678118654752440f * h;
  Plant::State f;
  Plant::Jacobian J;
  RomWSolver<float, F> w;
  Plant::Contact c = plant.contact(x);
  plant.jacobian(x, J);
  w.factor(J, a);
  volatile float sink = 0;
  auto contact = [&] {
    c = plant.contact(x);
    sink = c.lump1.F;
  };
  auto jacobian = [&] {
    plant.jacobian_entries(x, c, J, true);
    sink = J(3, 3);
  };
  auto factor = [&] {
    w.factor(J, a);
    sink = a;
  };
  auto solve = [&] { sink = w.solve(f)(3); };
  auto derivative_shared = [&] {
    plant.derivative(x, c, f);
    sink = f(3);
  };
  auto derivative = [&] {
    plant.derivative(x, f);
    sink = f(3);
  };
  // Every term, so that none is left out as unused.
  auto power = [&] {
    const RomPower<float> p = plant.power(x, c);
    sink = p.input_W + p.actuator_W + p.load_W + p.friction_loss_W + p.damping_loss_W;
  };
  auto jacobian_duals = [&] {
    jacobian_by_duals(plant, x, J);
    sink = J(3, 3);
  };
  auto substep = [&] {
    Plant::State y = x;
    rom_step_implicit(Method::ros2, plant, y, h, c, true);
    sink = y(3);
  };
  struct Part {
    const char* name;
    std::uint32_t n;
  };
  const Part parts[] = {
      {"contact", cvt::port::icount_per_call(contact, 50)},
      {"jacobian", cvt::port::icount_per_call(jacobian, 50)},
      {"w_factor", cvt::port::icount_per_call(factor, 50)},
      {"w_solve", cvt::port::icount_per_call(solve, 50)},
      {"derivative_shared", cvt::port::icount_per_call(derivative_shared, 50)},
      {"derivative", cvt::port::icount_per_call(derivative, 50)},
      {"ledger_power", cvt::port::icount_per_call(power, 50)},
      {"ros2_substep", cvt::port::icount_per_call(substep, 50)},
      {"jacobian_duals", cvt::port::icount_per_call(jacobian_duals, 50)},
  };
  for (const Part& p : parts) console() << "ICOUNT rom_part_wedging float " << p.name << ' ' << p.n << '\n';
  // A substep from an evaluated contact is one Jacobian, one factorisation,
  // two solves and two right-hand sides, plus the vector updates.
  const std::uint32_t sum = parts[1].n + parts[2].n + 2 * parts[3].n + parts[4].n + parts[5].n;
  CHECK_GE(parts[7].n, sum);
  CHECK_LE(parts[7].n, sum + 800u);
  // The analytic Jacobian is what makes the variable-ratio plant affordable
  // (against the 11-wide dual numbers, which evaluate the contact too).
  CHECK_LT(4 * (parts[0].n + parts[1].n), parts[8].n);
}
