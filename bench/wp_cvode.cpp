// Work-precision of SUNDIALS CVODE on the same generated right-hand sides: BDF with the dense
// linear solver and the exact Jacobian (M), and Adams with fixed-point (functional) iteration.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "paper_scenes.hpp"

namespace {

using namespace bench;

// CVODE's callbacks: the state arrives as an N_Vector; it is copied into the generated code's
// fixed-size State (10-12 doubles, a few ns) because the generated rhs takes Eigen types.
template <class Sys>
int cv_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* data) {
  const auto& pb = *static_cast<const Problem<Sys>*>(data);
  const typename Sys::State x = Eigen::Map<const typename Sys::State>(N_VGetArrayPointer(y));
  typename Sys::State dx;
  pb.rhs(t, x, dx);
  Eigen::Map<typename Sys::State>(N_VGetArrayPointer(ydot)) = dx;
  return 0;
}

// The model is linear: the Jacobian is the generated M.
template <class Sys>
int cv_jac(sunrealtype, N_Vector, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector, N_Vector) {
  const auto& pb = *static_cast<const Problem<Sys>*>(data);
  for (int j = 0; j < Sys::nx; ++j)
    for (int i = 0; i < Sys::nx; ++i) SM_ELEMENT_D(J, i, j) = pb.M(i, j);
  return 0;
}

// One whole simulation: CVODE's memory, vectors and solvers are created and freed inside (as a
// program simulating one scene would), the SUNDIALS context once per process.
template <class Sys>
IntegratorRun run_cvode(const Problem<Sys>& pb, bool bdf, double rtol, SUNContext ctx, Samples& s) {
  IntegratorRun r;
  N_Vector y = N_VNew_Serial(Sys::nx, ctx);
  Eigen::Map<typename Sys::State>(N_VGetArrayPointer(y)) = pb.x0;
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  SUNMatrix A = nullptr;
  SUNLinearSolver ls = nullptr;
  SUNNonlinearSolver nls = nullptr;
  int flag = CVodeInit(mem, cv_rhs<Sys>, 0.0, y);
  flag |= CVodeSetUserData(mem, const_cast<Problem<Sys>*>(&pb));
  flag |= CVodeSStolerances(mem, rtol, rt::absolute_per_relative_tolerance * rtol);  // as pogear's runs
  flag |= CVodeSetMaxNumSteps(mem, 100000000);
  if (bdf) {
    A = SUNDenseMatrix(Sys::nx, Sys::nx, ctx);
    ls = SUNLinSol_Dense(y, A, ctx);
    flag |= CVodeSetLinearSolver(mem, ls, A);
    flag |= CVodeSetJacFn(mem, cv_jac<Sys>);
  } else {
    nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
    flag |= CVodeSetNonlinearSolver(mem, nls);
  }
  if (flag != CV_SUCCESS) {
    r.ok = false;
    r.message = "CVODE setup failed";
  }
  s.restart();
  s.push(Eigen::Map<const typename Sys::State>(N_VGetArrayPointer(y)));
  for (long k = 1; k < pb.count && r.ok; ++k) {
    sunrealtype t = 0;
    flag = CVode(mem, pb.time(k), y, &t, CV_NORMAL);  // CVODE interpolates onto the sample time
    if (flag < 0) {
      r.ok = false;
      r.message = "CVode returned " + std::to_string(flag) + " at t = " + fmt_double(t);
      break;
    }
    s.push(Eigen::Map<const typename Sys::State>(N_VGetArrayPointer(y)));
  }
  CVodeGetNumSteps(mem, &r.steps);
  CVodeGetNumRhsEvals(mem, &r.rhs_evals);
  CVodeFree(&mem);
  if (ls) SUNLinSolFree(ls);
  if (A) SUNMatDestroy(A);
  if (nls) SUNNonlinSolFree(nls);
  N_VDestroy(y);
  return r;
}

template <class Sys>
void bench_cvode(const Problem<Sys>& pb, SUNContext ctx, const Options& o, Results& res, Checker& chk) {
  Samples s;
  s.reset(Sys::nx, pb.count);
  // CVODE is a variable-order code (BDF 1-5, Adams 1-12).
  for (const bool bdf : {true, false})
    integrator_rows(pb, "cvode", bdf ? "cvode_bdf" : "cvode_adams", s, o, res, chk,
                    [&](double rtol) { return run_cvode(pb, bdf, rtol, ctx, s); });
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk{o.check};
  Results res(o.out + "/wp_cvode.csv", kWpHeader);
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0) {
    std::fprintf(stderr, "wp_cvode: error: cannot create a SUNDIALS context\n");
    return 2;
  }
  std::printf("CVODE (SUNDIALS %s)\n", SUNDIALS_VERSION);
  for_each_paper_scene([&](const auto& elastic, const auto& rigid) {
    bench_cvode(elastic, ctx, o, res, chk);
    bench_cvode(rigid, ctx, o, res, chk);
  });
  SUNContext_Free(&ctx);
  return chk.exit_code("wp_cvode");
}
