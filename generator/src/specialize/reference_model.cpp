// See reference_model.hpp: exact rational arithmetic on the assembled matrices, rounded once.
#include "specialize/reference_model.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "specialize/parameter_folding.hpp"
#include "specialize/specialization.hpp"
#include "specialize/state_torques.hpp"
#include "specialize/torque_limits.hpp"
#include "specialize/triggered_signals.hpp"

namespace pogear {

namespace {

// Where v stands among the ports, or their count when it is not one of them.
Eigen::Index index_of(const std::vector<Variable>& ports, Variable v) {
  return static_cast<Eigen::Index>(std::find(ports.begin(), ports.end(), v) - ports.begin());
}

// The gear's system with the loads' and controllers' torques as inputs (after the system's own):
// the matrices of dx/dt = M x + N u, y = C x + D u + E dx/dt over the gear's states.
struct OpenLoop {
  Eigen::MatrixXd M, N, L, C, D, E, S;
  Eigen::MatrixXd speeds;  // omega = speeds x, one row per body
};

OpenLoop open_loop(const SpecializedScene& model, const SpecializedSystem& sys, const std::vector<Variable>& inputs,
                   std::size_t nx) {
  const Derivation& d = model.derivation;
  const GiNaC::exmap& values = model.values.numbers;
  const ElasticModel& e = d.elastic;
  // Exact rational arithmetic on the assembled matrices, rounded once at the end: the same
  // numbers the specialized expressions give, by another formula.
  auto exact = [&](const GiNaC::matrix& m) { return exact_matrix(m, values); };
  auto doubles = [](const GiNaC::matrix& m) { return evaluate_matrix(m, {}); };
  OpenLoop out;
  // The torque of each input on each body (tau_, loads, controllers: a unit column; friction
  // torques: -e_k^T; set-points: none).
  const GiNaC::matrix G_in = input_torques(d.topology, model.scene, inputs);
  auto input_columns = [&](const GiNaC::matrix& B) { return exact_product(B, G_in); };
  const std::size_t ny = sys.outputs.size(), nu = inputs.size(), n = d.topology.bodies.size();
  out.C = Eigen::MatrixXd::Zero(ny, nx);
  out.D = Eigen::MatrixXd::Zero(ny, nu);
  out.E = Eigen::MatrixXd::Zero(ny, nx);
  out.speeds = Eigen::MatrixXd::Zero(n, nx);
  const std::vector<Variable> states = state_variables(sys);
  auto state_index = [&](Variable v) { return index_of(states, v); };
  const GiNaC::matrix E_rows = engagement_rows(d.topology, sys.friction_elements);
  out.S = Eigen::MatrixXd::Zero(E_rows.rows(), nx);
  if (sys.kind == SystemKind::elastic) {
    for (unsigned r = 0; r < E_rows.rows(); ++r)
      for (std::size_t i = 0; i < nx; ++i)
        if (states[i].kind == VariableKind::velocity) out.S(r, i) = to_double(as_number(E_rows(r, states[i].index)));
    for (std::size_t b = 0; b < n; ++b) out.speeds(b, state_index({VariableKind::velocity, static_cast<int>(b)})) = 1;
    const GiNaC::matrix L = exact(e.L);
    out.L = doubles(L);
    out.M = doubles(exact_solve(L, exact(e.A)));
    out.N = doubles(exact_solve(L, input_columns(exact(e.B))));
    const GiNaC::matrix BKR = exact_product(exact(e.B_K), exact(e.R));
    for (std::size_t i = 0; i < ny; ++i) {
      const Variable y = sys.outputs[i].variable;
      if (y.kind == VariableKind::controller_torque) continue;
      if (of_driveline(y.kind)) {  // an input the run computes
        out.D(i, index_of(inputs, y)) = 1;
        continue;
      }
      if (of_vehicle(y.kind)) {  // km/h of the vehicle body's speed, m/s^2 of its acceleration
        const Eigen::Index w = state_index({VariableKind::velocity, model.scene.vehicle->vehicle_body});
        const double per_omega = model.scene.vehicle->speed_per_omega();
        if (y.kind == VariableKind::vehicle_speed) out.C(i, w) = 3.6 * per_omega;
        else if (y.kind == VariableKind::vehicle_acceleration) out.E(i, w) = per_omega;
        continue;  // vehicle_jerk: vehicle_jerk_rows, from the closed loop's M
      }
      if (y.kind == VariableKind::spring_force) {
        out.C(i, state_index({VariableKind::force, y.index})) = 1;
        continue;
      }
      out.C(i, state_index(y)) = 1;
      if (y.kind == VariableKind::force)  // the damper's share: F + b_K R omega
        for (std::size_t b = 0; b < n; ++b)
          out.C(i, state_index({VariableKind::velocity, static_cast<int>(b)})) +=
              to_double(as_number(BKR(static_cast<unsigned>(y.index), static_cast<unsigned>(b))));
    }
  } else {
    // L1, A1 and Q1 from Q1's entries, not by substituting into the closed forms (the same numbers).
    const RigidValues v = exact_rigid_values(d.rigid, e, values);
    const GiNaC::matrix& Q1 = v.Q1;
    const GiNaC::matrix R = exact(e.R), J = exact(e.J), BJ = exact(e.B_J);
    out.L = doubles(v.L1);
    out.M = doubles(exact_solve(v.L1, v.A1));
    out.N = doubles(exact_solve(v.L1, input_columns(Q1.transpose())));
    // Eq. (8) literally, F = (R R^T)^-1 R g with g = tau - J Q1 x1' - B_J Q1 x1; with redundant
    // meshes the stiffness-weighted split F = K R (R^T K R)^+ g, which equals
    // K R (R^T K R + Q1 Q1^T)^-1 g because g is orthogonal to ker R = span Q1. The inverse is
    // applied to the columns needed, [B_J Q1, J Q1, the inputs' unit vectors], not formed.
    const unsigned k = Q1.cols();
    GiNaC::matrix G(n, 2 * k + nu);
    for (unsigned b = 0; b < n; ++b)
      for (unsigned j = 0; j < k; ++j) {
        G(b, j) = BJ(b, b) * Q1(b, j);
        G(b, k + j) = J(b, b) * Q1(b, j);
      }
    for (unsigned b = 0; b < n; ++b)
      for (std::size_t j = 0; j < nu; ++j) G(b, 2 * k + j) = G_in(b, j);
    GiNaC::matrix PG;  // P G
    if (!d.rigid.redundant_meshes) {
      PG = exact_solve(exact_product(R, R.transpose()), exact_product(R, G));
    } else {
      const GiNaC::matrix K = exact(e.K);
      const GiNaC::matrix S = exact_product(exact_product(R.transpose(), K), R).add(exact_product(Q1, Q1.transpose()));
      PG = exact_product(exact_product(K, R), exact_solve(S, G));
    }
    const Eigen::MatrixXd PGn = doubles(PG), Q1n = doubles(Q1);
    out.speeds = Q1n;
    if (E_rows.rows() > 0) out.S = doubles(exact_product(E_rows, Q1));
    const Eigen::MatrixXd C_F = -PGn.leftCols(k), E_F = -PGn.middleCols(k, k);
    for (std::size_t i = 0; i < ny; ++i) {
      const Variable y = sys.outputs[i].variable;
      if (y.kind == VariableKind::velocity) {
        out.C.row(i) = Q1n.row(y.index);
      } else if (of_driveline(y.kind)) {
        out.D(i, index_of(inputs, y)) = 1;
      } else if (of_vehicle(y.kind)) {
        const double per_omega = model.scene.vehicle->speed_per_omega();
        const auto row = Q1n.row(model.scene.vehicle->vehicle_body);
        if (y.kind == VariableKind::vehicle_speed) out.C.row(i) = 3.6 * per_omega * row;
        else if (y.kind == VariableKind::vehicle_acceleration) out.E.row(i) = per_omega * row;
      } else if (y.kind == VariableKind::force || y.kind == VariableKind::spring_force) {  // the spring carries F
        const Eigen::Index f = y.index;
        out.C.row(i) = C_F.row(f);
        out.E.row(i) = E_F.row(f);
        for (std::size_t j = 0; j < nu; ++j) out.D(i, j) = PGn(f, 2 * k + j);
      }
    }
  }
  return out;
}

}  // namespace

namespace {

// The loads' and controllers' torques as inputs after the system's, w = Kx x + Kv u (+ the
// quadratic loads) closing the loop. A controller with torque limits has its torque among the
// system's inputs already, closed by the hybrid runs through its law.
struct LoopInputs {
  std::vector<Variable> inputs;  // the system's, then the closed controllers' Tc_ and the state loads' TL_
  std::vector<int> closed;       // controllers closed here
  std::vector<const LoadSpec*> state_loads;  // loads with a linear or quadratic part
};

LoopInputs loop_inputs(const Scene& sc, const std::vector<Variable>& system_inputs) {
  LoopInputs out{system_inputs, {}, {}};
  for (std::size_t c = 0; c < sc.controllers.size(); ++c)
    if (!sc.controllers[c].limited()) {
      out.inputs.push_back({VariableKind::controller_torque, static_cast<int>(c)});
      out.closed.push_back(static_cast<int>(c));
    }
  for (const LoadSpec& l : sc.loads)
    if (l.linear != 0 || l.quadratic != 0) {
      out.inputs.push_back({VariableKind::load_torque, l.body});
      out.state_loads.push_back(&l);
    }
  return out;
}

// Each controller's law, Tc = kp (ref - omega_measured) + ki theta, as rows over x and u (its
// integral's row theta' = ref - omega_measured written into M and N); with torque limits, the
// integral's back-calculation at a limit, theta' += (Tc - law) / (ki tracking_time), and the law
// for the hybrid runs.
struct ControllerLaws {
  Eigen::MatrixXd x, u;
};

ControllerLaws controller_laws(const Scene& sc, const SpecializedSystem& sys, const std::vector<Variable>& system_inputs,
                               const Eigen::MatrixXd& speeds, Eigen::Index nb, NumericSystem& out) {
  const auto nc = static_cast<Eigen::Index>(sc.controllers.size());
  const Eigen::Index nx = out.M.rows(), nu = out.N.cols();
  ControllerLaws law{Eigen::MatrixXd::Zero(nc, nx), Eigen::MatrixXd::Zero(nc, nu)};
  for (Eigen::Index c = 0; c < nc; ++c) {
    const ControllerSpec& k = sc.controllers[static_cast<std::size_t>(c)];
    const Eigen::Index ref = index_of(system_inputs, {VariableKind::set_point, static_cast<int>(c)});
    Eigen::RowVectorXd measured = Eigen::RowVectorXd::Zero(speeds.cols());
    if (k.supplies >= 0) {  // a slip controller's: its element's slip, E omega
      const GiNaC::matrix e = engagement_rows(sc.model, {k.supplies});
      for (unsigned b = 0; b < e.cols(); ++b) measured += to_double(as_number(e(0, b))) * speeds.row(b);
    } else {
      measured = speeds.row(k.measured);
    }
    out.M.row(nb + c).head(nb) = -measured;
    out.N(nb + c, ref) = 1;
    law.x.row(c).head(nb) = -k.kp * measured;
    law.x(c, nb + c) = k.ki;
    law.u(c, ref) = k.kp;
  }
  for (const int c : sys.limited_controllers) {
    const ControllerSpec& k = sc.controllers[static_cast<std::size_t>(c)];
    if (k.ki != 0 && k.integral_time_tracking) {  // theta' = (T - ki theta) / kp: the error cancels
      const Eigen::Index torque = index_of(system_inputs, {VariableKind::controller_torque, c});
      out.M.row(nb + c).setZero();
      out.N.row(nb + c).setZero();
      out.M(nb + c, nb + c) = -k.ki / k.kp;
      out.N(nb + c, torque) = 1 / k.kp;
    } else if (k.ki != 0) {
      const double gain = 1 / (k.ki * k.tracking_time);
      const Eigen::Index torque = index_of(system_inputs, {VariableKind::controller_torque, c});
      out.M.row(nb + c) -= gain * law.x.row(c);
      out.N.row(nb + c) -= gain * law.u.row(c);
      out.N(nb + c, torque) += gain;
    }
    out.limit_x.conservativeResize(out.limit_x.rows() + 1, nx);
    out.limit_u.conservativeResize(out.limit_u.rows() + 1, nu);
    out.limit_x.bottomRows(1) = law.x.row(c);
    out.limit_u.bottomRows(1) = law.u.row(c);
  }
  return law;
}

// A controller's torque as an output: its law, or with limits the input the hybrid run sets.
void controller_outputs(const SpecializedSystem& sys, const std::vector<Variable>& system_inputs,
                        const ControllerLaws& law, NumericSystem& out) {
  const auto nu = static_cast<Eigen::Index>(system_inputs.size());
  for (Eigen::Index i = 0; i < out.C.rows(); ++i)
    if (const Variable y = sys.outputs[static_cast<std::size_t>(i)].variable; y.kind == VariableKind::controller_torque) {
      const Eigen::Index input = index_of(system_inputs, y);
      out.C.row(i).setZero();
      out.D.row(i).setZero();
      if (input < nu) {
        out.D(i, input) = 1;
      } else {
        out.C.row(i) = law.x.row(y.index);
        out.D.row(i) = law.u.row(y.index);
      }
    }
}

// The elastic model's vehicle_jerk, (r/i) d/dt of the vehicle body's row of dx/dt: M's row on dx/dt
// and each quadratic load's column on its torque's rate (the specialization refuses inputs there
// that are not constant).
void vehicle_jerk_rows(const SpecializedScene& model, const SpecializedSystem& sys, NumericSystem& out) {
  for (Eigen::Index i = 0; i < out.C.rows(); ++i) {
    if (sys.outputs[static_cast<std::size_t>(i)].variable.kind != VariableKind::vehicle_jerk) continue;
    const Eigen::Index v = index_of(state_variables(sys), {VariableKind::velocity, model.scene.vehicle->vehicle_body});
    const double per_omega = model.scene.vehicle->speed_per_omega();
    out.C.row(i).setZero();
    out.D.row(i).setZero();
    out.E.row(i) = per_omega * out.M.row(v);
    for (QuadraticLoad& q : out.quadratic) q.rate_output_column(i) = per_omega * q.state_column(v);
  }
}

// A lumped planet's meshes: the model's force is its planets' sum, the output one planet's. Speeds
// in rpm when the scene asks.
void output_scales(const Topology& t, const SpecializedSystem& sys, NumericSystem& out) {
  for (Eigen::Index i = 0; i < out.C.rows(); ++i) {
    const OutputPort& y = sys.outputs[static_cast<std::size_t>(i)];
    if (y.variable.kind == VariableKind::force || y.variable.kind == VariableKind::spring_force) {
      // The exact factor as numerator over denominator: 1 / count divides, as the specialized outputs do.
      const GiNaC::numeric f = output_per_model_force(t, t.meshes[static_cast<std::size_t>(y.variable.index)]);
      const double numerator = f.numer().to_double(), denominator = f.denom().to_double();
      out.C.row(i) = out.C.row(i) * numerator / denominator;
      out.D.row(i) = out.D.row(i) * numerator / denominator;
      out.E.row(i) = out.E.row(i) * numerator / denominator;
      for (QuadraticLoad& q : out.quadratic) q.output_column(i) = q.output_column(i) * numerator / denominator;
    } else if (y.in_rpm) {
      out.C.row(i) *= rpm_per_rad_per_s;
      out.D.row(i) *= rpm_per_rad_per_s;
      out.E.row(i) *= rpm_per_rad_per_s;
      for (QuadraticLoad& q : out.quadratic) q.output_column(i) *= rpm_per_rad_per_s;
    }
  }
}

}  // namespace

NumericSystem numeric_system(const SpecializedScene& model, const SpecializedSystem& sys) {
  const Scene& sc = model.scene;
  const auto nx = static_cast<Eigen::Index>(sys.states.size()), nu = static_cast<Eigen::Index>(sys.inputs.size());
  const auto nb = nx - static_cast<Eigen::Index>(sc.controllers.size());  // the gear's states, then the integrals
  const std::vector<Variable> system_inputs = input_variables(sys);
  const LoopInputs loop = loop_inputs(sc, system_inputs);
  const OpenLoop o = open_loop(model, sys, loop.inputs, static_cast<std::size_t>(nb));
  const auto nw = static_cast<Eigen::Index>(loop.inputs.size()) - nu;
  NumericSystem out;
  out.M = Eigen::MatrixXd::Zero(nx, nx);
  out.N = Eigen::MatrixXd::Zero(nx, nu);
  out.M.topLeftCorner(nb, nb) = o.M;
  out.N.topRows(nb) = o.N.leftCols(nu);
  const ControllerLaws law = controller_laws(sc, sys, system_inputs, o.speeds, nb, out);
  Eigen::MatrixXd Kx = Eigen::MatrixXd::Zero(nw, nx), Kv = Eigen::MatrixXd::Zero(nw, nu);
  const auto ncl = static_cast<Eigen::Index>(loop.closed.size());
  for (Eigen::Index j = 0; j < ncl; ++j) {
    Kx.row(j) = law.x.row(loop.closed[static_cast<std::size_t>(j)]);
    Kv.row(j) = law.u.row(loop.closed[static_cast<std::size_t>(j)]);
  }
  const std::vector<const LoadSpec*>& loads = loop.state_loads;
  for (std::size_t l = 0; l < loads.size(); ++l)
    Kx.row(ncl + static_cast<Eigen::Index>(l)).head(nb) = -loads[l]->linear * o.speeds.row(loads[l]->body);
  Eigen::MatrixXd Nw = Eigen::MatrixXd::Zero(nx, nw);
  Nw.topRows(nb) = o.N.rightCols(nw);
  const Eigen::MatrixXd Dw = o.D.rightCols(nw);
  out.M += Nw * Kx;
  out.N += Nw * Kv;
  out.C = Eigen::MatrixXd::Zero(o.C.rows(), nx);
  out.C.leftCols(nb) = o.C;
  out.C += Dw * Kx;
  out.D = o.D.leftCols(nu) + Dw * Kv;
  out.E = Eigen::MatrixXd::Zero(o.C.rows(), nx);
  out.E.leftCols(nb) = o.E;
  for (std::size_t l = 0; l < loads.size(); ++l) {
    if (loads[l]->quadratic == 0) continue;
    const Eigen::Index column = ncl + static_cast<Eigen::Index>(l);
    QuadraticLoad q{Nw.col(column), Dw.col(column), Eigen::VectorXd::Zero(nx), loads[l]->quadratic,
                    Eigen::VectorXd::Zero(out.C.rows())};
    q.speed_row.head(nb) = o.speeds.row(loads[l]->body).transpose();
    out.quadratic.push_back(std::move(q));
  }
  // The speed of each driveline torque's body, from the open loop's speeds.
  out.driveline_speeds = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(sys.driveline.size()), nx);
  for (std::size_t i = 0; i < sys.driveline.size(); ++i)
    out.driveline_speeds.row(static_cast<Eigen::Index>(i)).head(nb) = o.speeds.row(driveline_body(sc, sys.driveline[i].kind));
  controller_outputs(sys, system_inputs, law, out);
  vehicle_jerk_rows(model, sys, out);
  if (sc.controllers.empty()) out.L = o.L;
  out.S = Eigen::MatrixXd::Zero(o.S.rows(), nx);
  out.S.leftCols(nb) = o.S;
  const std::vector<double> x0 = initial_values(sys);
  out.x0 = Eigen::Map<const Eigen::VectorXd>(x0.data(), nx);
  output_scales(model.derivation.topology, sys, out);
  return out;
}

