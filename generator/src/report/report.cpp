// Every expression is printed by print_expression, so reports are identical from run to run.
#include "report/report.hpp"

#include <algorithm>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "common/block_triangular_solve.hpp"
#include "common/exact_algebra.hpp"
#include "common/json_text.hpp"
#include "common/latex_layout.hpp"
#include "derive/force_recovery.hpp"
#include "derive/parameter_table.hpp"
#include "common/printer.hpp"
#include "read/tooth_counts.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// The quantities every report shows, printed once in one notation.
struct Printed {
  std::vector<std::string> velocities, forces, kept, torques;
  std::vector<std::string> geometry;  // "r_c == r_p+r_s1"
  std::vector<std::string> geometry_mesh;
  std::vector<std::string> angled;  // "ps and pl of carrier c: axes 41.99 deg apart (mesh pspl)"
  std::vector<std::string> lumped;  // "p stands for 3 planets (meshes ps, pr)"
  std::vector<std::string> shafts;  // "s joins a and b (torque T_s)"
  bool teeth = false;               // Q1, L1, A1 in tooth counts
  std::vector<std::vector<std::string>> R, Q1, L1, A1, B1;
  std::vector<std::pair<std::string, std::string>> closed_form;
  std::vector<std::string> force_recovery;
  std::vector<std::string> reactions;  // what force_recovery gives: F_<mesh>..., T_<element>...
  std::vector<std::string> engaged;
  std::vector<std::vector<std::string>> E;  // rows of the engaged elements under R
  std::vector<std::string> fixed, holding;  // T_<fixed body> and the housing's torque on it
};

std::vector<std::vector<std::string>> print_matrix(const GiNaC::matrix& m, Notation n) {
  std::vector<std::vector<std::string>> out(m.rows());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out[i].push_back(print_expression(m(i, j), n));
  return out;
}

// The rigid model as the reports print it: with toothed wheels, each pitch radius written m Z / 2 and
// each other length the geometry fixes (axis distances, radii left out) through its relation, so that ratios read in tooth counts (the module
// cancels within a set of meshing wheels); L1 and A1 are rebuilt from that Q1 as the reduction builds
// them. Without teeth, the derivation's own matrices.
struct RigidForms {
  GiNaC::matrix Q1, L1, A1;
  bool in_teeth = false;
};

RigidForms rigid_forms(const Derivation& d) {
  const GiNaC::exmap teeth = tooth_count_substitutions(d.topology, d.symbols);
  if (teeth.empty() || d.rigid.L1.rows() != d.rigid.Q1.cols()) return {d.rigid.Q1, d.rigid.L1, d.rigid.A1, false};
  // Every relation whose left side is no pitch radius: axis distances, radii the geometry gives.
  GiNaC::exmap distances;
  for (const auto& g : d.radius.relations)
    if (!teeth.count(parameter_symbol(d.symbols, g.parameter))) distances[parameter_symbol(d.symbols, g.parameter)] = g.rhs;
  RigidForms f;
  f.in_teeth = true;
  f.Q1 = GiNaC::matrix(d.rigid.Q1.rows(), d.rigid.Q1.cols());
  for (unsigned i = 0; i < f.Q1.rows(); ++i)
    for (unsigned j = 0; j < f.Q1.cols(); ++j) f.Q1(i, j) = d.rigid.Q1(i, j).subs(distances).subs(teeth).normal();
  const unsigned k = f.Q1.cols();
  f.L1 = f.A1 = GiNaC::matrix(k, k);
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = i; j < k; ++j) {
      GiNaC::exvector l, a;
      for (unsigned b = 0; b < f.Q1.rows(); ++b) {
        const GiNaC::ex q = normal_product(f.Q1(b, i), f.Q1(b, j));
        if (q.is_zero()) continue;
        l.push_back(d.elastic.J(b, b) * q);
        a.push_back(-d.elastic.B_J(b, b) * q);
      }
      f.L1(i, j) = f.L1(j, i) = GiNaC::add(l);
      f.A1(i, j) = f.A1(j, i) = GiNaC::add(a);
    }
  return f;
}

