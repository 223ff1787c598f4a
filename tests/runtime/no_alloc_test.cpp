// Checks that stepping fixed-size states never touches the heap (generated simulators run millions
// of steps), using Eigen's runtime malloc guard; and that the hybrid engine's stepping does not either
// once its caches hold a mode's step (exact, and adaptive with quadratic, engine and converter
// torques), counting every call into the C heap.
// The CMake target defines EIGEN_RUNTIME_NO_MALLOC for all its files (they must agree on Eigen's
// configuration); the fallback keeps this file meaningful when compiled on its own.
#ifndef EIGEN_RUNTIME_NO_MALLOC
#define EIGEN_RUNTIME_NO_MALLOC
#endif
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <pogear/hybrid.hpp>
#include <pogear/runtime.hpp>
#include <vector>

// The hybrid engine is compiled into libpogear_runtime, where Eigen's guard is not compiled in: its
// allocations are counted at the C heap instead. glibc lets a program replace malloc and its family
// (malloc(3), "Replacing malloc"); these forward to glibc's own allocator, counting while asked to.
// Every C++ allocation (operator new, Eigen's aligned_malloc) ends in one of them.
#if defined(__GLIBC__)
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
}
namespace {
std::atomic<bool> heap_counting{false};
std::atomic<long> heap_calls{0};
void count_heap_call() {
  if (heap_counting.load(std::memory_order_relaxed)) heap_calls.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace
extern "C" {
void* malloc(std::size_t n) noexcept {
  count_heap_call();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  count_heap_call();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) noexcept {
  count_heap_call();
  return __libc_realloc(p, n);
}
void* aligned_alloc(std::size_t alignment, std::size_t n) noexcept {
  count_heap_call();
  return __libc_memalign(alignment, n);
}
void* memalign(std::size_t alignment, std::size_t n) noexcept {
  count_heap_call();
  return __libc_memalign(alignment, n);
}
int posix_memalign(void** p, std::size_t alignment, std::size_t n) noexcept {
  count_heap_call();
  *p = __libc_memalign(alignment, n);
  return *p ? 0 : ENOMEM;
}
}
#define POGEAR_TEST_COUNTS_HEAP 1
#endif

namespace rt = pogear::rt;

namespace {

constexpr int kN = 24;  // a mid-sized generated model: fixed-size products may not spill to the heap
using X = Eigen::Matrix<double, kN, 1>;
using Mat = Eigen::Matrix<double, kN, kN>;

// A chain of damped oscillators, as a gear train is: a well-conditioned, mildly stiff test system.
Mat chain() {
  Mat A = Mat::Zero();
  for (int i = 0; i < kN; i += 2) {
    A(i, i + 1) = 1;
    A(i + 1, i) = -4 - i;
    A(i + 1, i + 1) = -0.5;
    if (i + 2 < kN) A(i + 1, i + 2) = A(i + 3, i) = 1;
  }
  return A;
}

// Turns Eigen's malloc guard on for a scope.
struct NoMalloc {
  NoMalloc() { Eigen::internal::set_is_malloc_allowed(false); }
  ~NoMalloc() { Eigen::internal::set_is_malloc_allowed(true); }
};

}  // namespace

TEST(NoAlloc, GuardIsActive) {
  NoMalloc guard;
  EXPECT_DEATH_IF_SUPPORTED((void)Eigen::VectorXd(3), "");  // proves the guard would catch a heap allocation
}

TEST(NoAlloc, SteppersAndExactWithFixedSizes) {
  const Mat A = chain();
  const Eigen::Matrix<double, kN, 2> B = Eigen::Matrix<double, kN, 2>::Ones();
  auto f = [&](double t, const X& x, X& dx) {
    dx.noalias() = A * x;
    dx(1) += std::sin(t);
  };
  auto jac = [&](double, const X&, Mat& J) { J = A; };
  const X x0 = X::Ones();
  const rt::ExactDiscretization<kN, 2> disc(A, B, 1e-3);  // the exponential itself may allocate
  rt::SolverOptions opt;
  opt.rtol = 1e-6;
  double sum = 0;
  auto obs = [&](double, const X& x) { sum += x(0); };
  rt::RunStatus r1, r2, r3;
  X x = x0, xn;
  {
    NoMalloc guard;
    r1 = rt::simulate_rk4(f, x0, 0.0, 1.0, 0.01, opt, obs);
    r2 = rt::simulate_dopri5(f, x0, 0.0, 1.0, 0.01, opt, obs);
    r3 = rt::simulate_implicit(f, jac, true, x0, 0.0, 1.0, 0.01, opt, obs);
    const Eigen::Vector2d u(0.5, -1);
    for (int k = 0; k < 1000; ++k) {
      disc.step(x, u, u, xn);
      x = xn;
    }
  }
  EXPECT_TRUE(r1.ok) << r1.message;
  EXPECT_TRUE(r2.ok) << r2.message;
  EXPECT_TRUE(r3.ok) << r3.message;
  EXPECT_GT(r2.steps, 10);
  EXPECT_TRUE(x.allFinite());
  EXPECT_TRUE(std::isfinite(sum));
}

#if defined(POGEAR_TEST_COUNTS_HEAP)
namespace {

// Counts the calls into the C heap for a scope.
struct HeapCount {
  HeapCount() {
    heap_calls = 0;
    heap_counting = true;
  }
  ~HeapCount() { heap_counting = false; }
  long calls() const { return heap_calls.load(); }
};

}  // namespace

TEST(NoAlloc, HeapCountIsActive) {
  HeapCount count;
  {
    Eigen::VectorXd v(3);
    std::vector<int> u(5);
    v.setZero();
    u[0] = 1;
  }
  EXPECT_EQ(count.calls(), 2);  // proves the count sees Eigen's and the standard library's allocations
}

namespace {

// What drives clutch_and_shaft's bodies besides its two input signals.
enum class Drive {
  inputs,     // the signals alone
  fan,        // a quadratic torque (an input of the state) brakes body 3
  driveline,  // an engine on body 1 and a converter from it to body 2, the clutch its lock-up
  triggered,  // the signals, the load's step starting 0.5 s after the clutch locks
  actuated,   // the clutch's actuator lags its command, which falls 0.5 s after the clutch locks
};

// Body 1 spins against bodies 2 and 3 (an elastic shaft between them) through a clutch that engages,
// locks, and breaks away under a load step.
rt::HybridSystem clutch_and_shaft(Drive drive) {
  const double J1 = 0.1, J2 = 0.1, J3 = 0.1, k = 60, c = 0.05;
  rt::HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(4, 4);  // x = [omega1, omega2, twist, omega3]
  sys.M.row(1) << 0, -c / J2, -k / J2, c / J2;
  sys.M.row(2) << 0, 1, 0, -1;
  sys.M.row(3) << 0, c / J3, k / J3, -c / J3;
  // w = [tau1, load on body 3, state torques, clutch torque]
  const Eigen::Index q = drive == Drive::fan ? 1 : drive == Drive::driveline ? 3 : 0;
  sys.N = Eigen::MatrixXd::Zero(4, 3 + q);
  sys.N(0, 0) = 1 / J1;
  sys.N(3, 1) = -1 / J3;
  if (drive == Drive::fan) sys.N(3, 2) = 1 / J3;
  if (drive == Drive::driveline) {  // Tengine and Tpump on body 1, Tturbine on body 2
    sys.N(0, 2) = sys.N(0, 3) = 1 / J1;
    sys.N(1, 4) = 1 / J2;
  }
  sys.N(0, 2 + q) = -1 / J1;
  sys.N(1, 2 + q) = 1 / J2;
  sys.S = Eigen::MatrixXd(1, 4);
  sys.S << 1, -1, 0, 0;
  sys.elements.push_back({"C", 5, 1.2, rt::Table{{0.125, 0.375}, {0, 1}}});
  sys.inputs = {rt::Constant{0.5}, rt::Step{0, 30, 2}};
  if (drive == Drive::triggered) {  // a jump to 30 N m at its start: the table's repeated first time
    sys.inputs[1] = rt::Table{{0, 0}, {0, 30}};
    sys.triggered = {{false, 1, 0, rt::ElementState::stuck, 0.5, "load", std::nullopt, std::nullopt}};
  }
  if (drive == Drive::actuated) {  // its knots at the trigger in capacity reserved before the run
    rt::FrictionElementData& e = sys.elements[0];
    e.fill_delay = 0.02;
    e.time_constant = 0.05;
    sys.triggered = {{true, 0, 0, rt::ElementState::stuck, 0.5, "command_C", e.command, std::nullopt}};
    e.command = rt::Table{{0, 0.25}, {1, 0.6}};
  }
  if (drive == Drive::fan) sys.state_torques.push_back(rt::quadratic_torque_data(Eigen::RowVector4d(0, 0, 0, 1), 0.002));
  if (drive == Drive::driveline) {
    rt::DrivelineData d;
    d.engine = rt::EngineData{{0, 100}, {0, 1}, {{0, -2}, {4, 2}}};
    d.throttle = rt::Constant{0.6};
    d.engine_speed = d.pump_speed = Eigen::RowVector4d(1, 0, 0, 0);
    d.turbine_speed = Eigen::RowVector4d(0, 1, 0, 0);
    d.converter = rt::ConverterData{{{0, 0.5, 0.9}, {18, 20, 30}}, {{0, 0.5, 0.9}, {2, 1.4, 1}}};
    sys.state_torques = rt::driveline_state_torques(d);
  }
  return sys;
}

// Runs clutch_and_shaft(drive) from 30 rad/s on body 1 and expects no heap call in a sample period
// of a mode met before (none of its own or the one before it with an event or a change of mode).
void expect_later_periods_allocate_nothing(Drive drive, rt::HybridMethod method) {
  const double sample = 0.03125, horizon = 4;
  const rt::HybridSystem sys = clutch_and_shaft(drive);
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(4);
  x0(0) = 30;
  rt::HybridEngine engine(sys, horizon, method);
  const auto n = static_cast<std::size_t>(horizon / sample) + 2;
  std::vector<double> t, events;
  std::vector<long> calls;
  std::vector<std::uint32_t> mode;
  t.reserve(n);
  calls.reserve(n);
  mode.reserve(n);
  events.reserve(1000);
  rt::RunStatus status;
  int started = 0;
  {
    HeapCount count;
    status = engine.run(
        x0, sample,
        [&](double ts, const rt::HybridSample& s) {
          t.push_back(ts);
          calls.push_back(count.calls());
          mode.push_back(s.mode);
          return true;
        },
        [&](const rt::HybridEvent& e) {
          events.push_back(e.t);
          started += e.started >= 0;
        });
  }
  ASSERT_TRUE(status.ok) << status.message;
  ASSERT_EQ(t.size() + 1, n);
  ASSERT_GE(events.size(), 3u);  // engages, locks, breaks away
  EXPECT_EQ(started, drive == Drive::triggered || drive == Drive::actuated ? 1 : 0);
  auto has_event = [&](std::size_t i) {  // in the sample period (t[i-1], t[i]]
    for (const double e : events)
      if (e > t[i - 1] && e <= t[i]) return true;
    return false;
  };
  std::size_t checked = 0, stuck = 0;
  for (std::size_t i = 2; i < t.size(); ++i) {
    if (has_event(i) || has_event(i - 1) || mode[i] != mode[i - 1] || mode[i - 1] != mode[i - 2]) continue;
    EXPECT_EQ(calls[i] - calls[i - 1], 0) << "heap calls in the sample period ending at t = " << t[i];
    ++checked;
    stuck += mode[i] != 0;
  }
  // Most periods are such later periods of a mode, the clutch slipping and stuck.
  EXPECT_GT(checked, t.size() / 2);
  EXPECT_GT(stuck, 10u);
  EXPECT_GT(checked - stuck, 10u);
}

}  // namespace

// An exact hybrid run: once a mode has been stepped through a whole sample period (its
// discretization and event proof for that step cached), its later periods allocate nothing. The
// sample period is longer than each mode's event_step, so that whole-period steps go through the
// event proof; the breakpoints fall on sample times.
TEST(NoAlloc, HybridExactStepping) {
  ASSERT_GT(0.03125, 0.25 * std::numbers::pi / std::sqrt(60 * (1 / 0.1 + 1 / 0.1)));  // the stuck mode's is longer still
  expect_later_periods_allocate_nothing(Drive::inputs, rt::HybridMethod{rt::Solver::exact, {}});
}

// dopri5 and TR-BDF2 stepping the nonlinear modes of the same clutch with a fan.
TEST(NoAlloc, HybridAdaptiveSteppingOfNonlinearModes) {
  for (const rt::Solver solver : {rt::Solver::dopri5, rt::Solver::implicit}) {
    SCOPED_TRACE(std::string(rt::solver_name(solver)));
    expect_later_periods_allocate_nothing(Drive::fan, rt::HybridMethod{solver, {}});
  }
}

// The same clutch with its load step started by its lock-up (a triggered signal: its copy in the
// workspace, its breakpoints in capacity reserved before the run), stepped exactly and by dopri5.
TEST(NoAlloc, HybridSteppingWithATriggeredSignal) {
  for (const rt::Solver solver : {rt::Solver::exact, rt::Solver::dopri5}) {
    SCOPED_TRACE(std::string(rt::solver_name(solver)));
    expect_later_periods_allocate_nothing(Drive::triggered, rt::HybridMethod{solver, {}});
  }
}

// The same with an engine map and a converter, the clutch as its lock-up: their torques and slopes
// come from the tables in place.
TEST(NoAlloc, HybridSteppingOfAnEngineAndAConverter) {
  for (const rt::Solver solver : {rt::Solver::dopri5, rt::Solver::implicit}) {
    SCOPED_TRACE(std::string(rt::solver_name(solver)));
    expect_later_periods_allocate_nothing(Drive::driveline, rt::HybridMethod{solver, {}});
  }
}

// The clutch's command through an actuator (delay and lag), falling on a trigger: the engagement's
// knots, rebuilt at the trigger, in the capacity reserved before the run.
TEST(NoAlloc, HybridSteppingThroughAnActuator) {
  for (const rt::Solver solver : {rt::Solver::dopri5, rt::Solver::implicit}) {
    SCOPED_TRACE(std::string(rt::solver_name(solver)));
    expect_later_periods_allocate_nothing(Drive::actuated, rt::HybridMethod{solver, {}});
  }
}
#endif
