// Explicit instantiations that make the core archive compile its templates
// with the build's own flags: the seed oscillator with every method in every
// scalar type, and the real-time plant's frame stepper in the two embedded
// types with the widest feature set each has (every feature in float; all
// but wedging in q16.16). The embedded no-heap link check (tests/target,
// whole archive) then sees the code of every feature; a firmware image still
// compiles only the plants it names. Double plants run on hosts, where the
// host tools compile all of them (lib/src/all_plants_*.cpp).
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
#include "cvtplant/plant/rom_sim.hpp"
#include "cvtplant/scalar/fixed_eigen.hpp"
#include "cvtplant/scalar/scalar.hpp"

namespace cvt {

template class StickSlipOscillator<double>;
template class StickSlipOscillator<float>;
template class StickSlipOscillator<q16_16>;

template void step<StickSlipOscillator<double>>(Method, const StickSlipOscillator<double>&,
                                                StateOf<StickSlipOscillator<double>>&, double);
template void step<StickSlipOscillator<float>>(Method, const StickSlipOscillator<float>&,
                                               StateOf<StickSlipOscillator<float>>&, float);
template void step<StickSlipOscillator<q16_16>>(Method, const StickSlipOscillator<q16_16>&,
                                                StateOf<StickSlipOscillator<q16_16>>&, q16_16);

template class RomSimulator<float, rom_feature::known>;
template class RomSimulator<q16_16, rom_feature::basic | rom_feature::tension>;

}  // namespace cvt