Printed print_all(const Derivation& d, Notation n) {
  Printed p;
  auto name = [&](const std::string& x) { return n == Notation::latex ? latex_symbol(x) : x; };
  for (const auto& v : d.elastic.velocities) p.velocities.push_back(name(v));
  for (const auto& f : d.elastic.forces) p.forces.push_back(name(f));
  for (const auto& t : d.elastic.torques) p.torques.push_back(name(t));
  for (int k : d.rigid.kept) p.kept.push_back(name(d.elastic.velocities[k]));
  for (const auto& g : d.radius.relations) {
    p.geometry.push_back(print_expression(parameter_symbol(d.symbols, g.parameter) == g.rhs, n));
    p.geometry_mesh.push_back(d.topology.meshes[g.mesh].name);
  }
  // Names in running text (symbols above are in mathematics).
  auto text = [&](const std::string& x) { return n == Notation::latex ? latex_text(x) : x; };
  for (const AngledMesh& a : d.radius.angled) {
    const Mesh& m = d.topology.meshes[a.mesh];
    const Body& first = d.topology.bodies[m.first.body];
    p.angled.push_back(fmt::format("{} and {} of carrier {}: axes {:.2f} deg apart (mesh {})", text(first.name),
                                   text(d.topology.bodies[m.second.body].name), text(first.carrier),
                                   a.angle * 180 / std::numbers::pi, text(m.name)));
  }
  for (const Body& b : d.topology.bodies) {
    if (b.count == 1) continue;
    std::vector<std::string> meshes;
    for (const Mesh& m : d.topology.meshes)
      if (&body(d.topology, m.first.body) == &b || &body(d.topology, m.second.body) == &b) meshes.push_back(text(m.name));
    p.lumped.push_back(fmt::format("{} stands for {} planets (meshes {})", text(b.name), b.count, joined(meshes)));
  }
  for (std::size_t i = 0; i < d.topology.meshes.size(); ++i)
    if (const Mesh& m = d.topology.meshes[i]; m.shaft)
      p.shafts.push_back(fmt::format("{} joins {} and {} (torque {})", text(m.name), text(body(d.topology, m.first.body).name),
                                     text(body(d.topology, m.second.body).name), text(d.elastic.forces[i])));
  p.R = print_matrix(d.elastic.R, n);
  const RigidForms rigid = rigid_forms(d);
  p.teeth = rigid.in_teeth;
  p.Q1 = print_matrix(rigid.Q1, n);
  p.L1 = print_matrix(rigid.L1, n);
  p.A1 = print_matrix(rigid.A1, n);
  p.B1 = print_matrix(rigid.Q1.transpose(), n);
  if (d.rigid.kept.size() == 2 && rigid.L1.rows() == 2) {
    auto at = [&](const GiNaC::matrix& m, int i, int j) { return print_expression(m(i, j), n); };
    p.closed_form = {{"J1", at(rigid.L1, 0, 0)}, {"J2", at(rigid.L1, 1, 1)}, {"J3", at(rigid.L1, 0, 1)},
                     {"b1", at(rigid.A1, 0, 0)}, {"b2", at(rigid.A1, 1, 1)}, {"b3", at(rigid.A1, 0, 1)}};
  }
  // The split of redundant meshes has exact weights, long fractions of the parameter values: they
  // print as decimals, each correctly rounded.
  // A lumped planet's meshes carry its planets' sum; the reports give one planet's share.
  const GiNaC::exset variables = body_variable_symbols(d.symbols);
  for (std::size_t i = 0; i < d.rigid.force_recovery.size(); ++i) {
    const int count = i < d.topology.meshes.size() ? mesh_count(d.topology, d.topology.meshes[i]) : 1;
    const GiNaC::ex f = (d.rigid.force_recovery[i] / count).expand();
    p.force_recovery.push_back(print_expression(d.rigid.redundant_meshes ? f.evalf() : f, n, variables));
  }
  for (const auto& r : d.rigid.reactions) p.reactions.push_back(name(r));
  const std::vector<GiNaC::ex> holding = fixed_body_torques(d.topology, d.radius.fixed_columns, d.rigid.force_recovery);
  for (std::size_t k = 0; k < holding.size(); ++k) {
    p.fixed.push_back(name(fixed_body_torque_name(d.topology.grounded[k].name)));
    p.holding.push_back(print_expression(d.rigid.redundant_meshes ? holding[k].evalf() : holding[k], n, variables));
  }
  for (int k : d.engaged) p.engaged.push_back(d.topology.friction_elements[k].name);
  const unsigned meshes = d.elastic.R.rows();
  for (unsigned i = meshes; i < d.constraints.rows(); ++i) {
    p.E.emplace_back();
    for (unsigned j = 0; j < d.constraints.cols(); ++j) p.E.back().push_back(print_expression(d.constraints(i, j), n));
  }
  return p;
}

