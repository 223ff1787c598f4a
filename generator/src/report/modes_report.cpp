// Numbers are printed to 6 significant digits in text, Markdown and LaTeX (the eigenproblem is
// accurate to ~8, vibration_modes.hpp) and in shortest round-trip form in JSON.
#include "report/modes_report.hpp"

#include <fmt/format.h>

#include "common/json_text.hpp"
#include "common/latex_layout.hpp"
#include "common/printer.hpp"

namespace pogear {
namespace {

std::string zeta_text(const VibrationMode& m) { return m.damping_ratio ? six_digits(*m.damping_ratio) : "-"; }

// Entries of a per-body or per-mesh vector as "name value" pairs.
std::string named_values(const std::vector<std::string>& names, const Eigen::VectorXd& v) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i)
    s += fmt::format("{}{} {}", i ? ", " : "", names[i], six_digits(std::abs(v(i)) < 1e-12 ? 0.0 : v(i)));
  return s;
}

std::string summary(const VibrationModes& m) {
  int rigid = 0;
  for (const VibrationMode& mode : m.modes) rigid += mode.kind == ModeKind::rigid;
  const int elastic = static_cast<int>(m.modes.size()) - rigid;
  std::string s = fmt::format("{} rigid-body mode{}, {} elastic mode{}", rigid, rigid == 1 ? "" : "s", elastic,
                              elastic == 1 ? "" : "s");
  if (elastic > 0) {
    s += fmt::format("; lowest natural frequency {} Hz: the rigid model holds for inputs well below it",
                     six_digits(m.modes[rigid].frequency_hz));
  }
  return s;
}

// det(R^T K R - lambda J) / lambda^(n - rank R), highest power first, each coefficient printed on
// its own: one printed sum would order the powers of lambda among the parameters' terms.
std::string characteristic_polynomial(const VibrationModes& m, Notation notation) {
  const std::string lambda = notation == Notation::latex ? "\\lambda" : "lambda";
  const std::string times = notation == Notation::latex ? " " : "*";
  std::string s;
  for (std::size_t k = m.characteristic.size(); k-- > 0;) {
    const std::string c = print_expression(m.characteristic[k], notation);
    const std::string open = notation == Notation::latex ? "\\left(" : "(", close = notation == Notation::latex ? "\\right)" : ")";
    if (!s.empty()) s += notation == Notation::ginac ? "+" : " + ";
    s += open + c + close;
    if (k >= 1) s += times + lambda;
    if (k >= 2) s += notation == Notation::latex ? fmt::format("^{{{}}}", k) : fmt::format("^{}", k);
  }
  return s;
}

int rigid_count(const VibrationModes& m) {
  return static_cast<int>(m.modes.size() - m.characteristic.size() + 1);
}

// With brakes or clutches stuck, what the equations' R and J are; empty with all open.
std::string engaged_line(const VibrationModes& m) {
  if (m.engaged.empty()) return "";
  std::string names;
  for (const std::string& e : m.engaged) names += (names.empty() ? "" : ", ") + e;
  return "engaged (stuck): " + names + "; bodies they tie move as one and bodies a brake holds are at rest, so R and "
         "J are those of the groups of bodies that move";
}

std::string damping_line(const VibrationModes& m, const char* first_word = "damping") {
  std::string s = std::string(first_word) + " ratios of: " + m.damping;
  if (!m.damping_note.empty()) s += "; " + m.damping_note;
  return s;
}

}  // namespace

