#pragma once
// The plant's signals: one list of names, units and descriptions for every
// quantity a frame reports (docs/rom.md#outputs). The CSV writer, the
// validation tables, the analysis toolkit's signal choice, the reference's
// stepping interface and the FMU's variables all read this list, so a signal
// is named and described in one place.
#include <cstdint>

#include "cvtplant/plant/rom_energy.hpp"
#include "cvtplant/plant/rom_outputs.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

// Output groups logged besides the base signals (docs/rom.md#outputs).
namespace rom_log {
inline constexpr std::uint32_t base = 0;            // always: omega1, omega2, F_ax, slip
inline constexpr std::uint32_t torques = 1u << 0;   // tau_in, tau_load, torque_transmitted
inline constexpr std::uint32_t friction = 1u << 1;  // F1, F2, v_rel1, v_rel2, stick1, stick2
inline constexpr std::uint32_t ratios = 1u << 2;    // speed_ratio, geometric_ratio, r1, r2
inline constexpr std::uint32_t energy = 1u << 3;    // ledger and residual
inline constexpr std::uint32_t states = 1u << 4;    // raw state vector (rom_state_name)
inline constexpr std::uint32_t tension = 1u << 5;   // T_t, T_s, T_c, creep strain, sheave on its stop (feature tension)
inline constexpr std::uint32_t all = torques | friction | ratios | energy | states | tension;
// The wedging plant's driven clamping, radial friction and ratio end stops:
// read by the FMU (docs/fmu.md#variables); no scene log writes them, so the
// CSV's columns stay as they are.
inline constexpr std::uint32_t radial = 1u << 6;
}  // namespace rom_log

enum class RomSignal : std::uint8_t {
  omega1, omega2, clamp_force, slip,
  tau_in, tau_load, torque_transmitted,
  friction1, friction2, v_rel1, v_rel2, stick1, stick2,
  speed_ratio, geometric_ratio, radius1, radius2,
  energy_stored, work_input, work_actuator, work_load, work_friction, work_damping, energy_residual,
  tension_tight, tension_slack, tension_centrifugal, creep_strain, sheave_on_stop,
  driven_clamp_force, radial_friction1, radial_friction2, stop_underdrive, stop_overdrive,
  count
};

enum class RomSignalKind : std::uint8_t { real, flag };

struct RomSignalInfo {
  RomSignal id;
  const char* name;         // CSV column and table name
  const char* unit;         // SI unit; "1" for a dimensionless quantity or flag
  std::uint32_t log;        // the rom_log group that writes it (base: always)
  RomSignalKind kind;
  const char* description;
};

