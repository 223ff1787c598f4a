// A scene's [simulation]: horizon, sample period, solver and its tolerance, step and step budget,
// each checked against the limits the runs keep (pogear/run_limits.hpp).
#include "read/simulation_table.hpp"

#include <fmt/format.h>

#include "pogear/run_limits.hpp"

namespace pogear {

void read_simulation(const SceneReader& r, const toml::node& n, Scene& s) {
  if (!n.is_table()) r.fail(n, "[simulation] must be a table");
  const toml::table& t = *n.as_table();
  r.only_keys(t, {"horizon", "sample", "solver", "tolerance", "step", "max_steps"}, "[simulation]");
  if (const toml::node* v = t.get("max_steps")) {
    if (!v->is_integer() || *v->value<long>() < rt::limits::min_max_steps ||
        *v->value<long>() > rt::limits::max_max_steps)
      r.fail(*v, fmt::format("max_steps is a whole number from {} to {}", rt::limits::min_max_steps,
                             rt::limits::max_max_steps));
    s.max_steps = *v->value<long>();
  }
  if (const toml::node* v = t.get("horizon")) s.horizon = r.quantity(*v, time_dimension(), "horizon");
  if (const toml::node* v = t.get("sample")) {
    s.sample = r.quantity(*v, time_dimension(), "sample");
    s.sample_where = r.loc(*v);
  }
  if (const toml::node* v = t.get("step")) s.step = r.quantity(*v, time_dimension(), "step");
  if (const toml::node* v = t.get("tolerance")) {
    if (!v->is_number()) r.fail(*v, "tolerance is a plain number, the relative tolerance, e.g. 1e-8");
    s.tolerance = *v->value<double>();
    if (!(s.tolerance >= rt::limits::min_tolerance && s.tolerance <= rt::limits::max_tolerance))
      r.fail(*v, fmt::format("tolerance must be from {} to {} (a looser one lets an adaptive method "
                             "diverge, a tighter one stalls it on rounding); give one in that range, e.g. 1e-8",
                             rt::limits::min_tolerance, rt::limits::max_tolerance));
  }
  if (const toml::node* v = t.get("solver")) {
    s.solver_where = r.loc(*v);
    s.solver = parse_solver(r.string(*v, "solver"), s.solver_where);
    s.solver_given = true;
  }
  if (!(s.horizon > 0)) r.fail(*t.get("horizon"), "horizon must be positive; give the simulated time, e.g. horizon = \"2*s\"");
  if (!(s.sample > 0) || s.sample > s.horizon)
    r.fail(t.get("sample") ? *t.get("sample") : n, "sample must be positive and at most the horizon");
  if (!(s.step > 0)) r.fail(*t.get("step"), "step must be positive");
  if (!(s.step >= rt::limits::min_step && s.step <= rt::limits::max_step))
    r.fail(*t.get("step"), fmt::format("step must be from {} s to {} s; give a step in that range",
                                           rt::limits::min_step, rt::limits::max_step));
  if (s.horizon / s.sample > rt::limits::max_samples)
    r.fail(n, fmt::format("{} samples requested; at most 1e7 (raise sample or shorten the horizon)", s.horizon / s.sample));
}

}  // namespace pogear