std::string force_bodies(const Derivation& d) {
  std::vector<std::string> S;
  for (int b : d.rigid.force_bodies) S.push_back(d.topology.bodies[b].name);
  return joined(S, ", ");
}

std::string title_of(const Derivation& d) {
  return d.topology.title.empty() ? d.topology.name : d.topology.name + ": " + d.topology.title;
}

// One row of an aligned display: `lhs &= rhs`, then a remark (\text{...}) or nothing.
struct AlignedRow {
  std::string lhs, rhs, remark;
};

// LaTeX and Markdown share the mathematics; only the wrapping differs. What is wider than LaTeX's
// line (latex_layout.hpp) is made breakable, or split into one display per entry or row, in both:
// only LaTeX has a page to fit, but the two carry the same mathematics.
struct MathDisplay {
  std::string math_open, math_close, heading_open, heading_close;
  bool latex = false;
  std::string display(const std::string& math) const {
    return latex ? latex_display(math) : math_open + latex_fitted(math) + math_close;
  }
  // `label = [...]`, or where that is wider than the line its nonzero entries one display each.
  std::string matrix(const std::string& label, const std::vector<std::vector<std::string>>& m) const {
    if (!latex_matrix_too_wide(label, m)) return display(label + " = " + latex_matrix(m));
    const MatrixEntries entries = latex_matrix_entries(label, m);
    std::string s = paragraph("$" + label + "$ entry by entry, too wide for the page" +
                              (entries.symmetric ? "; it is symmetric, the entries below the diagonal are those above it" : "") +
                              "; the entries not listed are zero:");
    for (const std::string& e : entries.formulas) s += display(e);
    return s;
  }
  // The rows in one aligned display while it fits the line, else one display per row.
  std::string aligned(const std::vector<AlignedRow>& rows) const {
    std::string block = "\\begin{aligned}\n";
    for (const AlignedRow& r : rows)
      block += "  " + r.lhs + " &= " + r.rhs + (r.remark.empty() ? "" : " && " + r.remark) + " \\\\\n";
    block += "\\end{aligned}";
    if (latex_width(block) <= latex_line_width) return display(block);
    std::string s;
    for (const AlignedRow& r : rows) s += display(r.lhs + " = " + r.rhs + (r.remark.empty() ? "" : " \\quad " + r.remark));
    return s;
  }
  std::string heading(const std::string& text) const { return heading_open + text + heading_close; }
  std::string paragraph(const std::string& text) const { return text + "\n\n"; }
  // A table of plain text cells (names, values as written).
  std::string table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) const {
    return latex ? latex_table(header, rows) : markdown_table(header, rows);
  }
};

// F_<mesh> = ..., T_<element> = ...: the forces and torques the rigid model recovers.
std::vector<AlignedRow> recovery_rows(const Printed& p) {
  std::vector<AlignedRow> rows;
  for (std::size_t i = 0; i < p.reactions.size(); ++i) rows.push_back({p.reactions[i], p.force_recovery[i], ""});
  return rows;
}