// In CSV column order: a group's signals are contiguous and the groups come
// in the order of their bits (states, which are not outputs, between energy
// and tension).
inline constexpr RomSignalInfo kRomSignals[] = {
    {RomSignal::omega1, "omega1", "rad/s", rom_log::base, RomSignalKind::real, "driver pulley speed"},
    {RomSignal::omega2, "omega2", "rad/s", rom_log::base, RomSignalKind::real, "driven pulley speed"},
    {RomSignal::clamp_force, "F_ax", "N", rom_log::base, RomSignalKind::real,
     "axial force pressing the driver wrap's lumps (with the link-passing ripple where modelled)"},
    {RomSignal::slip, "slip", "1", rom_log::base, RomSignalKind::real,
     "driver slip (v1 - v_chain) / v1 (0 while |v1| < 1e-3 m/s)"},
    {RomSignal::tau_in, "tau_in", "N.m", rom_log::torques, RomSignalKind::real,
     "input torque on the driver pulley as applied (a held pulley reports its holding torque)"},
    {RomSignal::tau_load, "tau_load", "N.m", rom_log::torques, RomSignalKind::real,
     "load torque on the driven pulley as applied (road load included)"},
    {RomSignal::torque_transmitted, "torque_transmitted", "N.m", rom_log::torques, RomSignalKind::real,
     "friction torque the chain exerts on the driver pulley"},
    {RomSignal::friction1, "F1", "N", rom_log::friction, RomSignalKind::real, "tangential friction on the entry lump"},
    {RomSignal::friction2, "F2", "N", rom_log::friction, RomSignalKind::real, "tangential friction on the exit lump"},
    {RomSignal::v_rel1, "v_rel1", "m/s", rom_log::friction, RomSignalKind::real, "sliding speed of the entry lump"},
    {RomSignal::v_rel2, "v_rel2", "m/s", rom_log::friction, RomSignalKind::real, "sliding speed of the exit lump"},
    {RomSignal::stick1, "stick1", "1", rom_log::friction, RomSignalKind::flag, "entry lump sticks (1) or slides (0)"},
    {RomSignal::stick2, "stick2", "1", rom_log::friction, RomSignalKind::flag, "exit lump sticks (1) or slides (0)"},
    {RomSignal::speed_ratio, "speed_ratio", "1", rom_log::ratios, RomSignalKind::real,
     "speed ratio omega1 / omega2 (0 while |omega2| < 1e-3 rad/s)"},
    {RomSignal::geometric_ratio, "geometric_ratio", "1", rom_log::ratios, RomSignalKind::real,
     "geometric ratio r2 / r1"},
    {RomSignal::radius1, "r1", "m", rom_log::ratios, RomSignalKind::real, "running (pitch) radius on the driver"},
    {RomSignal::radius2, "r2", "m", rom_log::ratios, RomSignalKind::real, "running (pitch) radius on the driven"},
    {RomSignal::energy_stored, "E_stored", "J", rom_log::energy, RomSignalKind::real,
     "kinetic and elastic energy stored in the plant"},
    {RomSignal::work_input, "W_in", "J", rom_log::energy, RomSignalKind::real, "work of the input torque since start"},
    {RomSignal::work_actuator, "W_actuator", "J", rom_log::energy, RomSignalKind::real,
     "work of the clamping actuators since start"},
    {RomSignal::work_load, "W_load", "J", rom_log::energy, RomSignalKind::real, "work taken by the load since start"},
    {RomSignal::work_friction, "W_friction", "J", rom_log::energy, RomSignalKind::real,
     "energy dissipated by friction since start"},
    {RomSignal::work_damping, "W_damping", "J", rom_log::energy, RomSignalKind::real,
     "energy dissipated by damping since start"},
    {RomSignal::energy_residual, "E_residual", "J", rom_log::energy, RomSignalKind::real,
     "energy-ledger residual: stored change minus net work (0 for the exact solution)"},
    {RomSignal::tension_tight, "T_tight", "N", rom_log::tension, RomSignalKind::real, "tight-strand tension"},
    {RomSignal::tension_slack, "T_slack", "N", rom_log::tension, RomSignalKind::real, "slack-strand tension"},
    {RomSignal::tension_centrifugal, "T_centrifugal", "N", rom_log::tension, RomSignalKind::real,
     "centrifugal tension m' v^2 of the chain"},
    {RomSignal::creep_strain, "creep_strain", "1", rom_log::tension, RomSignalKind::real,
     "strain difference across the driver wrap that makes the creep"},
    {RomSignal::sheave_on_stop, "sheave_on_stop", "1", rom_log::tension, RomSignalKind::flag,
     "driver sheave on its stop or fixed (1)"},
    {RomSignal::driven_clamp_force, "F_ax2", "N", rom_log::radial, RomSignalKind::real,
     "driven clamping force F_ax2 as the driven actuator applies it"},
    {RomSignal::radial_friction1, "Fr1", "N", rom_log::radial, RomSignalKind::real,
     "radial friction along the flank on the entry lump (seed Eq. 7)"},
    {RomSignal::radial_friction2, "Fr2", "N", rom_log::radial, RomSignalKind::real,
     "radial friction along the flank on the exit lump (seed Eq. 7)"},
    {RomSignal::stop_underdrive, "stop_underdrive", "1", rom_log::radial, RomSignalKind::flag,
     "chain pressed into the ratio end stop at the driver's smallest radius (1)"},
    {RomSignal::stop_overdrive, "stop_overdrive", "1", rom_log::radial, RomSignalKind::flag,
     "chain pressed into the ratio end stop at the driver's largest radius (1)"},
};
inline constexpr int kRomSignalCount = static_cast<int>(sizeof(kRomSignals) / sizeof(kRomSignals[0]));
static_assert(kRomSignalCount == static_cast<int>(RomSignal::count), "one row per RomSignal");

