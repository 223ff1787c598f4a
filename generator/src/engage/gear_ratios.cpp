// See gear_ratios.hpp. Ranks are numeric at the model's values, as for the rigid model. Each ratio's
// number is its closed form evaluated exactly; a second, exact solve with R at the file's radii
// checks the closed form's algebra.
#include "engage/gear_ratios.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "common/block_triangular_solve.hpp"
#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"
#include "read/tooth_counts.hpp"

namespace pogear {

const char* status_name(EngagementStatus s) {
  switch (s) {
    case EngagementStatus::ratio: return "ratio";
    case EngagementStatus::output_held: return "output held";
    case EngagementStatus::input_held: return "input held";
    case EngagementStatus::free: return "free";
    case EngagementStatus::locked: return "locked";
  }
  return "";
}

namespace {

int body_named(const Topology& t, const std::string& name, const char* option, const SourceLocation& where) {
  const int b = find_body(t, name);
  if (b >= 0) return b;
  if (const std::string why = fixed_body_refusal(t, name, option); !why.empty()) throw InputError(where, why);
  std::string list;
  for (const auto& x : t.bodies) list += (list.empty() ? "" : ", ") + x.name;
  throw InputError(where, fmt::format("{} '{}' is not a body of the model; its bodies are {}", option, name, list));
}

// The sets of k elements out of m, each ascending, in lexicographic order.
void subsets_of_size(int m, int k, int from, std::vector<int>& current, std::vector<std::vector<int>>& out) {
  if (static_cast<int>(current.size()) == k) {
    out.push_back(current);
    return;
  }
  for (int i = from; i < m; ++i) {
    current.push_back(i);
    subsets_of_size(m, k, i + 1, current, out);
    current.pop_back();
  }
}

// The one-way elements of a gear (status ratio), and which way each holds. With the output held by
// its load's reaction tau_out and a unit torque on the input, the gear is static:
//   a_in e_in + e_out tau_out + R^T F - E_S^T T = 0
// (the elements' torques act as -E_S^T T, E_S their slip rows). The constraints [R; E_S; e_out]
// leave nothing free, so T is unique (each element adds a constraint, and so does holding a
// turning output). A one-way element carries T <= 0 only: it holds in drive where T <= 0 and in
// coast, where every torque changes sign, where T >= 0.
std::vector<OneWayHold> one_way_holds(const Topology& t, const Eigen::MatrixXd& Rn, const std::vector<int>& S,
                                      int in, int out) {
  std::vector<OneWayHold> holds;
  if (std::none_of(S.begin(), S.end(), [&](int k) { return t.friction_elements[static_cast<std::size_t>(k)].one_way; }))
    return holds;
  const GiNaC::matrix E = engagement_rows(t, S);
  const Eigen::Index n = Rn.cols(), m = Rn.rows(), ns = static_cast<Eigen::Index>(S.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, m + ns + 1);
  A.leftCols(m) = Rn.transpose();
  for (Eigen::Index k = 0; k < ns; ++k)
    for (Eigen::Index b = 0; b < n; ++b)
      A(b, m + k) = -GiNaC::ex_to<GiNaC::numeric>(E(static_cast<unsigned>(k), static_cast<unsigned>(b))).to_double();
  A(out, m + ns) = 1;
  Eigen::VectorXd drive = Eigen::VectorXd::Zero(n);
  drive(in) = -t.bodies[static_cast<std::size_t>(in)].arrow;
  const Eigen::VectorXd y = A.completeOrthogonalDecomposition().solve(drive);
  const Eigen::VectorXd T = y.segment(m, ns);
  // A torque below rounding of the others is none: the element holds either way.
  const double floor = 1e-9 * std::max(1.0, y.cwiseAbs().maxCoeff());
  for (Eigen::Index k = 0; k < ns; ++k) {
    const int element = S[static_cast<std::size_t>(k)];
    if (!t.friction_elements[static_cast<std::size_t>(element)].one_way) continue;
    holds.push_back({element, T(k) <= floor, T(k) >= -floor});
  }
  return holds;
}

// The engagement a named gear is, or its refusal: a gear between input and output has one degree
// of freedom, and both turn.
const EngagementRatio& engagement_of(const GearRatios& g, const Topology& t, const NamedGear& gear) {
  const auto it = std::find_if(g.engagements.begin(), g.engagements.end(),
                               [&](const EngagementRatio& e) { return e.engaged == gear.engaged; });
  const std::string engaged = gear.engaged.empty() ? "nothing" : engaged_names(t, gear.engaged, ", ");
  if (it == g.engagements.end())
    throw InputError(gear.where, fmt::format("gear '{}' engages {}, of which one element adds no constraint to the "
                                             "others (the set moves as it would without it); name the elements that "
                                             "make the gear", gear.name, engaged));
  switch (it->status) {
    case EngagementStatus::ratio: return *it;
    case EngagementStatus::free:
      throw InputError(gear.where, fmt::format("gear '{}' ({}) leaves {} degrees of freedom; a gear leaves one: "
                                               "engage more elements", gear.name, engaged, it->freedoms));
    case EngagementStatus::locked:
      throw InputError(gear.where, fmt::format("gear '{}' ({}) locks the gear: nothing turns; engage fewer elements",
                                               gear.name, engaged));
    case EngagementStatus::input_held:
    case EngagementStatus::output_held: break;
  }
  throw InputError(gear.where, fmt::format("gear '{}' ({}) holds the {} '{}', so it has no ratio between {} and {}",
                                           gear.name, engaged,
                                           it->status == EngagementStatus::input_held ? "input" : "output",
                                           it->status == EngagementStatus::input_held ? g.input : g.output, g.input,
                                           g.output));
}

// The named gears with i = 1 / ratio, exactly; steps between neighbours that are both forward
// gears, and the spread of the forward gears.
void name_gears(const Topology& t, GearRatios& g) {
  std::vector<GiNaC::ex> exact;
  for (const NamedGear& gear : t.gears) {
    const EngagementRatio& e = engagement_of(g, t, gear);
    exact.push_back(1 / e.exact);
    g.gears.push_back({gear.name, gear.engaged, (1 / *e.ratio).normal(), to_double(exact.back()), std::nullopt});
  }
  // Rounding keeps a sign, and the gears with the largest and smallest rounded i have the largest
  // and smallest exact i (or one equal to it): the steps and the spread are computed exactly.
  auto forward = [&](std::size_t k) { return g.gears[k].value > 0; };
  std::optional<std::size_t> lowest, highest;
  int forward_gears = 0;
  for (std::size_t k = 0; k < exact.size(); ++k) {
    if (!forward(k)) continue;
    ++forward_gears;
    if (k + 1 < exact.size() && forward(k + 1)) g.gears[k].step = to_double(exact[k] / exact[k + 1]);
    if (!lowest || g.gears[k].value < g.gears[*lowest].value) lowest = k;
    if (!highest || g.gears[k].value > g.gears[*highest].value) highest = k;
  }
  if (forward_gears >= 2) g.spread = to_double(exact[*highest] / exact[*lowest]);
}

}  // namespace

GearRatios gear_ratios(const Derivation& d, const std::string& input, const std::string& output,
                       const SourceLocation& where) {
  const Topology& t = d.topology;
  GearRatios g;
  g.model = t.name;
  g.input = input;
  g.output = output;
  const int in = body_named(t, input, "--input", where);
  const int out = body_named(t, output, "--output", where);
  if (in == out) throw InputError(where, fmt::format("--input and --output are both '{}'; give two bodies", input));
  const int n = static_cast<int>(t.bodies.size());
  const Eigen::MatrixXd Rn = evaluate_matrix(d.elastic.R, d.values);
  const int gear_rank = numeric_rank(Rn);
  g.gear_freedoms = n - gear_rank;
  const GiNaC::exmap geometry = geometry_substitutions(d.radius, d.symbols);
  const GiNaC::exmap teeth = tooth_count_substitutions(t, d.symbols);
  // One rotation sense for both: omega times its arrow.
  const int sense = t.bodies[in].arrow * t.bodies[out].arrow;

  const int m = static_cast<int>(t.friction_elements.size());
  for (int size = 0; size <= m; ++size) {
    std::vector<std::vector<int>> sets;
    std::vector<int> current;
    subsets_of_size(m, size, 0, current, sets);
    for (const std::vector<int>& S : sets) {
      const GiNaC::matrix E = engagement_rows(t, S);
      const Eigen::MatrixXd Cn = stacked_for_rank(Rn, E);
      const int rank = numeric_rank(Cn);
      if (rank != gear_rank + size) {
        ++g.redundant_sets;
        continue;
      }
      EngagementRatio r;
      r.engaged = S;
      r.freedoms = n - rank;
      if (r.freedoms == 0) r.status = EngagementStatus::locked;
      else if (r.freedoms > 1) r.status = EngagementStatus::free;
      else {
        std::vector<int> elim;
        for (int b = 0; b < n; ++b)
          if (b != in) elim.push_back(b);
        if (numeric_rank(columns(Cn, elim)) < n - 1) {
          r.status = EngagementStatus::input_held;
        } else {
          const GiNaC::matrix C = stacked(d.elastic.R, E);
          const std::vector<int> rows = independent_rows(Cn, elim);
          const GiNaC::ex closed = (sense * kernel_basis(C, rows, {in}, elim)(out, 0)).subs(geometry).normal();
          const GiNaC::ex value = exact_value(closed, d.values);
          // The same ratio from R at the file's radii, which meet the geometry relations to the
          // parser's 1e-9 (relative) and not exactly: a check of the closed form's algebra, which
          // a wrong sign or a lost term would fail by far more than that.
          const double direct = to_double(sense * kernel_basis(exact_matrix(C, d.values), rows, {in}, elim)(out, 0));
          // Written in tooth counts when the model gives them, as the reports write the rigid model;
          // its value is then the tooth ratio itself, not its value at pitch radii rounded to doubles.
          r.ratio = teeth.empty() ? closed : closed.subs(teeth).normal();
          const std::optional<GiNaC::ex> in_teeth = teeth.empty() ? std::nullopt : in_tooth_numbers(*r.ratio, t);
          r.exact = in_teeth ? *in_teeth : value;
          r.value = to_double(r.exact);
          if (!(std::abs(r.value - direct) <= 1e-7 * std::max(1.0, std::abs(direct))))
            throw std::logic_error(fmt::format("the closed-form ratio with {} engaged, {}, disagrees with R at the "
                                               "model's values, {}", engaged_names(t, S, ","), r.value, direct));
          r.status = value.is_zero() ? EngagementStatus::output_held : EngagementStatus::ratio;
          if (r.status == EngagementStatus::ratio) r.one_way = one_way_holds(t, Rn, S, in, out);
        }
      }
      g.engagements.push_back(std::move(r));
    }
  }
  name_gears(t, g);
  return g;
}

}  // namespace pogear
