// The mode's rigid model is derived like `pogear derive --engaged`, kept on the named bodies, and
// solved in exact rationals: the slips of the engaged elements are then zero to the rounding of the
// speeds, which the hybrid engine's zero-slip rule reads as stuck.
#include "specialize/gear_start.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "pogear/actuator.hpp"
#include "common/exact_algebra.hpp"
#include "derive/engagement.hpp"
#include "names/model_variables.hpp"
#include "names/symbols.hpp"

namespace pogear {
namespace {

std::string gear_label(const Scene& sc, const Topology& t) {
  if (!sc.initial_gear.empty()) return fmt::format("gear '{}'", sc.initial_gear);
  return "engaged = [" + engaged_names(t, sc.initial_engaged, ", ") + "]";
}

// The bodies whose speeds [initial] names, in body order; refuses what the gear's model computes.
std::vector<std::string> named_speeds(const Scene& sc, const Topology& t, const std::string& gear) {
  std::vector<std::string> named;
  for (const auto& [v, value] : sc.initial) {
    if (v.kind == VariableKind::velocity && sc.start == Start::rigid) {
      named.push_back(t.bodies[static_cast<std::size_t>(v.index)].name);
      continue;
    }
    throw InputError(sc.initial_where,
                     fmt::format("starting in {} {}; remove {} from [initial]", gear,
                                 sc.start == Start::steady ? "at equilibrium computes every speed and force"
                                                           : "takes the mesh forces from the gear's rigid model",
                                 variable_name(t, v)));
  }
  return named;
}

// The mode's derivation, kept on the named bodies (steady: on its first valid set).
Derivation mode_derivation(const Scene& sc, const Topology& t, const std::vector<std::string>& named,
                           const std::string& gear) {
  const Derivation free = derive_topology(t, std::nullopt, sc.initial_engaged_where, false, sc.initial_engaged);
  const std::size_t dof = free.rigid.kept.size();
  if (sc.start == Start::steady) return free;
  if (named.size() != dof) {
    std::string example;
    for (int b : free.rigid.kept) example += (example.empty() ? "" : ", ") + variable_name(t, {VariableKind::velocity, b});
    throw InputError(sc.initial_where,
                     fmt::format("{} leaves {} degree{} of freedom, so the start needs the speed of {} bod{} in "
                                 "[initial] ({} named), e.g. {}",
                                 gear, dof, dof == 1 ? "" : "s", dof, dof == 1 ? "y" : "ies", named.size(), example));
  }
  return derive_topology(t, named, sc.initial_where, false, sc.initial_engaged);
}

// What an element engages with at t = 0: its command then, or with an actuator the engagement
// the actuator has at rest on the command before the run (0 there for a command that rises at t = 0
// behind a delay or a lag).
double engagement_at_start(const FrictionRun& run) {
  const double command = value_at_start(run.command, run.start);
  if (!(run.fill_delay > 0 || run.time_constant > 0)) return command;
  rt::ActuatorKnots knots;
  rt::add_knots(knots, run.start ? rt::held_until_start(run.command, run.start->before) : run.command,
                -std::numeric_limits<double>::infinity(), run.fill_delay, run.time_constant);
  return rt::engagement(knots, run.time_constant, 0.0);
}

// The elements the gear does not engage are open at t = 0: one commanded would slip with a torque
// the gear's rigid model does not carry, or stick into another mode.
void check_others_open(const SpecializedScene& model, const std::string& gear) {
  const Scene& sc = model.scene;
  const Topology& t = model.derivation.topology;
  for (const FrictionRun& run : model.friction) {
    const bool in_gear = std::find(sc.initial_engaged.begin(), sc.initial_engaged.end(), run.element) != sc.initial_engaged.end();
    const double command = engagement_at_start(run);
    if (!in_gear && command != 0)
      throw InputError(sc.initial_engaged_where,
                       fmt::format("starting in {}, {} is commanded {:.6g} at t = 0, but the gear does not engage it; "
                                   "open it at t = 0 (its command 0), or start in a gear that engages it",
                                   gear, t.friction_elements[static_cast<std::size_t>(run.element)].name, command));
  }
}

// The engaged elements' commands at t = 0, and their stuck torques within static capacity.
void check_stuck_torques(const SpecializedScene& model, const std::string& gear, const Derivation& mode,
                         const std::vector<GiNaC::numeric>& recovered) {
  const Scene& sc = model.scene;
  const Topology& t = mode.topology;
  const std::size_t meshes = t.meshes.size();
  for (std::size_t j = 0; j < sc.initial_engaged.size(); ++j) {
    const int k = sc.initial_engaged[j];
    const FrictionElement& e = t.friction_elements[static_cast<std::size_t>(k)];
    const auto run = std::find_if(model.friction.begin(), model.friction.end(), [&](const FrictionRun& f) { return f.element == k; });
    const double command = run == model.friction.end() ? 0.0 : engagement_at_start(*run);
    if (!(command > 0) && run != model.friction.end() && value_at_start(run->command, run->start) > 0)
      throw InputError(sc.initial_engaged_where,
                       fmt::format("{} engages {}, but its actuator has not engaged it at t = 0 (its command rises at "
                                   "t = 0, behind its fill delay or lag); command it engaged before the run, e.g. {} = \"1\"",
                                   gear, e.name, e.name));
    if (!(command > 0))
      throw InputError(sc.initial_engaged_where,
                       fmt::format("{} engages {}, but [engagement] leaves it open at t = 0; command it engaged from "
                                   "the start, e.g. {} = \"1\"", gear, e.name, e.name));
    const double torque = to_double(recovered.at(meshes + j));
    const double holds = run->static_ratio * run->capacity * command;
    if (std::abs(torque) > holds) {
      // Six digits, or as many as tell the torque from the capacity it exceeds.
      int digits = 6;
      while (digits < 17 && fmt::format("{:.{}g}", std::abs(torque), digits) == fmt::format("{:.{}g}", holds, digits)) ++digits;
      throw InputError(sc.initial_engaged_where,
                       fmt::format("starting in {}, {} carries {:.{}g} N m at t = 0, beyond its static capacity of "
                                   "{:.{}g} N m ({:.6g} N m x static ratio {:.6g} x command {:.6g}); raise its capacity "
                                   "or its command, or start with smaller torques",
                                   gear, e.name, torque, digits, holds, digits, run->capacity, run->static_ratio, command));
    }
    // A one-way element holds against negative slip only: with T > 0 it freewheels.
    if (e.one_way && torque > 0)
      throw InputError(sc.initial_engaged_where,
                       fmt::format("starting in {}, one-way {} would carry {:.6g} N m at t = 0, in the direction it "
                                   "turns freely, so it does not hold; start in a gear that it holds in",
                                   gear, e.name, torque));
  }
}

}  // namespace

StartState start_in_gear(const SpecializedScene& model) {
  const Scene& sc = model.scene;
  const Topology& t = model.derivation.topology;
  const std::string gear = gear_label(sc, t);
  check_others_open(model, gear);
  const std::vector<std::string> named = named_speeds(sc, t, gear);
  const Derivation mode = mode_derivation(sc, t, named, gear);
  const RigidValues rv = exact_rigid_values(mode.rigid, mode.elastic, mode.values);
  const unsigned k = rv.Q1.cols();
  std::vector<GiNaC::numeric> tau = torques_at_start(sc, t.bodies.size());
  GiNaC::matrix x(k, 1), dx(k, 1);
  if (sc.start == Start::steady) {
    x = steady_rigid_state(sc, rv, tau);
  } else {
    for (unsigned j = 0; j < k; ++j)
      x(j, 0) = exact_number(sc.initial.at(Variable{VariableKind::velocity, mode.rigid.kept[j]}));
    add_speed_dependent_torques(sc, exact_product(rv.Q1, x), tau);
    dx = rigid_acceleration(rv, x, tau);
  }
  const GiNaC::matrix omega = exact_product(rv.Q1, x), domega = exact_product(rv.Q1, dx);
  GiNaC::exmap at_start = mode.values;
  for (std::size_t b = 0; b < t.bodies.size(); ++b) {
    const int i = static_cast<int>(b);
    at_start[variable_symbol(mode.symbols, {VariableKind::velocity, i})] = omega(b, 0);
    at_start[variable_symbol(mode.symbols, {VariableKind::acceleration, i})] = domega(b, 0);
    at_start[variable_symbol(mode.symbols, {VariableKind::torque, i})] = tau[b];
  }
  // Mesh forces, then the engaged elements' torques: eq. (8) with C = [R; E_S].
  std::vector<GiNaC::numeric> recovered;
  for (const GiNaC::ex& f : mode.rigid.force_recovery) recovered.push_back(GiNaC::ex_to<GiNaC::numeric>(exact_value(f, at_start)));
  check_stuck_torques(model, gear, mode, recovered);
  auto state = [&](const SpecializedSystem& sys) {
    std::vector<double> x0;
    for (const StatePort& port : sys.states) {
      const auto i = static_cast<unsigned>(port.variable.index);
      x0.push_back(port.variable.kind == VariableKind::velocity ? to_double(omega(i, 0)) : to_double(recovered.at(i)));
    }
    return x0;
  };
  return {state(model.main), model.rigid ? state(*model.rigid) : std::vector<double>{}};
}

}  // namespace pogear