std::string math_body(const Derivation& d, const Diagnostics& diagnostics, const MathDisplay& w) {
  const Printed p = print_all(d, Notation::latex);
  const std::size_t n = p.velocities.size();
  std::string s;
  s += w.heading("Variables");
  s += w.display("\\boldsymbol{\\omega} = " + latex_vector(p.velocities) + ", \\quad \\boldsymbol{\\tau} = " +
                 latex_vector(p.torques) + ", \\quad \\mathbf{F} = " + latex_vector(p.forces));
  s += w.heading("Radius matrix");
  s += w.matrix("\\mathbf{R}", p.R);
  if (!p.geometry.empty()) {
    s += w.paragraph("Geometry relations of the layout, each from the contact of one mesh:");
    std::vector<AlignedRow> rows;
    for (std::size_t i = 0; i < p.geometry.size(); ++i) {
      const std::string& rel = p.geometry[i];
      const auto eq = rel.find(" = ");
      rows.push_back({rel.substr(0, eq), rel.substr(eq + 3), "\\text{(mesh " + latex_text(p.geometry_mesh[i]) + ")}"});
    }
    s += w.aligned(rows);
  }
  if (!p.angled.empty()) {
    std::string a = "Pinions meshing at an angle, each such row taken in the carrier's frame:";
    for (const auto& line : p.angled) a += " " + line + ";";
    a.back() = '.';
    s += w.paragraph(a);
  }
  if (!p.lumped.empty())
    s += w.paragraph("Lumped planets, each body standing for identical planets that share the load equally: " +
                     joined(p.lumped, "; ") + ". The model multiplies their inertia and friction, and their meshes' "
                     "stiffness and damping, by the count; the mesh forces below are one planet's.");
  if (!p.shafts.empty())
    s += w.paragraph("Shafts, torsional springs and dampers whose rows of R are their twist rates: " +
                     joined(p.shafts, "; ") + ". Their entries of $\\mathbf{F}$ are torques (N m), of $\\mathbf{K}$ and "
                     "$\\mathbf{B}_K$ in N m/rad and N m s/rad.");
  s += w.heading("Diagnostics");
  s += w.paragraph("Of the elastic model with every effect, at the model's values:");
  {
    std::string list;
    std::istringstream lines(diagnostics_text(diagnostics, ""));
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) list += w.latex ? latex_text(line) + "\\\\\n" : "- " + line + "\n";
    s += list + "\n";
  }
  s += w.heading("Elastic model");
  s += w.paragraph(fmt::format("State $\\mathbf{{x}} = [\\boldsymbol{{\\omega}}; \\mathbf{{F}}]$ of size {}, "
                               "$\\mathbf{{L}}\\dot{{\\mathbf{{x}}}} = \\mathbf{{A}}\\mathbf{{x}} + \\mathbf{{B}}\\boldsymbol{{\\tau}}$ with",
                               n + p.forces.size()));
  s += w.display("\\mathbf{L} = \\begin{bmatrix} \\mathbf{J} & 0 \\\\ 0 & \\mathbf{K}^{-1} \\end{bmatrix}, \\quad "
                 "\\mathbf{A} = \\begin{bmatrix} -\\mathbf{B}_J - \\mathbf{R}^{\\mathsf{T}} \\mathbf{B}_K \\mathbf{R} & "
                 "-\\mathbf{R}^{\\mathsf{T}} \\\\ \\mathbf{R} & 0 \\end{bmatrix}, \\quad "
                 "\\mathbf{B} = \\begin{bmatrix} \\mathbf{I} \\\\ 0 \\end{bmatrix}");
  if (!p.engaged.empty()) {
    s += w.heading("Engaged: " + latex_text(joined(p.engaged, ", ")));
    s += w.paragraph("Each engaged brake or clutch is stuck: its row $\\mathbf{e}_k$ ($\\mathbf{e}_k \\boldsymbol{\\omega}$ "
                     "is its slip) joins the constraints, $\\mathbf{C} = [\\mathbf{R}; \\mathbf{E}_S]$, and the rigid "
                     "model below is that of this mode; its torques $T$ are recovered with the mesh forces.");
    s += w.matrix("\\mathbf{E}_S", p.E);
  }
  s += w.heading("Rigid reduced model");
  s += w.paragraph(fmt::format("Rank of $\\mathbf{{{}}}$: {}; kept velocities $\\mathbf{{x}}_1 = ({})$, "
                               "$\\boldsymbol{{\\omega}} = \\mathbf{{Q}}_1 \\mathbf{{x}}_1$, "
                               "$\\mathbf{{L}}_1 \\dot{{\\mathbf{{x}}}}_1 = \\mathbf{{A}}_1 \\mathbf{{x}}_1 + \\mathbf{{B}}_1 \\boldsymbol{{\\tau}}$.",
                               p.engaged.empty() ? "R" : "C", d.rigid.rank, joined(p.kept, ", ")));
  if (p.teeth)
    s += w.paragraph("In tooth counts: each pitch radius is $r = m Z / 2$, each length the geometry fixes follows "
                     "its relation, and the module $m$ cancels between meshing wheels.");
  s += w.matrix("\\mathbf{Q}_1", p.Q1);
  if (!p.closed_form.empty()) {
    s += w.display("\\mathbf{L}_1 = \\begin{bmatrix} J_{1} & J_{3} \\\\ J_{3} & J_{2} \\end{bmatrix}, \\quad "
                   "\\mathbf{A}_1 = \\begin{bmatrix} b_{1} & b_{3} \\\\ b_{3} & b_{2} \\end{bmatrix}, \\quad "
                   "\\mathbf{B}_1 = \\mathbf{Q}_1^{\\mathsf{T}}");
    std::vector<AlignedRow> rows;
    for (const auto& [name, value] : p.closed_form)
      rows.push_back({fmt::format("{}_{{{}}}", name.substr(0, 1), name.substr(1)), value, ""});
    s += w.aligned(rows);
  } else {
    s += w.matrix("\\mathbf{L}_1", p.L1);
    s += w.matrix("\\mathbf{A}_1", p.A1);
    s += w.display("\\mathbf{B}_1 = \\mathbf{Q}_1^{\\mathsf{T}}");
  }
  s += w.heading(p.engaged.empty() ? "Mesh forces from the rigid model"
                                   : "Mesh forces and engaged torques from the rigid model");
  if (d.rigid.redundant_meshes) {
    s += w.paragraph("$\\mathbf{R}\\mathbf{R}^{\\mathsf{T}}$ is singular (redundant meshes): the rigid model "
                     "splits the load as $\\mathbf{F} = \\mathbf{K}\\mathbf{R}(\\mathbf{R}^{\\mathsf{T}}\\mathbf{K}\\mathbf{R})^{+}\\mathbf{g}$, "
                     "with weights at the model's parameter values:");
    s += w.aligned(recovery_rows(p));
  } else {
    // With elements engaged the constraints are C = [R; E_S] and the torques T join F.
    const std::string C = p.engaged.empty() ? "\\mathbf{R}" : "\\mathbf{C}";
    const std::string lhs = p.engaged.empty() ? "\\mathbf{F}" : "[\\mathbf{F}; \\mathbf{T}]";
    s += w.paragraph("Eq. (8): $" + lhs + " = (" + C + C + "^{\\mathsf{T}})^{-1}" + C + "(\\boldsymbol{\\tau} - "
                     "\\mathbf{J}\\mathbf{Q}_1\\dot{\\mathbf{x}}_1 - \\mathbf{B}_J\\mathbf{Q}_1\\mathbf{x}_1)$. "
                     "On the rigid model the bracket lies in the range of $" + C + "^{\\mathsf{T}}$, so this equals "
                     "$(" + C + "_S^{\\mathsf{T}})^{-1}$ applied to the rows $S$ = (" + latex_text(force_bodies(d)) + ") of the bracket:");
    s += w.aligned(recovery_rows(p));
  }
  if (!p.fixed.empty()) {
    s += w.heading("Fixed bodies");
    s += w.paragraph("Held by the housing ($\\omega = 0$: no column of $\\mathbf{R}$, no state). Each puts on the "
                     "housing the torque the meshes put on it, $T = -a\\,\\mathbf{r}^{\\mathsf{T}}\\mathbf{F}$, "
                     "$\\mathbf{r}$ the column of $\\mathbf{R}$ it would have and $a$ its arrow; as a stuck brake "
                     "holding it would take it, $T$ acts as $-T$ on the body:");
    std::vector<AlignedRow> rows;
    for (std::size_t i = 0; i < p.fixed.size(); ++i) rows.push_back({p.fixed[i], p.holding[i], ""});
    s += w.aligned(rows);
  }
  s += w.heading("Parameters");
  s += w.table({"parameter", "as given", "value (SI)", "defined at"}, parameter_report_rows(d.parameters));
  return s;
}

}  // namespace

