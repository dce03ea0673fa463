// CVODE BDF + KLU for the chain model (docs/mbd.md#numerics).
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "chain_solver.hpp"
#include "integrators.hpp"
#include "sundials_kernels.hpp"

namespace cvt::mbd::detail {

namespace {

class Bdf final : public Integrator {
 public:
  Bdf(const ChainModel& m, double t0, const double* y0, double rtol, long long step_cap, bool stop_at_outputs,
      LinearSolver solver)
      : m_(m), rtol_(rtol), cap_(step_cap), t_(t0), stop_at_outputs_(stop_at_outputs), solver_(solver) {
    try {
      create(y0);
    } catch (...) {
      release();
      throw;
    }
  }

  ~Bdf() override { release(); }

  void advance_to(double tout, double* y) override {
    if (tout > t_) {
      long nst = 0;
      CVodeGetNumSteps(mem_, &nst);
      const long long left = cap_ - (before_.steps + nst);
      if (left <= 0) throw RunFailure(t_, "step cap of " + std::to_string(cap_) + " steps reached (raise --max-steps)");
      CVodeSetMaxNumSteps(mem_, static_cast<long>(std::min<long long>(left, 1000000000LL)));
      if (stop_at_outputs_) CVodeSetStopTime(mem_, tout);
      double tret = t_;
      const int flag = CVode(mem_, tout, y_, &tret, CV_NORMAL);
      if (flag < 0) fail(flag, tret);
      t_ = tret;
    }
    std::copy(N_VGetArrayPointer(y_), N_VGetArrayPointer(y_) + m_.size(), y);
  }

  void set_step_cap(long long cap) override { cap_ = cap; }

  void reinit(double t, const double* y) override {
    std::copy(y, y + m_.size(), N_VGetArrayPointer(y_));
    check(CVodeReInit(mem_, t, y_), "CVodeReInit");
    before_ += counters_now();
    t_ = t;
  }

  SolverCounters counters() const override {
    SolverCounters c = counters_now();
    c += before_;
    return c;
  }

 private:
  // CVODE's counters since the last (re)initialisation.
  SolverCounters counters_now() const {
    const auto get = [this](int (*fn)(void*, long*)) {
      long v = 0;
      fn(mem_, &v);
      return static_cast<long long>(v);
    };
    SolverCounters c;
    c.steps = get(CVodeGetNumSteps);
    // Right-hand sides of the integrator and of the linear solver interface.
    c.rhs_evals = get(CVodeGetNumRhsEvals) + get(CVodeGetNumLinRhsEvals);
    c.jac_evals = get(CVodeGetNumJacEvals);
    c.linear_setups = get(CVodeGetNumLinSolvSetups);
    c.newton_iters = get(CVodeGetNumNonlinSolvIters);
    c.error_test_fails = get(CVodeGetNumErrTestFails);
    c.newton_fails = get(CVodeGetNumNonlinSolvConvFails);
    return c;
  }

  void create(const double* y0) {
    const double t0 = t_;
    check(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create");
    const int n = m_.size();
    y_ = N_VNew_Serial(n, ctx_);
    std::copy(y0, y0 + n, N_VGetArrayPointer(y_));
    install_fast_vector_kernels(y_);
    mem_ = CVodeCreate(CV_BDF, ctx_);
    if (mem_ == nullptr) throw RunFailure(t0, "CVODE could not be created");
    CVodeSetErrHandlerFn(mem_, &Bdf::on_error, this);
    check(CVodeInit(mem_, &Bdf::f, t0, y_), "CVodeInit");
    check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
    check(CVodeWFtolerances(mem_, &Bdf::weights), "CVodeWFtolerances");
    if (solver_ == LinearSolver::chain) {
      // docs/mbd.md#linear-algebra: CVODE hands over gamma and whether J is
      // still good; the solver keeps J and factors I - gamma J in its blocks.
      A_ = make_chain_placeholder_matrix(ctx_);
      try {
        LS_ = make_chain_linear_solver(m_, ctx_);
      } catch (const std::logic_error& e) {
        throw RunFailure(t0, std::string("chain linear solver: ") + e.what());
      }
      if (A_ == nullptr || LS_ == nullptr) throw RunFailure(t0, "chain linear solver could not be created");
      check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
      check(CVodeSetLinSysFn(mem_, &Bdf::linear_system), "CVodeSetLinSysFn");
      return;
    }
    A_ = SUNSparseMatrix(n, n, m_.pattern().nnz(), CSC_MAT, ctx_);
    LS_ = SUNLinSol_KLU(y_, A_, ctx_);
    if (A_ == nullptr || LS_ == nullptr) throw RunFailure(t0, "KLU sparse solver could not be created");
    install_fast_matrix_kernels(A_);
    // AMD ordering: it puts the dense pulley and sheave rows and columns last,
    // where COLAMD's fill made clamped-sheave runs 2.7x slower.
    check(SUNLinSol_KLUSetOrdering(LS_, 0), "SUNLinSol_KLUSetOrdering");
    check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(mem_, &Bdf::jac), "CVodeSetJacFn");
  }