std::string modes_text(const VibrationModes& m) {
  std::string s = "vibration modes of " + m.model + " (R^T K R phi = lambda J phi, f = sqrt(lambda)/(2 pi))\n";
  if (!m.engaged.empty()) s += engaged_line(m) + "\n";
  s += summary(m) + "\n" + damping_line(m) + "\n\n";
  s += fmt::format("{:>4}  {:>14}  {:>13}  {:>12}  {}\n", "mode", "frequency [Hz]", "damping ratio", "multiplicity",
                   "kind");
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    s += fmt::format("{:>4}  {:>14}  {:>13}  {:>12}  {}\n", i + 1, six_digits(mode.frequency_hz), zeta_text(mode),
                     mode.multiplicity, mode_kind_name(mode.kind));
  }
  if (!m.damping_note.empty() && !m.damped.empty()) {
    s += "\ndamped modes (eigenvalues s of M): frequency |s|/2pi [Hz], damping ratio -Re s/|s|\n";
    for (const DampedMode& dm : m.damped) s += fmt::format("  {:>14}  {:>13}\n", six_digits(dm.frequency_hz), six_digits(dm.damping_ratio));
  }
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    s += fmt::format("\nmode {}: {} Hz, {}\n", i + 1, six_digits(mode.frequency_hz), mode_kind_name(mode.kind));
    s += "  shape           " + named_values(m.bodies, mode.shape) + "\n";
    if (mode.strain_energy.size())
      s += "  strain energy   " + named_values(m.meshes, mode.strain_energy) + "\n";
    s += "  kinetic energy  " + named_values(m.bodies, mode.kinetic_energy) + "\n";
  }
  if (!m.characteristic.empty()) {
    s += fmt::format("\ndet(R^T K R - lambda J) = lambda^{} p(lambda), p(lambda) = {}\n", rigid_count(m),
                     characteristic_polynomial(m, Notation::text));
    for (std::size_t k = 0; k < m.closed_form.size(); ++k)
      s += fmt::format("lambda_{} = {}\n", k + 1, print_expression(m.closed_form[k], Notation::text));
  }
  return s;
}

std::string modes_markdown(const VibrationModes& m) {
  std::string s = "# Vibration modes of " + m.model + "\n\n";
  s += "$R^T K R \\varphi = \\lambda J \\varphi$, $f = \\sqrt{\\lambda} / 2\\pi$. " + summary(m) + ". " +
       damping_line(m, "Damping") + ".\n\n";
  if (!m.engaged.empty()) s += "Brakes and clutches " + engaged_line(m) + ".\n\n";
  s += "| mode | frequency [Hz] | damping ratio | multiplicity | kind |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    s += fmt::format("| {} | {} | {} | {} | {} |\n", i + 1, six_digits(mode.frequency_hz), zeta_text(mode), mode.multiplicity,
                     mode_kind_name(mode.kind));
  }
  if (!m.damping_note.empty() && !m.damped.empty()) {
    s += "\nDamped modes (eigenvalues s of M):\n\n| frequency \\|s\\|/2π [Hz] | damping ratio −Re s/\\|s\\| |\n|---|---|\n";
    for (const DampedMode& dm : m.damped) s += fmt::format("| {} | {} |\n", six_digits(dm.frequency_hz), six_digits(dm.damping_ratio));
  }
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    s += fmt::format("\n## Mode {}: {} Hz, {}\n\n", i + 1, six_digits(mode.frequency_hz), mode_kind_name(mode.kind));
    s += "- shape: " + named_values(m.bodies, mode.shape) + "\n";
    if (mode.strain_energy.size()) s += "- strain energy: " + named_values(m.meshes, mode.strain_energy) + "\n";
    s += "- kinetic energy: " + named_values(m.bodies, mode.kinetic_energy) + "\n";
  }
  if (!m.characteristic.empty()) {
    s += fmt::format("\n## Closed form\n\n$$\n\\det(R^T K R - \\lambda J) = \\lambda^{{{}}} \\left({}\\right)\n$$\n\n",
                     rigid_count(m), characteristic_polynomial(m, Notation::latex));
    for (std::size_t k = 0; k < m.closed_form.size(); ++k)
      s += fmt::format("$$\n\\lambda_{{{}}} = {}\n$$\n\n", k + 1, print_expression(m.closed_form[k], Notation::latex));
  }
  return s;
}