constexpr const RomSignalInfo& rom_signal_info(RomSignal s) { return kRomSignals[static_cast<int>(s)]; }

namespace detail {
constexpr bool rom_signals_in_enum_order() {
  for (int i = 0; i < kRomSignalCount; ++i)
    if (static_cast<int>(kRomSignals[i].id) != i) return false;
  return true;
}
constexpr bool rom_signal_names_equal(const char* a, const char* b) {
  while (*a != '\0' && *a == *b) {
    ++a;
    ++b;
  }
  return *a == *b;
}
}  // namespace detail
static_assert(detail::rom_signals_in_enum_order(), "kRomSignals is indexed by RomSignal");

// The signal of a name, or RomSignal::count.
constexpr RomSignal rom_signal_by_name(const char* name) {
  for (const auto& s : kRomSignals)
    if (detail::rom_signal_names_equal(s.name, name)) return s.id;
  return RomSignal::count;
}

// The value of signal `s` in a frame's outputs and energy ledger, in SI
// units whatever the scalar; a flag reads 1 or 0.
template <class T, class A>
double rom_signal(const RomOutputs<T>& out, const EnergyLedger<A>& e, RomSignal s) {
  const auto flag = [](bool b) { return b ? 1.0 : 0.0; };
  const RomOutputs<T>& o = out;
  switch (s) {
    case RomSignal::omega1: return to_double(o.omega1_rad_s);
    case RomSignal::omega2: return to_double(o.omega2_rad_s);
    case RomSignal::clamp_force: return to_double(o.clamp_force_N);
    case RomSignal::slip: return to_double(o.slip);
    case RomSignal::tau_in: return to_double(o.tau_in_Nm);
    case RomSignal::tau_load: return to_double(o.tau_load_Nm);
    case RomSignal::torque_transmitted: return to_double(o.torque_transmitted_Nm);
    case RomSignal::friction1: return to_double(o.friction1_N);
    case RomSignal::friction2: return to_double(o.friction2_N);
    case RomSignal::v_rel1: return to_double(o.v_rel1_m_s);
    case RomSignal::v_rel2: return to_double(o.v_rel2_m_s);
    case RomSignal::stick1: return flag(o.stick1);
    case RomSignal::stick2: return flag(o.stick2);
    case RomSignal::speed_ratio: return to_double(o.speed_ratio);
    case RomSignal::geometric_ratio: return to_double(o.geometric_ratio);
    case RomSignal::radius1: return to_double(o.radius1_m);
    case RomSignal::radius2: return to_double(o.radius2_m);
    case RomSignal::energy_stored: return double(e.stored_J);
    case RomSignal::work_input: return double(e.input_J);
    case RomSignal::work_actuator: return double(e.actuator_J);
    case RomSignal::work_load: return double(e.load_J);
    case RomSignal::work_friction: return double(e.friction_loss_J);
    case RomSignal::work_damping: return double(e.damping_loss_J);
    case RomSignal::energy_residual: return double(e.residual_J());
    case RomSignal::tension_tight: return to_double(o.tension_tight_N);
    case RomSignal::tension_slack: return to_double(o.tension_slack_N);
    case RomSignal::tension_centrifugal: return to_double(o.centrifugal_tension_N);
    case RomSignal::creep_strain: return to_double(o.creep_strain);
    case RomSignal::sheave_on_stop: return flag(o.sheave_on_stop);
    case RomSignal::driven_clamp_force: return to_double(o.driven_clamp_force_N);
    case RomSignal::radial_friction1: return to_double(o.radial_friction1_N);
    case RomSignal::radial_friction2: return to_double(o.radial_friction2_N);
    case RomSignal::stop_underdrive: return flag(o.stop_underdrive);
    case RomSignal::stop_overdrive: return flag(o.stop_overdrive);
    case RomSignal::count: break;
  }
  return 0.0;
}

}  // namespace cvt
