#pragma once
// Vector and sparse-matrix kernels for CVODE, compiled with the project's
// flags (docs/mbd.md#speed). Debian 12's libsundials is built without
// optimisation (its serial N_VLinearSum runs ~20 instructions per element),
// and those kernels took half of a run's time. The serial vector keeps its
// data layout; only the function pointers of the hot operations change, and
// CVODE's clones inherit them.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_matrix.h>

namespace cvt::mbd::detail {

// Replaces the element-wise operations and reductions of a serial N_Vector
// (and so of every vector CVODE clones from it) with optimised loops, and
// enables the fused operations CVODE uses when present.
void install_fast_vector_kernels(N_Vector v);

// Replaces zero, copy and scale-add-identity of a CSC sparse SUNMatrix with
// loops that keep the structure (every column's diagonal is in the pattern);
// anything else falls back to SUNDIALS' own implementation.
void install_fast_matrix_kernels(SUNMatrix A);

}  // namespace cvt::mbd::detail