std::string report_text(const Derivation& d, const Diagnostics& diagnostics) {
  const Printed p = print_all(d, Notation::text);
  std::string s = "model " + title_of(d) + "\n\n";
  s += "omega = (" + joined(p.velocities, ", ") + ")\n";
  s += "F     = (" + joined(p.forces, ", ") + ")\n\n";
  s += text_matrix("R", p.R) + "\n";
  if (!p.geometry.empty()) {
    s += "geometry relations:\n";
    for (std::size_t i = 0; i < p.geometry.size(); ++i)
      s += fmt::format("  {:<36} (mesh {})\n", p.geometry[i], p.geometry_mesh[i]);
    std::vector<std::string> derived;
    for (const DerivedRadius& r : d.radius.derived) derived.push_back(r.parameter);
    if (!derived.empty()) s += "  computed from them: " + joined(derived, ", ") + "\n";
    s += "\n";
  }
  if (!p.angled.empty()) {
    s += "pinions meshing at an angle (each such row taken in the carrier's frame):\n";
    for (const auto& line : p.angled) s += "  " + line + "\n";
    s += "\n";
  }
  if (!p.lumped.empty()) {
    s += "lumped planets (identical planets sharing the load equally; inertia, friction and the meshes'\n"
         "stiffness and damping count each planet; the mesh forces below are one planet's):\n";
    for (const auto& line : p.lumped) s += "  " + line + "\n";
    s += "\n";
  }
  if (!p.shafts.empty()) {
    s += "shafts (torsional springs and dampers; their rows of R are their twist rates, their entries of F\n"
         "torques [N m], of K and B_K N m/rad and N m s/rad):\n";
    for (const auto& line : p.shafts) s += "  " + line + "\n";
    s += "\n";
  }
  s += "diagnostics (elastic model, every effect, at the model's values):\n" + diagnostics_text(diagnostics, "  ") + "\n";
  if (!p.engaged.empty()) {
    s += "engaged: " + joined(p.engaged, ", ") + ", stuck: their rows E_S (E_S omega is each one's slip) join R, and\n"
         "the rigid model below is that of this mode, C = [R; E_S]; their torques are recovered with the mesh forces\n";
    s += text_matrix("E_S", p.E) + "\n";
  }
  s += fmt::format("rank {} = {}, degrees of freedom = {}, kept x1 = ({})\n\n", p.engaged.empty() ? "R" : "C", d.rigid.rank,
                   d.elastic.velocities.size() - d.rigid.rank, joined(p.kept, ", "));
  if (p.teeth)
    s += "in tooth counts: each pitch radius is r = m*Z/2, each length the geometry fixes follows its relation,\n"
         "and the module m cancels between meshing wheels\n";
  s += text_matrix("Q1", p.Q1) + "\n";
  if (!p.closed_form.empty()) {
    s += "L1 = [J1 J3; J3 J2], A1 = [b1 b3; b3 b2], B1 = Q1^T\n";
    for (const auto& [name, value] : p.closed_form) s += fmt::format("  {} = {}\n", name, value);
    s += "\n";
  } else {
    s += text_matrix("L1", p.L1) + "\n" + text_matrix("A1", p.A1) + "\nB1 = Q1^T\n\n";
  }
  if (d.rigid.redundant_meshes) {
    s += "mesh forces: R R^T is singular (redundant meshes), so eq. (8) does not apply; the elastic model's\n"
         "limit splits the load by stiffness, F = K R (R^T K R)^+ g, g = tau - J Q1 dx1/dt - B_J Q1 x1\n"
         "(weights at the model's parameter values; domega = d omega/dt):\n";
    for (std::size_t i = 0; i < p.reactions.size(); ++i) s += fmt::format("  {} = {}\n", p.reactions[i], p.force_recovery[i]);
  } else {
    std::vector<std::string> S;
    for (int b : d.rigid.force_bodies) S.push_back(d.topology.bodies[b].name);
    if (p.engaged.empty())
      s += "mesh forces, eq. (8): F = (R R^T)^-1 R g, g = tau - J Q1 dx1/dt - B_J Q1 x1, which on the rigid\n"
           "model equals (R_S^T)^-1 g_S for S = (" + joined(S, ", ") + "); domega = d omega/dt:\n";
    else
      s += "mesh forces and engaged torques, eq. (8) with C: [F; T] = (C C^T)^-1 C g, g = tau - J Q1 dx1/dt - B_J Q1 x1,\n"
           "which on the rigid model equals (C_S^T)^-1 g_S for S = (" + joined(S, ", ") + "); domega = d omega/dt:\n";
    for (std::size_t i = 0; i < p.reactions.size(); ++i) s += fmt::format("  {} = {}\n", p.reactions[i], p.force_recovery[i]);
  }
  if (!p.fixed.empty()) {
    s += "\nfixed bodies (held by the housing): the torque each puts on the housing, T = -a (its column of R) . F\n"
         "(a its arrow), as a stuck brake holding it would take it (acting as -T on the body):\n";
    for (std::size_t i = 0; i < p.fixed.size(); ++i) s += fmt::format("  {} = {}\n", p.fixed[i], p.holding[i]);
  }
  return s;
}

