// docs/mbd.md#speed: the same arithmetic as SUNDIALS' serial kernels, in the
// same order, compiled with optimisation.
#include "sundials_kernels.hpp"

#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>

namespace cvt::mbd::detail {

namespace {

inline sunindextype len(N_Vector v) { return NV_LENGTH_S(v); }
inline double* data(N_Vector v) { return NV_DATA_S(v); }

void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
}
void constant(double c, N_Vector z) {
  std::fill(data(z), data(z) + len(z), c);
}
void prod(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] * yd[i];
}
void div(N_Vector x, N_Vector y, N_Vector z) {
  const sunindextype n = len(x);
  const double *xd = data(x), *yd = data(y);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] / yd[i];
}
void scale(double c, N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
}
void absolute(N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = std::fabs(xd[i]);
}
void inverse(N_Vector x, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = 1.0 / xd[i];
}
void add_const(N_Vector x, double b, N_Vector z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + b;
}
double wsqrsum(N_Vector x, N_Vector w) {
  const sunindextype n = len(x);
  const double *xd = data(x), *wd = data(w);
  double sum = 0;
  for (sunindextype i = 0; i < n; ++i) {
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}
double wrms_norm(N_Vector x, N_Vector w) { return std::sqrt(wsqrsum(x, w) / static_cast<double>(len(x))); }
double max_norm(N_Vector x) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  double m = 0;
  for (sunindextype i = 0; i < n; ++i) m = std::max(m, std::fabs(xd[i]));
  return m;
}
int linear_combination(int nv, double* c, N_Vector* X, N_Vector z) {
  const sunindextype n = len(z);
  double* zd = data(z);
  for (sunindextype i = 0; i < n; ++i) {
    double s = c[0] * data(X[0])[i];
    for (int j = 1; j < nv; ++j) s += c[j] * data(X[j])[i];
    zd[i] = s;
  }
  return 0;
}
int scale_add_multi(int nv, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const sunindextype n = len(x);
  const double* xd = data(x);
  for (int j = 0; j < nv; ++j) {
    const double* yd = data(Y[j]);
    double* zd = data(Z[j]);
    for (sunindextype i = 0; i < n; ++i) zd[i] = a[j] * xd[i] + yd[i];
  }
  return 0;
}

// Original matrix operations, for the cases the fast ones do not cover.
int (*g_zero)(SUNMatrix) = nullptr;
int (*g_copy)(SUNMatrix, SUNMatrix) = nullptr;
int (*g_scaleaddi)(double, SUNMatrix) = nullptr;
SUNMatrix (*g_clone)(SUNMatrix) = nullptr;

int mat_zero(SUNMatrix A) {
  // Values only: the pattern is rewritten by the Jacobian routine anyway.
  std::fill(SM_DATA_S(A), SM_DATA_S(A) + SM_NNZ_S(A), 0.0);
  return 0;
}
int mat_copy(SUNMatrix A, SUNMatrix B) {
  const sunindextype n = SM_COLUMNS_S(A);
  const sunindextype nnz = SM_INDEXPTRS_S(A)[n];
  if (SM_NNZ_S(B) < nnz || SM_COLUMNS_S(B) != n) return g_copy(A, B);
  std::copy(SM_INDEXPTRS_S(A), SM_INDEXPTRS_S(A) + n + 1, SM_INDEXPTRS_S(B));
  std::copy(SM_INDEXVALS_S(A), SM_INDEXVALS_S(A) + nnz, SM_INDEXVALS_S(B));
  std::copy(SM_DATA_S(A), SM_DATA_S(A) + nnz, SM_DATA_S(B));
  return 0;
}
int mat_scale_add_identity(double c, SUNMatrix A) {
  const sunindextype n = SM_COLUMNS_S(A);
  const sunindextype* ptr = SM_INDEXPTRS_S(A);
  const sunindextype* row = SM_INDEXVALS_S(A);
  double* v = SM_DATA_S(A);
  // Every column must hold its diagonal; otherwise SUNDIALS' version grows the matrix.
  for (sunindextype j = 0; j < n; ++j) {
    bool diag = false;
    for (sunindextype k = ptr[j]; k < ptr[j + 1]; ++k) diag = diag || row[k] == j;
    if (!diag) return g_scaleaddi(c, A);
  }
  for (sunindextype j = 0; j < n; ++j)
    for (sunindextype k = ptr[j]; k < ptr[j + 1]; ++k) v[k] = c * v[k] + (row[k] == j ? 1.0 : 0.0);
  return 0;
}

SUNMatrix mat_clone(SUNMatrix A) {
  // CVODE keeps a saved Jacobian cloned from A; it gets the same kernels.
  SUNMatrix B = g_clone(A);
  if (B != nullptr) install_fast_matrix_kernels(B);
  return B;
}

}  // namespace

void install_fast_vector_kernels(N_Vector v) {
  N_Vector_Ops o = v->ops;
  o->nvlinearsum = linear_sum;
  o->nvconst = constant;
  o->nvprod = prod;
  o->nvdiv = div;
  o->nvscale = scale;
  o->nvabs = absolute;
  o->nvinv = inverse;
  o->nvaddconst = add_const;
  o->nvwrmsnorm = wrms_norm;
  o->nvwsqrsumlocal = wsqrsum;
  o->nvmaxnorm = max_norm;
  o->nvmaxnormlocal = max_norm;
  o->nvlinearcombination = linear_combination;
  o->nvscaleaddmulti = scale_add_multi;
}

void install_fast_matrix_kernels(SUNMatrix A) {
  if (SUNMatGetID(A) != SUNMATRIX_SPARSE || SM_SPARSETYPE_S(A) != CSC_MAT) return;
  if (g_zero == nullptr) {
    g_zero = A->ops->zero;
    g_copy = A->ops->copy;
    g_scaleaddi = A->ops->scaleaddi;
    g_clone = A->ops->clone;
  }
  A->ops->clone = mat_clone;
  A->ops->zero = mat_zero;
  A->ops->copy = mat_copy;
  A->ops->scaleaddi = mat_scale_add_identity;
}

}  // namespace cvt::mbd::detail
