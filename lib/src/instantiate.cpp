// Explicit instantiations of the core for every scalar type, so that a build of
// this archive (host or Cortex-M) compiles all of it with the embedded flags
// and the no-heap link check of the target image sees every code path.
#include "cvtplant/integrate/method.hpp"
#include "cvtplant/plant/oscillator.hpp"
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

}  // namespace cvt
