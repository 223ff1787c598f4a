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

struct CvodeRun {
  bool ok = true;
  std::string message;
  long steps = 0, rhs_evals = 0;
};

// One whole simulation: CVODE's memory, vectors and solvers are created and freed inside (as a
// program simulating one scene would), the SUNDIALS context once per process.
template <class Sys>
CvodeRun run_cvode(const Problem<Sys>& pb, bool bdf, double rtol, SUNContext ctx, Samples& s) {
  CvodeRun r;
  N_Vector y = N_VNew_Serial(Sys::nx, ctx);
  Eigen::Map<typename Sys::State>(N_VGetArrayPointer(y)) = pb.x0;
  void* mem = CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx);
  SUNMatrix A = nullptr;
  SUNLinearSolver ls = nullptr;
  SUNNonlinearSolver nls = nullptr;
  int flag = CVodeInit(mem, cv_rhs<Sys>, 0.0, y);
  flag |= CVodeSetUserData(mem, const_cast<Problem<Sys>*>(&pb));
  flag |= CVodeSStolerances(mem, rtol, 1e-2 * rtol);  // pogear's atol = 1e-2 rtol
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
  const std::vector<double> tolerances =
      o.quick ? std::vector<double>{1e-4, 1e-8}
              : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  Samples s;
  s.reset(Sys::nx, pb.count);
  for (const bool bdf : {true, false}) {
    bool slow = false;
    for (double rtol : tolerances) {
      Row r;
      r.scene = pb.scene;
      r.model = pb.model;
      r.family = "cvode";
      r.method = bdf ? "cvode_bdf" : "cvode_adams";
      r.knob = "rtol";
      r.value = rtol;
      r.horizon = pb.horizon;
      if (slow) {
        r.status = "skipped";
        r.note = "a looser tolerance already took longer than " + fmt_double(o.max_run) + " s";
        write_row(res, r);
        continue;
      }
      CvodeRun cr;
      auto run = [&] { cr = run_cvode(pb, bdf, rtol, ctx, s); };
      run();
      r.error = max_rel_error(s, pb.ref);
      r.steps = cr.steps;
      r.rhs_evals = cr.rhs_evals;
      if (!cr.ok) {
        r.status = "failed";
        r.note = cr.message;
      }
      r.time = measure(run, o);
      slow = r.time.median > o.max_run;
      write_row(res, r);
      // CVODE is a variable-order code (BDF 1-5, Adams 1-12) whose global error tracks the tolerance
      // like dopri5's does: the same bound.
      expect_error_within(chk, pb.label(), r, cr.ok, rtol, adaptive_bound(rtol));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk;
  chk.enabled = o.check;
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
