// Brakes and clutches in a scene's run: a generated (or interpreted) system with friction torques as
// its last inputs, run by the hybrid engine (hybrid.hpp), its CSV and its events file written.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "pogear/element_thermal.hpp"
#include "pogear/hybrid.hpp"
#include "pogear/output_file.hpp"
#include "pogear/run_system.hpp"

namespace pogear::rt {

// Writes OUT/<name><suffix>.events.csv: `t [s],element,from,to`, one row per change of state (a
// controller's states are `linear` and `at_limit`, a slip controller's also `off`), and one `t,<signal>,waiting,started` where a
// triggered signal starts. Element, controller and signal names are identifiers (the readers check
// them), so no field needs quoting.
inline bool write_events(const SceneRun& run, const std::string& suffix, const std::vector<HybridEvent>& events,
                         const std::vector<FrictionElementData>& elements, const std::vector<TorqueLimitData>& limits,
                         const std::vector<TriggeredSignal>& triggered, const std::string& incomplete) {
  OutputFile file(run.out_dir + "/" + run.name + suffix + ".events.csv");
  if (!file.ok()) {
    std::fprintf(stderr, "%s%s: error: %s\n", run.name.c_str(), suffix.c_str(), file.error().c_str());
    return false;
  }
  std::string text = "t [s],element,from,to\n";
  for (const HybridEvent& e : events) {
    char t[32];
    text.append(t, std::to_chars(t, t + sizeof t, e.t).ptr);
    const auto k = static_cast<std::size_t>(e.element);
    if (e.started >= 0 && static_cast<std::size_t>(e.started) < triggered.size()) {
      text += ',' + triggered[static_cast<std::size_t>(e.started)].name + ",waiting,started\n";
    } else if (k < elements.size()) {
      text += ',' + elements[k].name + ',' + state_name(e.from) + ',' + state_name(e.to) + '\n';
    } else {
      auto name = [](ElementState s) { return s == ElementState::stuck ? "linear" : s == ElementState::open ? "off" : "at_limit"; };
      text += ',' + limits[k - elements.size()].name + ',' + name(e.from) + ',' + name(e.to) + '\n';
    }
  }
  if (!incomplete.empty()) text += "# incomplete: " + incomplete + "\n";
  file.write(text);
  if (!file.commit()) {
    std::fprintf(stderr, "%s%s: error: %s\n", run.name.c_str(), suffix.c_str(), file.error().c_str());
    return false;
  }
  return true;
}

// Runs `sys` (a generated system struct whose last inputs are the elements' torques, with
// slip_matrix) with brakes and clutches and torque-limited controllers, and writes
// OUT/<name><suffix>.csv (the system's outputs, a controller's torque among them, then for each
// brake and clutch T_<element> [N m], slip_<element> [rad/s, or rpm with run.speeds_in_rpm],
// E_<element> [J], and the mode) and
// OUT/<name><suffix>.events.csv, with the exact method, dopri5 or implicit (rk4 is refused). The
// controllers' laws come from the system's torque_limit_laws, the quadratic loads of a nonlinear system
// from its quadratic_loads, a converter's and an engine's torques from its driveline (exact
// stepping then refused; the CSV then has E_converter [J], the converter's loss, and W_engine [J],
// the engine's work, before the mode). `triggered`: the signals and commands that start on an
// event (HybridSystem::triggered). `thermal`: the elements whose temperature temp_<element> [degC]
// the CSV has, after the E_ columns. Returns 0, or 3 when the run failed.
template <class System>
int run_hybrid_system(const System& sys, const typename System::Params& p, const std::vector<Signal>& signals,
                      const std::vector<FrictionElementData>& elements, std::vector<TorqueLimitData> limits,
                      const typename System::State& x0, const SceneRun& run, const std::string& suffix,
                      std::vector<TriggeredSignal> triggered = {}, const std::vector<ElementThermal>& thermal = {}) {
  const Eigen::Index nx = x0.size();
  const auto nu = static_cast<Eigen::Index>(signals.size()), ne = static_cast<Eigen::Index>(elements.size()),
             nl = static_cast<Eigen::Index>(limits.size());
  const auto ny = static_cast<Eigen::Index>(std::size(sys.output_names));
  // A converter's and an engine's torques are inputs of the system right after its signals (its outputs
  // read them), which the run computes from the state.
  std::vector<StateTorqueData> driveline;
  if constexpr (requires { sys.driveline(p); }) driveline = driveline_state_torques(sys.driveline(p));
  const auto nd = static_cast<Eigen::Index>(driveline.size());
  typename System::StateMatrix M(nx, nx);
  typename System::InputMatrix N(nx, nu + nd + ne + nl);
  sys.matrices(p, M, N);
  HybridSystem hs;
  hs.M = M;
  hs.state_torques = std::move(driveline);
  // w = [u; q; T]: the state torques' columns between the signals' and the elements', the driveline's
  // first, then the quadratic loads' (which the system's outputs compute themselves).
  Eigen::MatrixXd Nq(nx, 0);
  if constexpr (requires(Eigen::MatrixXd& A, Eigen::VectorXd& c) { sys.quadratic_loads(p, A, A, c); }) {
    Eigen::MatrixXd speeds;
    Eigen::VectorXd coefficients;
    sys.quadratic_loads(p, Nq, speeds, coefficients);
    for (Eigen::Index i = 0; i < coefficients.size(); ++i) hs.state_torques.push_back(quadratic_torque_data(speeds.row(i), coefficients(i)));
  }
  const Eigen::Index nq = nd + Nq.cols();
  hs.N = with_quadratic_columns(N, nu + nd, Nq);
  sys.slip_matrix(p, hs.S);
  if constexpr (requires(Eigen::MatrixXd& X) { sys.torque_limit_laws(p, X, X); }) {
    Eigen::MatrixXd X, W;
    sys.torque_limit_laws(p, X, W);
    for (Eigen::Index l = 0; l < nl; ++l) {
      limits[static_cast<std::size_t>(l)].law_x = X.row(l);
      limits[static_cast<std::size_t>(l)].law_w = law_with_quadratic_columns(W.row(l), nu + nd, Nq.cols());
    }
  }
  for (Eigen::Index j = 0; j < nx; ++j)
    if (sys.state_units[static_cast<std::size_t>(j)] == "rad/s") hs.speed_states.push_back(j);
  hs.elements = elements;
  hs.limits = std::move(limits);
  hs.inputs = signals;
  hs.triggered = std::move(triggered);

  std::vector<std::string> names(std::begin(sys.output_names), std::end(sys.output_names));
  std::vector<std::string> units(std::begin(sys.output_units), std::end(sys.output_units));
  // A crossing of a speed output: its row over the states, read off the outputs (a speed is linear
  // in the state alone), in rad/s.
  for (TriggeredSignal& s : hs.triggered) {
    if (!s.crossing || s.crossing->output.empty()) continue;
    const auto j = static_cast<Eigen::Index>(std::find(names.begin(), names.end(), s.crossing->output) - names.begin());
    if (j == ny || (units[static_cast<std::size_t>(j)] != "rad/s" && units[static_cast<std::size_t>(j)] != "rpm")) {
      std::fprintf(stderr, "%s%s: error: %s waits for %s, which is no speed output of the system\n", run.name.c_str(),
                   suffix.c_str(), s.name.c_str(), s.crossing->output.c_str());
      return 3;
    }
    typename System::State e = x0;
    typename System::Input w0(nu + nd + ne + nl);
    typename System::Output y(ny);
    w0.setZero();
    s.crossing->speed.resize(nx);
    const double to_rad_s = units[static_cast<std::size_t>(j)] == "rpm" ? std::numbers::pi / 30 : 1.0;
    for (Eigen::Index c = 0; c < nx; ++c) {
      e.setZero();
      e(c) = 1;
      sys.outputs(p, e, w0, y);
      s.crossing->speed(c) = to_rad_s * y(j);
    }
  }
  for (const char* prefix : {"T_", "slip_", "E_"})
    for (const auto& e : elements) {
      names.push_back(prefix + e.name);
      units.emplace_back(prefix[0] == 'T' ? "N m" : prefix[0] == 's' ? (run.speeds_in_rpm ? "rpm" : "rad/s") : "J");
    }
  // A capacity that follows tunable parameters (friction_elements(p)) may leave its range at the
  // values --param gave.
  for (const auto& e : elements)
    if (!(e.capacity > 0) || !std::isfinite(e.capacity)) {
      std::fprintf(stderr, "%s%s: error: %s has a torque capacity of %g N m; a capacity is positive: give --param "
                   "values that keep it so\n", run.name.c_str(), suffix.c_str(), e.name.c_str(), e.capacity);
      return 3;
    }
  for (const ElementThermal& th : thermal) {
    if (th.element < 0 || th.element >= ne || !(th.heat_capacity > 0) || !(th.conductance >= 0) ||
        !std::isfinite(th.conductance) || !std::isfinite(th.ambient) || !std::isfinite(th.initial)) {
      std::fprintf(stderr, "%s%s: error: a temperature is of no brake or clutch, or its heat capacity, conductance "
                   "or temperatures are not finite and positive\n", run.name.c_str(), suffix.c_str());
      return 3;
    }
    names.push_back("temp_" + elements[static_cast<std::size_t>(th.element)].name);
    units.emplace_back("degC");
  }
  const auto nt = static_cast<Eigen::Index>(thermal.size());
  // A converter's loss and an engine's work, integrated by the run (the state torques' work, HybridSample).
  const auto driveline_work = [&](bool converter) {
    std::vector<Eigen::Index> columns;
    for (Eigen::Index i = 0; i < nd; ++i)
      if ((hs.state_torques[static_cast<std::size_t>(i)].kind != StateTorqueKind::engine) == converter) columns.push_back(i);
    return columns;
  };
  const std::vector<Eigen::Index> converter_columns = driveline_work(true), engine_columns = driveline_work(false);
  if (!converter_columns.empty()) {
    names.emplace_back("E_converter");
    units.emplace_back("J");
  }
  if (!engine_columns.empty()) {
    names.emplace_back("W_engine");
    units.emplace_back("J");
  }
  const auto nwork = static_cast<Eigen::Index>(!converter_columns.empty() + !engine_columns.empty());
  names.emplace_back("mode");
  units.emplace_back("bits of the stuck elements");
  SystemRunLog log(run, suffix, names, units);
  // The one admissibility rule (solver.hpp), as pogear simulate words it.
  const SystemTraits traits{.nonlinear = nq > 0, .engages_friction = ne > 0, .limits_torque = nl > 0, .driveline = nd > 0,
                            .slip_control = std::any_of(hs.limits.begin(), hs.limits.end(),
                                                        [](const TorqueLimitData& l) { return l.supplies >= 0; }),
                            .friction_curve = varies_with_slip(hs), .actuator_lag = lags_its_command(hs)};
  if (const auto refusal = solver_refusal(run.solver, traits)) {
    const std::vector<Solver> solvers = admissible_solvers(traits);
    std::fprintf(stderr, "%s%s: error: %s; use --solver %s\n", run.name.c_str(), suffix.c_str(),
                 describe(*refusal).c_str(), solver_alternatives(solvers, false).c_str());
    return 3;
  }

  // The divergence check of run_system: friction only dissipates, and a friction torque never
  // exceeds its static capacity (or its friction curve's highest), so it enters the bound as an input
  // of that size; a quadratic load
  // only dissipates (its power -c |s|^3 on its own body's speed s), so it enters as an input of none.
  std::optional<EnergyBound<Eigen::MatrixXd, Eigen::MatrixXd>> energy_bound;
  if constexpr (requires(typename System::StateMatrix& L) { sys.energy_matrix(p, L); }) {
    typename System::StateMatrix L(nx, nx);
    sys.energy_matrix(p, L);
    std::vector<Signal> bounds = signals;
    bounds.insert(bounds.end(), static_cast<std::size_t>(nq), Constant{0.0});
    for (const auto& e : elements) bounds.push_back(Constant{largest_friction_ratio(e) * e.capacity});
    if (L.size() > 0)  // an empty L: no bound (a speed controller feeds in power)
      energy_bound.emplace(Eigen::MatrixXd(L), hs.N, bounds, Eigen::VectorXd(x0), run.horizon);
  }

  // 30 / pi rpm per rad/s, as the generator converts the speed outputs.
  const double slip_scale = run.speeds_in_rpm ? 30 / std::numbers::pi : 1.0;
  typename System::Input w(nu + nd + ne + nl);
  typename System::Output y(ny);
  Eigen::VectorXd row(ny + 3 * ne + nt + nwork + 1);
  // The temperatures and, at the last sample, the time and the elements' heat.
  Eigen::VectorXd temperature(nt), heat_then(ne);
  double t_then = 0;
  RunStatus st;
  std::vector<HybridEvent> events;
  int modes = 0;
  for (int rep = 0; rep < run.repeat; ++rep) {
    if (!log.begin()) return 3;
    events.clear();
    HybridEngine engine(hs, run.horizon, HybridMethod{run.solver, run.options});
    auto obs = [&](double t, const HybridSample& s) {
      if (energy_bound && !energy_bound->within(t, s.x, energy_bound_safety_factor)) {
        log.diverged(t, energy_bound->ratio(t, s.x), nq == 0);
        return false;
      }
      const typename System::State x = s.x;
      w << s.w.head(nu + nd), s.w.tail(ne + nl);  // the system's inputs: its outputs compute the quadratic q
      sys.outputs(p, x, w, y);
      row.head(ny) = y;
      row.segment(ny, ne) = s.w.segment(nu + nq, ne);
      row.segment(ny + ne, ne) = slip_scale * s.slip.head(ne);
      row.segment(ny + 2 * ne, ne) = s.energy.head(ne);
      for (Eigen::Index i = 0; i < nt; ++i) {
        const ElementThermal& th = thermal[static_cast<std::size_t>(i)];
        const double heat = s.energy(th.element);
        temperature(i) = t == 0 ? th.initial : next_temperature(th, temperature(i), heat - heat_then(th.element), t - t_then);
        row(ny + 3 * ne + i) = temperature(i);
      }
      heat_then = s.energy.head(ne);
      t_then = t;
      Eigen::Index at = ny + 3 * ne + nt;
      for (const auto* columns : {&converter_columns, &engine_columns}) {
        if (columns->empty()) continue;
        double work = 0;
        for (const Eigen::Index i : *columns) work += s.energy(ne + nl + i);
        row(at++) = columns == &converter_columns ? -work : work;  // the converter's loss, the engine's work
      }
      row(at) = static_cast<double>(s.mode);
      if (log.writes_csv()) log.row(t, row.data(), static_cast<long>(row.size()));
      return true;
    };
    st = engine.run(Eigen::VectorXd(x0), run.sample, obs, [&](const HybridEvent& e) { events.push_back(e); });
    st.steps = engine.steps();
    st.rhs_evals = engine.rhs_evals();
    modes = engine.modes_met();
    if (!log.end(st)) return 3;
    if (run.csv && !write_events(run, suffix, events, elements, hs.limits, hs.triggered, st.ok ? "" : st.message)) return 3;
    if (!st.ok) break;
  }
  if (st.ok && !run.quiet)
    std::printf("%s%s: %zu events, %d modes met\n", run.name.c_str(), suffix.c_str(), events.size(), modes);
  return log.finish(st);
}

// The same without torque-limited controllers.
template <class System>
int run_hybrid_system(const System& sys, const typename System::Params& p, const std::vector<Signal>& signals,
                      const std::vector<FrictionElementData>& elements, const typename System::State& x0,
                      const SceneRun& run, const std::string& suffix, std::vector<TriggeredSignal> triggered = {},
                      const std::vector<ElementThermal>& thermal = {}) {
  return run_hybrid_system(sys, p, signals, elements, std::vector<TorqueLimitData>{}, x0, run, suffix,
                           std::move(triggered), thermal);
}

}  // namespace pogear::rt