  static int linear_system(double t, N_Vector y, N_Vector, SUNMatrix, booleantype jok, booleantype* jcur,
                           double gamma, void* user, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<Bdf*>(user);
    int fresh = 0;
    const int r = chain_linear_system(self->LS_, self->m_, t, N_VGetArrayPointer(y), jok != 0, &fresh, gamma);
    *jcur = fresh != 0 ? SUNTRUE : SUNFALSE;
    return r;
  }

  void release() {
    if (mem_ != nullptr) CVodeFree(&mem_);
    if (LS_ != nullptr) SUNLinSolFree(LS_);
    if (A_ != nullptr) SUNMatDestroy(A_);
    if (y_ != nullptr) N_VDestroy(y_);
    if (ctx_ != nullptr) SUNContext_Free(&ctx_);
    ctx_ = nullptr;
    mem_ = nullptr;
    LS_ = nullptr;
    A_ = nullptr;
    y_ = nullptr;
  }

  static int f(double t, N_Vector y, N_Vector ydot, void* user) {
    auto* self = static_cast<Bdf*>(user);
    // A non-finite force is recoverable: CVODE retries with a smaller step,
    // and if that keeps failing it stops and the fault names the quantity.
    return self->m_.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot)) ? 0 : 1;
  }

  static int jac(double t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
    auto* self = static_cast<Bdf*>(user);
    const SparsePattern& p = self->m_.pattern();
    std::copy(p.col_start.begin(), p.col_start.end(), SUNSparseMatrix_IndexPointers(J));
    std::copy(p.row.begin(), p.row.end(), SUNSparseMatrix_IndexValues(J));
    self->m_.jacobian(t, N_VGetArrayPointer(y), SUNSparseMatrix_Data(J));
    return 0;
  }

  // docs/mbd.md#tolerances: w_i = 1 / (rtol (|y_i| + scale_i)), link angles
  // without the |y_i| term.
  static int weights(N_Vector y, N_Vector ewt, void* user) {
    auto* self = static_cast<Bdf*>(user);
    const double* yv = N_VGetArrayPointer(y);
    double* w = N_VGetArrayPointer(ewt);
    const int n = self->m_.size();
    if (self->scale_.empty()) {
      self->scale_.resize(static_cast<std::size_t>(n));
      self->relative_.resize(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) {
        self->scale_[static_cast<std::size_t>(i)] = self->m_.tolerance_scale(i);
        self->relative_[static_cast<std::size_t>(i)] = self->m_.tolerance_relative(i);
      }
    }
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      w[i] = 1.0 / (self->rtol_ * (self->relative_[k] * std::fabs(yv[i]) + self->scale_[k]));
    }
    return 0;
  }

  static void on_error(int, const char*, const char*, char* msg, void* user) {
    static_cast<Bdf*>(user)->last_error_ = msg != nullptr ? msg : "";
  }

  void check(int flag, const char* what) const {
    if (flag != 0) throw RunFailure(t_, std::string(what) + " failed (" + std::to_string(flag) + ")");
  }

  [[noreturn]] void fail(int flag, double t) const {
    double h = 0;
    CVodeGetCurrentStep(mem_, &h);
    char hs[64];
    std::snprintf(hs, sizeof hs, "%.3g s", h);
    switch (flag) {
      case CV_TOO_MUCH_WORK:
        throw RunFailure(t, "step cap of " + std::to_string(cap_) + " steps reached (raise --max-steps)");
      case CV_RHSFUNC_FAIL:
      case CV_REPTD_RHSFUNC_ERR:
      case CV_UNREC_RHSFUNC_ERR:
      case CV_FIRST_RHSFUNC_ERR:
        throw RunFailure(m_.fault().set ? m_.fault().t_s : t,
                         m_.fault().set ? m_.fault().quantity : std::string("right-hand side failed"));
      case CV_ERR_FAILURE:
      case CV_CONV_FAILURE:
        throw RunFailure(t, std::string("BDF could not meet the tolerance (step size ") + hs +
                                (m_.fault().set ? "; last fault: " + m_.fault().quantity : "") + "): " + last_error_);
      default:
        throw RunFailure(t, "CVODE failed (" + std::string(CVodeGetReturnFlagName(flag)) + "): " + last_error_);
    }
  }

  const ChainModel& m_;
  double rtol_;
  long long cap_;
  double t_;
  bool stop_at_outputs_;
  LinearSolver solver_;
  SolverCounters before_;  // work before the last reinit (counters() and the cap run on)
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  std::vector<double> scale_, relative_;
  std::string last_error_;
};

}  // namespace

std::unique_ptr<Integrator> make_bdf(const ChainModel& m, double t0, const double* y0, double rtol,
                                     long long step_cap, bool stop_at_outputs, LinearSolver solver) {
  return std::make_unique<Bdf>(m, t0, y0, rtol, step_cap, stop_at_outputs, solver);
}

}  // namespace cvt::mbd::detail