std::string report_latex(const Derivation& d, const Diagnostics& diagnostics) {
  const MathDisplay w{"\\[\n", "\n\\]\n", "\\subsection*{", "}\n", true};
  std::string s;
  s += "% Generated by pogear derive from " + latex_text(d.topology.file) + ". Compile with pdflatex.\n";
  s += latex_preamble();
  std::string title = title_of(d);
  s += "\\section*{" + latex_text(title) + "}\n";
  s += math_body(d, diagnostics, w);
  s += "\\end{document}\n";
  return s;
}

std::string report_markdown(const Derivation& d, const Diagnostics& diagnostics) {
  const MathDisplay w{"$$\n", "\n$$\n\n", "## ", "\n\n"};
  return "# " + markdown_text(title_of(d)) + "\n\n" + math_body(d, diagnostics, w);
}

std::string report_json(const Derivation& d, const Diagnostics& diagnostics) {
  const Printed p = print_all(d, Notation::ginac);
  const GiNaC::exmap& values = d.values;
  std::vector<std::string> names;
  for (int k : d.rigid.kept) names.push_back(d.topology.bodies[k].name);
  const auto diag = [&](const GiNaC::matrix& m) {
    return Eigen::VectorXd(evaluate_matrix(m, values).diagonal());
  };
  std::string j = "{\n";
  j += "  \"model\": " + json_string(d.topology.name) + ",\n";
  j += "  \"velocities\": " + json_strings(p.velocities) + ",\n";
  j += "  \"forces\": " + json_strings(p.forces) + ",\n";
  j += "  \"keep\": " + json_strings(names) + ",\n";
  j += "  \"geometry\": " + json_strings(p.geometry) + ",\n";
  std::vector<std::string> angled;
  for (const AngledMesh& a : d.radius.angled)
    angled.push_back(fmt::format("{{\"mesh\": {}, \"angle_deg\": {}}}", json_string(d.topology.meshes[a.mesh].name),
                                 json_number(a.angle * 180 / std::numbers::pi)));
  j += "  \"angled_pinions\": [" + joined(angled, ", ") + "],\n";
  std::vector<std::string> lumped;
  for (const Body& b : d.topology.bodies)
    if (b.count > 1) lumped.push_back(fmt::format("{{\"body\": {}, \"count\": {}}}", json_string(b.name), b.count));
  j += "  \"lumped_planets\": [" + joined(lumped, ", ") + "],\n";
  std::vector<std::string> shafts;  // in the order of their rows of R, after the meshes
  for (const Mesh& m : d.topology.meshes)
    if (m.shaft)
      shafts.push_back(fmt::format("{{\"shaft\": {}, \"bodies\": [{}, {}], \"stiffness\": {}, \"damping\": {}}}",
                                   json_string(m.name), json_string(body(d.topology, m.first.body).name),
                                   json_string(body(d.topology, m.second.body).name),
                                   json_string(m.stiffness_parameter), json_string(m.damping_parameter)));
  j += "  \"shafts\": [" + joined(shafts, ", ") + "],\n";
  std::vector<std::string> fixed;
  for (const Body& b : d.topology.grounded) fixed.push_back(b.name);
  j += "  \"fixed\": " + json_strings(fixed) + ",\n";
  j += "  \"R\": " + json_string_matrix(p.R, "  ") + ",\n";
  j += "  \"Q1\": " + json_string_matrix(p.Q1, "  ") + ",\n";
  j += "  \"L1\": " + json_string_matrix(p.L1, "  ") + ",\n";
  j += "  \"A1\": " + json_string_matrix(p.A1, "  ") + ",\n";
  j += "  \"B1\": " + json_string_matrix(p.B1, "  ") + ",\n";
  if (!p.closed_form.empty()) {
    std::vector<std::string> cf;
    for (const auto& [name, value] : p.closed_form) cf.push_back(json_string(name) + ": " + json_string(value));
    j += "  \"closed_form\": {" + joined(cf, ", ") + "},\n";
  }
  j += "  \"engaged\": " + json_strings(p.engaged) + ",\n";
  j += "  \"E\": " + (p.E.empty() ? std::string("[]") : json_string_matrix(p.E, "  ")) + ",\n";
  j += "  \"reactions\": " + json_strings(p.reactions) + ",\n";
  j += "  \"force_recovery\": " + json_strings(p.force_recovery) + ",\n";
  j += "  \"housing_torques\": {";
  for (std::size_t i = 0; i < p.fixed.size(); ++i)
    j += (i ? ", " : "") + json_string(p.fixed[i]) + ": " + json_string(p.holding[i]);
  j += "},\n";
  j += "  \"numeric\": {\n";
  j += "    \"J\": " + json_numbers(diag(d.elastic.J)) + ",\n";
  j += "    \"b\": " + json_numbers(diag(d.elastic.B_J)) + ",\n";
  j += "    \"K\": " + json_numbers(diag(d.elastic.K)) + ",\n";
  j += "    \"b_K\": " + json_numbers(diag(d.elastic.B_K)) + ",\n";
  j += "    \"R\": " + json_number_matrix(evaluate_matrix(d.elastic.R, values)) + ",\n";
  const RigidValues& rigid = d.rigid_values;
  j += "    \"Q1\": " + json_number_matrix(evaluate_matrix(rigid.Q1, {})) + ",\n";
  j += "    \"L1\": " + json_number_matrix(evaluate_matrix(rigid.L1, {})) + ",\n";
  j += "    \"A1\": " + json_number_matrix(evaluate_matrix(rigid.A1, {})) + "\n";
  j += "  },\n";
  j += "  \"diagnostics\": " + diagnostics_json(diagnostics, "  ") + "\n}\n";
  return j;
}

std::string derive_report(const Derivation& d, const Diagnostics& diagnostics, ReportFormat format) {
  switch (format) {
    case ReportFormat::json: return report_json(d, diagnostics);
    case ReportFormat::latex: return report_latex(d, diagnostics);
    case ReportFormat::markdown: return report_markdown(d, diagnostics);
    case ReportFormat::text: break;
  }
  return report_text(d, diagnostics);
}

}  // namespace pogear
