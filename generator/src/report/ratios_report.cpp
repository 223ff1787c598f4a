// Ratios are exact values of their closed forms; text, Markdown and LaTeX round them to 6 significant
// digits, JSON gives the shortest form that reads back as the same double.
#include "report/ratios_report.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/json_text.hpp"
#include "common/latex_layout.hpp"
#include "common/printer.hpp"

namespace pogear {
namespace {

std::string engaged_or_none(const Topology& t, const std::vector<int>& engaged, const std::string& separator) {
  return engaged.empty() ? std::string("(none)") : engaged_names(t, engaged, separator);
}

std::string status_text(const EngagementRatio& e) {
  if (e.status == EngagementStatus::free) return fmt::format("free ({} degrees of freedom)", e.freedoms);
  return status_name(e.status);
}

std::string heading(const GearRatios& g) {
  return fmt::format("ratio = omega_{} / omega_{} (output over input, both in one rotation sense: reverse gears are "
                     "negative)", g.output, g.input);
}

std::string footer(const GearRatios& g) {
  std::string s = fmt::format("With nothing engaged the gear has {} degree{} of freedom.", g.gear_freedoms,
                              g.gear_freedoms == 1 ? "" : "s");
  if (g.redundant_sets > 0)
    s += fmt::format(" {} other set{} of elements {} not listed: in each, an element adds no constraint to the others, "
                     "so it moves as the set without that element.",
                     g.redundant_sets, g.redundant_sets == 1 ? "" : "s", g.redundant_sets == 1 ? "is" : "are");
  return s;
}

bool named(const GearRatios& g, const EngagementRatio& e) {
  return std::any_of(g.gears.begin(), g.gears.end(), [&](const NamedGearRatio& n) { return n.engaged == e.engaged; });
}

// What a report lists: the named gears, and every engagement without them or with --all.
bool lists_engagements(const GearRatios& g, bool all) { return all || g.gears.empty(); }

std::string gears_heading(const GearRatios& g) {
  return fmt::format("i = omega_{} / omega_{} (input over output, as gears are quoted: reverse is negative); step: i "
                     "over the next gear's i", g.input, g.output);
}

std::string spread_line(const GearRatios& g) {
  return g.spread ? fmt::format("Spread (largest over smallest forward i): {}.", six_digits(*g.spread)) : std::string();
}

std::string step_text(const NamedGearRatio& n) { return n.step ? six_digits(*n.step) : std::string(); }

// Which way each one-way element of a listed gear holds, a line per element; "" without any.
std::string one_way_lines(const GearRatios& g, const Topology& t, const std::string& bullet, bool all) {
  std::string s;
  for (const EngagementRatio& e : g.engagements) {
    if (!lists_engagements(g, all) && !named(g, e)) continue;
    for (const OneWayHold& h : e.one_way) {
      const std::string& name = t.friction_elements[static_cast<std::size_t>(h.element)].name;
      const std::string set = engaged_names(t, e.engaged, " ");
      s += bullet + (h.drive && h.coast ? fmt::format("{}: {} carries no torque", set, name)
                     : h.drive          ? fmt::format("{}: {} holds in drive and freewheels in coast", set, name)
                                        : fmt::format("{}: {} holds in coast only; in drive it freewheels, and the set "
                                                      "is no gear", set, name)) +
           "\n";
    }
  }
  if (s.empty()) return s;
  return fmt::format("One-way elements (drive: a positive torque on {}, against the load on {}; coast: the load "
                     "driving):\n", g.input, g.output) + s;
}

// Rows of text columns, aligned, two spaces in and two between.
template <std::size_t N>
std::string aligned(const std::vector<std::array<std::string, N>>& rows) {
  std::array<std::size_t, N> width{};
  for (const auto& r : rows)
    for (std::size_t j = 0; j < N; ++j) width[j] = std::max(width[j], r[j].size());
  std::string s;
  for (const auto& r : rows) {
    std::string line;
    for (std::size_t j = 0; j < N; ++j) line += fmt::format("  {:<{}}", r[j], width[j]);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    s += line + "\n";
  }
  return s;
}

std::string named_gears_text(const GearRatios& g, const Topology& t) {
  std::vector<std::array<std::string, 5>> rows{{"gear", "engaged", "i", "value", "step"}};
  for (const NamedGearRatio& n : g.gears)
    rows.push_back({n.name, engaged_or_none(t, n.engaged, " "),
                    print_expression(n.i, Notation::text), six_digits(n.value), step_text(n)});
  const std::string spread = spread_line(g);
  return gears_heading(g) + "\n\n" + aligned(rows) + (spread.empty() ? "" : "\n" + spread + "\n");
}

// A table whose third column holds closed forms: each one wider than its column is broken.
std::string latex_ratio_table(const std::vector<std::string>& header, std::vector<std::vector<std::string>> rows,
                              const std::vector<std::string>& ratios) {
  const std::vector<std::size_t> widths = latex_column_widths(header, rows);
  const std::size_t room = widths[2] > 2 ? widths[2] - 2 : 1;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (!ratios[i].empty() && latex_width(ratios[i]) > room)
      rows[i][2] = "$\\displaystyle " + latex_breakable(ratios[i], room) + "$";
  return latex_longtable(header, rows, widths) + "\n";
}

std::string latex_named_gears(const GearRatios& g, const Topology& t) {
  std::string s = fmt::format("Gears as quoted, $i = \\omega_{{{}}} / \\omega_{{{}}}$, input over output: reverse is "
                              "negative; step: $i$ over the next gear's $i$.\n\n",
                              latex_text(g.input), latex_text(g.output));
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> ratios;
  for (const NamedGearRatio& n : g.gears) {
    ratios.push_back(print_expression(n.i, Notation::latex));
    rows.push_back({latex_text(n.name), latex_text(engaged_or_none(t, n.engaged, ", ")),
                    "$\\displaystyle " + ratios.back() + "$", "$" + six_digits(n.value) + "$",
                    n.step ? "$" + step_text(n) + "$" : ""});
  }
  s += latex_ratio_table({"gear", "engaged", "i", "value", "step"}, std::move(rows), ratios);
  const std::string spread = spread_line(g);
  return s + (spread.empty() ? "" : latex_text(spread) + "\n\n");
}

std::string latex_engagements(const GearRatios& g, const Topology& t) {
  std::string s;
  s += fmt::format("Ratio $\\omega_{{{}}} / \\omega_{{{}}}$, output over input, both in one rotation sense: reverse "
                   "gears are negative.\n\n",
                   latex_text(g.output), latex_text(g.input));
  // The columns fit the page (a long table runs over pages); a ratio wider than its column breaks.
  const std::vector<std::string> header{"engaged", "status", "ratio", "value"};
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> ratios;
  for (const EngagementRatio& e : g.engagements) {
    ratios.push_back(e.ratio ? print_expression(*e.ratio, Notation::latex) : "");
    rows.push_back({latex_text(engaged_or_none(t, e.engaged, ", ")), latex_text(status_text(e)),
                    e.ratio ? "$\\displaystyle " + ratios.back() + "$" : "", e.ratio ? "$" + six_digits(e.value) + "$" : ""});
  }
  return s + latex_ratio_table(header, std::move(rows), ratios);
}

// ["C1", "B2"]: the elements' names as a JSON array.
std::string json_element_names(const Topology& t, const std::vector<int>& engaged) {
  std::vector<std::string> names;
  for (const int k : engaged) names.push_back(t.friction_elements[static_cast<std::size_t>(k)].name);
  return json_strings(names);
}

}  // namespace

std::string ratios_text(const GearRatios& g, const Topology& t, bool all) {
  std::string s = fmt::format("Gear ratios of {}: input {}, output {}\n", g.model, g.input, g.output);
  if (!g.gears.empty()) s += named_gears_text(g, t) + "\n";
  const std::string one_way = one_way_lines(g, t, "  ", all);
  if (!lists_engagements(g, all)) return s + (one_way.empty() ? "" : one_way + "\n") + footer(g) + "\n";
  std::vector<std::array<std::string, 4>> rows{{"engaged", "status", "ratio", "value"}};
  for (const EngagementRatio& e : g.engagements)
    rows.push_back({engaged_or_none(t, e.engaged, " "), status_text(e),
                    e.ratio ? print_expression(*e.ratio, Notation::text) : "", e.ratio ? six_digits(e.value) : ""});
  s += heading(g) + "\n\n" + aligned(rows);
  return s + "\n" + (one_way.empty() ? "" : one_way + "\n") + footer(g) + "\n";
}

std::string ratios_markdown(const GearRatios& g, const Topology& t, bool all) {
  std::string s = fmt::format("# Gear ratios of {}\n\n", g.model);
  if (!g.gears.empty()) {
    s += fmt::format("Input `{}`, output `{}`: {}.\n\n", g.input, g.output, gears_heading(g));
    s += "| gear | engaged | i | value | step |\n|---|---|---|---|---|\n";
    for (const NamedGearRatio& n : g.gears)
      s += fmt::format("| {} | {} | `{}` | {} | {} |\n", markdown_text(n.name),
                       markdown_text(engaged_or_none(t, n.engaged, ", ")),
                       print_expression(n.i, Notation::text), six_digits(n.value), step_text(n));
    const std::string spread = spread_line(g);
    s += "\n" + (spread.empty() ? "" : spread + "\n\n");
  }
  const std::string one_way = one_way_lines(g, t, "- ", all);
  if (!lists_engagements(g, all)) return s + (one_way.empty() ? "" : one_way + "\n") + footer(g) + "\n";
  s += fmt::format("Input `{}`, output `{}`: {}.\n\n", g.input, g.output, heading(g));
  s += "| engaged | status | ratio | value |\n|---|---|---|---|\n";
  for (const EngagementRatio& e : g.engagements)
    s += fmt::format("| {} | {} | {} | {} |\n", markdown_text(engaged_or_none(t, e.engaged, ", ")), status_text(e),
                     e.ratio ? fmt::format("`{}`", print_expression(*e.ratio, Notation::text)) : "", e.ratio ? six_digits(e.value) : "");
  return s + "\n" + (one_way.empty() ? "" : one_way + "\n") + footer(g) + "\n";
}

std::string ratios_latex(const GearRatios& g, const Topology& t, bool all) {
  std::string s = "% Generated by pogear ratios. Compile with pdflatex.\n" + latex_preamble();
  s += "\\section*{Gear ratios of " + latex_text(g.model) + "}\n";
  if (!g.gears.empty()) s += latex_named_gears(g, t);
  if (lists_engagements(g, all)) s += latex_engagements(g, t);
  const std::string one_way = one_way_lines(g, t, "", all);
  if (!one_way.empty()) {
    std::vector<std::string> lines;
    for (std::size_t from = 0, end; (end = one_way.find('\n', from)) != std::string::npos; from = end + 1)
      lines.push_back(one_way.substr(from, end - from));
    s += latex_text(lines.front()) + "\n\\begin{itemize}\n";
    for (std::size_t i = 1; i < lines.size(); ++i) s += "\\item " + latex_text(lines[i]) + "\n";
    s += "\\end{itemize}\n\n";
  }
  s += footer(g) + "\n";
  return s + "\\end{document}\n";
}

std::string ratios_json(const GearRatios& g, const Topology& t) {
  std::string j = "{\n  \"model\": " + json_string(g.model) + ",\n";
  j += "  \"input\": " + json_string(g.input) + ",\n";
  j += "  \"output\": " + json_string(g.output) + ",\n";
  j += fmt::format("  \"degrees_of_freedom\": {},\n", g.gear_freedoms);
  j += "  \"engagements\": [\n";
  for (std::size_t i = 0; i < g.engagements.size(); ++i) {
    const EngagementRatio& e = g.engagements[i];
    std::string one_way;
    for (std::size_t k = 0; k < e.one_way.size(); ++k)
      one_way += fmt::format("{}{{\"element\": {}, \"drive\": {}, \"coast\": {}}}", k ? ", " : "",
                             json_string(t.friction_elements[static_cast<std::size_t>(e.one_way[k].element)].name),
                             e.one_way[k].drive, e.one_way[k].coast);
    j += fmt::format("    {{\"engaged\": {}, \"status\": {}, \"degrees_of_freedom\": {}, \"ratio\": {}, \"value\": {}, "
                     "\"one_way\": [{}]}}{}\n",
                     json_element_names(t, e.engaged), json_string(status_name(e.status)), e.freedoms,
                     e.ratio ? json_string(print_expression(*e.ratio, Notation::ginac)) : std::string("null"),
                     e.ratio ? json_number(e.value) : std::string("null"), one_way, i + 1 < g.engagements.size() ? "," : "");
  }
  j += g.gears.empty() ? "  ],\n  \"gears\": [" : "  ],\n  \"gears\": [\n";
  for (std::size_t k = 0; k < g.gears.size(); ++k) {
    const NamedGearRatio& n = g.gears[k];
    j += fmt::format("    {{\"name\": {}, \"engaged\": {}, \"i\": {}, \"value\": {}, \"step\": {}}}{}\n",
                     json_string(n.name), json_element_names(t, n.engaged), json_string(print_expression(n.i, Notation::ginac)), json_number(n.value),
                     n.step ? json_number(*n.step) : std::string("null"), k + 1 < g.gears.size() ? "," : "");
  }
  return j + fmt::format("{}],\n  \"spread\": {}\n}}\n", g.gears.empty() ? "" : "  ",
                         g.spread ? json_number(*g.spread) : std::string("null"));
}

std::string ratios_report(const GearRatios& g, const Topology& t, ReportFormat format, bool all) {
  switch (format) {
    case ReportFormat::json: return ratios_json(g, t);
    case ReportFormat::latex: return ratios_latex(g, t, all);
    case ReportFormat::markdown: return ratios_markdown(g, t, all);
    case ReportFormat::text: break;
  }
  return ratios_text(g, t, all);
}

}  // namespace pogear