Eigen::MatrixXd state_matrix(const SpecializedScene& model, const SpecializedSystem& sys) {
  const GiNaC::exmap& values = model.values.numbers;
  if (!sys.implicit) return evaluate_matrix(sys.M, values);
  return evaluate_matrix(sys.implicit->L, values).llt().solve(evaluate_matrix(sys.implicit->A, values));
}

Eigen::MatrixXd state_matrix_within_limits(const SpecializedScene& model, const SpecializedSystem& sys) {
  if (sys.limited_controllers.empty()) return state_matrix(model, sys);
  const GiNaC::exmap& values = model.values.numbers;
  const Eigen::MatrixXd X = evaluate_matrix(sys.limit_law_x, values);
  const Eigen::Index nc = X.rows();  // the limited controllers' torques are the last inputs
  if (!sys.implicit) return evaluate_matrix(sys.M, values) + evaluate_matrix(sys.N, values).rightCols(nc) * X;
  // L^-1 (A + B_c X): one solve.
  const Eigen::MatrixXd B = evaluate_matrix(sys.implicit->B, values);
  return evaluate_matrix(sys.implicit->L, values).llt().solve(evaluate_matrix(sys.implicit->A, values) + B.rightCols(nc) * X);
}

rt::DrivelineData driveline_data(const Scene& scene, const SpecializedSystem& sys, const Eigen::MatrixXd& speeds) {
  rt::DrivelineData out;
  for (std::size_t i = 0; i < sys.driveline.size(); ++i) {
    const Eigen::RowVectorXd row = speeds.row(static_cast<Eigen::Index>(i));
    switch (sys.driveline[i].kind) {
      case VariableKind::engine_torque:
        out.engine = scene.engine->map;
        out.throttle = scene.engine->throttle;
        out.engine_speed = row;
        break;
      case VariableKind::pump_torque:
        out.converter = scene.converter->curves;
        out.pump_speed = row;
        break;
      default: out.turbine_speed = row;
    }
  }
  return out;
}