std::string modes_latex(const VibrationModes& m, const std::string& extra) {
  std::string s = "% Generated by pogear modes. Compile with pdflatex.\n" + latex_preamble();
  s += "\\section*{Vibration modes of " + latex_text(m.model) + "}\n";
  s += "$R^T K R \\varphi = \\lambda J \\varphi$, $f = \\sqrt{\\lambda} / 2\\pi$. " + latex_text(summary(m)) + ". " +
       latex_text(damping_line(m, "Damping")) + ".\n\n";
  if (!m.engaged.empty()) s += "Brakes and clutches " + latex_text(engaged_line(m)) + ".\n\n";
  const std::vector<std::string> header{"mode", "frequency [Hz]", "damping ratio", "multiplicity", "kind"};
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    rows.push_back({fmt::format("{}", i + 1), six_digits(mode.frequency_hz), zeta_text(mode),
                    fmt::format("{}", mode.multiplicity), latex_text(mode_kind_name(mode.kind))});
  }
  s += latex_longtable(header, rows, latex_column_widths(header, rows));
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    s += fmt::format("\\subsection*{{Mode {}: {} Hz, {}}}\n", i + 1, six_digits(mode.frequency_hz), mode_kind_name(mode.kind));
    s += "Shape: " + latex_text(named_values(m.bodies, mode.shape)) + ".\\\\\n";
    if (mode.strain_energy.size())
      s += "Strain energy: " + latex_text(named_values(m.meshes, mode.strain_energy)) + ".\\\\\n";
    s += "Kinetic energy: " + latex_text(named_values(m.bodies, mode.kinetic_energy)) + ".\n";
  }
  if (!m.characteristic.empty()) {
    s += "\\subsection*{Closed form}\n";
    s += latex_display(fmt::format("\\det(R^T K R - \\lambda J) = \\lambda^{{{}}} \\left({}\\right)", rigid_count(m),
                                   characteristic_polynomial(m, Notation::latex)));
    for (std::size_t k = 0; k < m.closed_form.size(); ++k)
      s += latex_display(fmt::format("\\lambda_{{{}}} = {}", k + 1, print_expression(m.closed_form[k], Notation::latex)));
  }
  return s + extra + "\\end{document}\n";
}

std::string modes_json(const VibrationModes& m, const std::string& extra_member) {
  auto object = [](const std::vector<std::string>& names, const Eigen::VectorXd& v) {
    std::string s = "{";
    for (Eigen::Index i = 0; i < v.size(); ++i)
      s += fmt::format("{}{}: {}", i ? ", " : "", json_string(names[i]), json_number(v(i)));
    return s + "}";
  };
  std::string j = "{\n  \"model\": " + json_string(m.model) + ",\n";
  j += "  \"engaged\": [";
  for (std::size_t k = 0; k < m.engaged.size(); ++k) j += (k ? ", " : "") + json_string(m.engaged[k]);
  j += "],\n";
  j += "  \"damping\": " + json_string(m.damping) + ",\n";
  if (!m.characteristic.empty())
    j += "  \"characteristic_polynomial\": " +
         json_string(characteristic_polynomial(m, Notation::ginac)) + ",\n";
  if (!m.closed_form.empty()) {
    j += "  \"closed_form\": [";
    for (std::size_t k = 0; k < m.closed_form.size(); ++k)
      j += (k ? ", " : "") + json_string(print_expression(m.closed_form[k], Notation::ginac));
    j += "],\n";
  }
  j += "  \"damped_modes\": [";
  for (std::size_t k = 0; k < m.damped.size(); ++k)
    j += fmt::format("{}{{\"frequency_hz\": {}, \"damping_ratio\": {}}}", k ? ", " : "", json_number(m.damped[k].frequency_hz),
                     json_number(m.damped[k].damping_ratio));
  j += "],\n";
  j += "  \"modes\": [\n";
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    const VibrationMode& mode = m.modes[i];
    j += "    {";
    j += "\"frequency_hz\": " + json_number(mode.frequency_hz);
    j += ", \"damping_ratio\": " + (mode.damping_ratio ? json_number(*mode.damping_ratio) : std::string("null"));
    j += fmt::format(", \"multiplicity\": {}", mode.multiplicity);
    j += ", \"kind\": " + json_string(std::string(mode_kind_name(mode.kind)));
    j += ", \"shape\": " + object(m.bodies, mode.shape);
    j += ", \"strain_energy\": " + object(m.meshes, mode.strain_energy);
    j += ", \"kinetic_energy\": " + object(m.bodies, mode.kinetic_energy);
    j += i + 1 < m.modes.size() ? "},\n" : "}\n";
  }
  j += "  ]";
  if (!extra_member.empty()) j += ",\n  " + extra_member;
  return j + "\n}\n";
}

std::string modes_report(const VibrationModes& m, ReportFormat format, const CampbellDiagram* campbell) {
  switch (format) {
    case ReportFormat::json: return modes_json(m, campbell ? campbell_json_member(*campbell) : "");
    case ReportFormat::latex: return modes_latex(m, campbell ? campbell_latex(*campbell) : "");
    case ReportFormat::markdown: return modes_markdown(m) + (campbell ? campbell_markdown(*campbell) : "");
    case ReportFormat::text: break;
  }
  return modes_text(m) + (campbell ? campbell_text(*campbell) : "");
}

}  // namespace pogear