rt::HybridSystem hybrid_system(const SpecializedScene& model, const SpecializedSystem& system, const NumericSystem& ns) {
  rt::HybridSystem hs;
  hs.M = ns.M;
  hs.S = ns.S;
  hs.inputs = input_signals(system);
  // w = [u; q; T]: the state torques' columns between the signals' and the elements', the driveline's
  // (inputs of the system after its signals) first, then the quadratic loads'.
  hs.state_torques = rt::driveline_state_torques(driveline_data(model.scene, system, ns.driveline_speeds));
  const auto head = static_cast<Eigen::Index>(hs.inputs.size() + hs.state_torques.size());
  const auto nq = static_cast<Eigen::Index>(ns.quadratic.size());
  Eigen::MatrixXd Nq(ns.N.rows(), nq);
  for (Eigen::Index i = 0; i < nq; ++i) {
    const QuadraticLoad& q = ns.quadratic[static_cast<std::size_t>(i)];
    Nq.col(i) = q.state_column;
    hs.state_torques.push_back(rt::quadratic_torque_data(q.speed_row.transpose(), q.coefficient));
  }
  hs.N = rt::with_quadratic_columns(ns.N, head, Nq);
  for (const FrictionRun& f : model.friction) hs.elements.push_back(element_data(f));
  hs.triggered = triggered_signals(model, system);
  hs.limits = torque_limit_data(model, system, hs.triggered);
  for (std::size_t l = 0; l < hs.limits.size(); ++l) {
    hs.limits[l].law_x = ns.limit_x.row(static_cast<Eigen::Index>(l));
    hs.limits[l].law_w = rt::law_with_quadratic_columns(ns.limit_u.row(static_cast<Eigen::Index>(l)), head, nq);
  }
  return hs;
}

}  // namespace pogear
