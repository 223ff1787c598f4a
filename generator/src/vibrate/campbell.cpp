// The operating line is solved exactly (rationals at the model's values); frequencies are doubles.
#include "vibrate/campbell.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "common/json_text.hpp"
#include "common/latex_layout.hpp"
#include "common/gnuplot.hpp"
#include "common/printer.hpp"

namespace pogear {
namespace {

// Every body's speed per unit input speed: the one motion with R omega = 0, the engaged elements'
// slips 0, the held bodies at rest, and omega_input = 1.
Eigen::VectorXd operating_line(const Derivation& d, const GiNaC::exmap& values, const std::vector<int>& engaged,
                               int input, const std::vector<int>& held) {
  const Topology& t = d.topology;
  const unsigned n = t.bodies.size();
  const GiNaC::matrix R = exact_matrix(d.elastic.R, values);
  const GiNaC::matrix E = engagement_rows(t, engaged);
  GiNaC::matrix C(R.rows() + E.rows() + held.size(), n);
  for (unsigned i = 0; i < R.rows(); ++i)
    for (unsigned j = 0; j < n; ++j) C(i, j) = R(i, j);
  for (unsigned i = 0; i < E.rows(); ++i)
    for (unsigned j = 0; j < n; ++j) C(R.rows() + i, j) = E(i, j);
  for (std::size_t h = 0; h < held.size(); ++h) C(R.rows() + E.rows() + h, held[h]) = 1;
  const unsigned freedom = n - C.rank();
  std::vector<std::string> names;
  for (int h : held) names.push_back(t.bodies[h].name);
  const std::string line = fmt::format("with {}{}", names.empty() ? "no body held" : joined(names) + " held",
                                       engaged.empty() ? "" : " and the engaged elements stuck");
  if (freedom != 1)
    throw std::domain_error(fmt::format(
        "a Campbell diagram follows one operating line, but {} the gear has {} degrees of freedom; {}", line, freedom,
        freedom == 0 ? "hold fewer bodies" : "hold more bodies (--hold) or engage brakes or clutches (--engaged)"));
  // [C; e_input] omega = [0; 1] has one solution when the input turns on the line: solved from
  // the normal equations, exactly.
  GiNaC::matrix A(C.rows() + 1, n), b(C.rows() + 1, 1);
  for (unsigned i = 0; i < C.rows(); ++i)
    for (unsigned j = 0; j < n; ++j) A(i, j) = C(i, j);
  A(C.rows(), input) = 1;
  b(C.rows(), 0) = 1;
  if (A.rank() != n)
    throw std::domain_error(fmt::format("on the operating line {} the input {} stands still; choose another input "
                                        "or other held bodies", line, t.bodies[input].name));
  const GiNaC::matrix At = A.transpose();
  const GiNaC::matrix omega = exact_solve(exact_product(At, A), exact_product(At, b));
  Eigen::VectorXd speeds(n);
  for (unsigned k = 0; k < n; ++k) speeds(k) = to_double(omega(k, 0));
  return speeds;
}

// The frame in which both axes of a mesh stand still: a planet's carrier, else the housing (-1).
int mesh_frame(const Topology& t, const Mesh& m) {
  for (int b : {m.first.body, m.second.body})
    if (body(t, b).axis == AxisKind::carried) return find_body(t, body(t, b).carrier);  // -1: a fixed carrier
  return -1;
}

}  // namespace

std::vector<std::pair<double, std::vector<std::string>>> mesh_line_groups(const CampbellDiagram& c) {
  std::vector<std::pair<double, std::vector<std::string>>> groups;
  for (const MeshLine& m : c.meshes) {
    auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return std::abs(g.first - m.hz_per_rpm) <= 1e-12 * std::max(g.first, m.hz_per_rpm);
    });
    if (same == groups.end()) groups.emplace_back(m.hz_per_rpm, std::vector<std::string>{m.mesh});
    else same->second.push_back(m.mesh);
  }
  return groups;
}

CampbellDiagram campbell_diagram(const Derivation& d, const GiNaC::exmap& values, const VibrationModes& modes,
                                 const std::vector<int>& engaged, int input, const std::vector<int>& held,
                                 double max_rpm, int harmonics) {
  const Topology& t = d.topology;
  CampbellDiagram c;
  c.model = t.name;
  c.input = t.bodies[input].name;
  for (int h : held) c.held.push_back(t.bodies[h].name);
  c.engaged = modes.engaged;
  c.bodies = modes.bodies;
  c.harmonics = harmonics;
  c.speeds = operating_line(d, values, engaged, input, held);
  for (const VibrationMode& mode : modes.modes) {
    if (mode.kind == ModeKind::rigid) continue;
    if (c.natural_hz.empty() || mode.frequency_hz > c.natural_hz.back() * (1 + degenerate_tolerance))
      c.natural_hz.push_back(mode.frequency_hz);
  }
  for (const Mesh& m : t.meshes) {
    if (m.shaft) continue;  // no teeth, no mesh frequency
    const int frame = mesh_frame(t, m);
    MeshLine line;
    for (const WheelRef w : {m.first, m.second}) {
      if (wheel(t, w).teeth == 0) continue;
      line.mesh = m.name;
      line.wheel = wheel(t, w).name;
      line.teeth = wheel(t, w).teeth;
      line.frame = frame < 0 ? "housing" : t.bodies[frame].name;
      // Z |omega_w - omega_F| / 2 pi per rad/s of input; an rpm is 2 pi / 60 rad/s.
      const double speed = is_grounded(t, w.body) ? 0.0 : c.speeds(w.body);
      const double relative = speed - (frame < 0 ? 0.0 : c.speeds(frame));
      line.hz_per_rpm = line.teeth * std::abs(relative) / 60;
      break;
    }
    if (line.teeth == 0) c.without_teeth.push_back(m.name);
    else c.meshes.push_back(line);
  }
  if (c.meshes.empty())
    throw std::domain_error("no mesh has a tooth count, so no mesh frequency is known; give the wheels' teeth "
                            "(docs/model-format.md, \"Tooth counts and modules\")");
  double slowest = 0;
  for (const MeshLine& line : c.meshes)
    if (line.hz_per_rpm > 0 && (slowest == 0 || line.hz_per_rpm < slowest)) slowest = line.hz_per_rpm;
  if (slowest == 0)
    throw std::domain_error(fmt::format("on this operating line every toothed wheel turns with its frame (the gear "
                                        "turns as one block), so no tooth passes another; hold another body"));
  if (max_rpm <= 0) {
    if (c.natural_hz.empty())
      throw std::domain_error("the gear has no elastic mode on this line to scale the speed axis by; give --to");
    max_rpm = 1.2 * c.natural_hz.back() / slowest;
  }
  c.max_rpm = max_rpm;
  for (const auto& [hz_per_rpm, names] : mesh_line_groups(c))
    for (int h = 1; h <= harmonics; ++h)
      for (double f : c.natural_hz) {
        if (hz_per_rpm <= 0) continue;
        const double rpm = f / (h * hz_per_rpm);
        if (rpm <= max_rpm) c.crossings.push_back({names, h, f, rpm});
      }
  std::stable_sort(c.crossings.begin(), c.crossings.end(),
                   [](const Crossing& a, const Crossing& b) { return a.input_rpm < b.input_rpm; });
  return c;
}

namespace {

std::string line_description(const CampbellDiagram& c) {
  std::string s = fmt::format("input {}", c.input);
  if (!c.held.empty()) s += ", held " + joined(c.held);
  if (!c.engaged.empty()) s += ", engaged " + joined(c.engaged);
  return s;
}

}  // namespace

std::vector<Crossing> listed_crossings(const CampbellDiagram& c) {
  std::vector<Crossing> out;
  for (const Crossing& x : c.crossings)
    if (x.input_rpm >= listed_crossing_fraction * c.max_rpm) out.push_back(x);
  return out;
}

namespace {

// "2 crossings below 80 rpm (1 % of the axis) are not listed", or "".
std::string unlisted_note(const CampbellDiagram& c, std::size_t listed) {
  const std::size_t below = c.crossings.size() - listed;
  if (below == 0) return "";
  return fmt::format("{} crossing{} below {} rpm (1 % of the axis) {} not listed: the gear only passes through such "
                     "speeds, where the meshes excite little",
                     below, below == 1 ? "" : "s", six_digits(listed_crossing_fraction * c.max_rpm),
                     below == 1 ? "is" : "are");
}

}  // namespace

std::string campbell_text(const CampbellDiagram& c) {
  std::string s = fmt::format("\nCampbell diagram ({}; 0 to {} rpm, harmonics 1 to {})\n", line_description(c),
                              six_digits(c.max_rpm), c.harmonics);
  s += "mesh frequencies per input speed (Z |omega_w - omega_frame| / 2 pi):\n";
  for (const MeshLine& m : c.meshes)
    s += fmt::format("  {:<8} {} Hz per rpm  ({} teeth of {}, frame {})\n", m.mesh, six_digits(m.hz_per_rpm), m.teeth, m.wheel,
                     m.frame);
  if (!c.without_teeth.empty()) s += "  without tooth counts (not drawn): " + joined(c.without_teeth) + "\n";
  if (!c.held.empty()) {
    std::vector<std::string> hz;
    for (double f : c.natural_hz) hz.push_back(six_digits(f));
    s += fmt::format("natural frequencies of the gear with {} held [Hz]: {}\n", joined(c.held), joined(hz));
  }
  if (c.crossings.empty()) {
    s += "no harmonic meets a natural frequency below " + six_digits(c.max_rpm) + " rpm\n";
    return s;
  }
  const std::vector<Crossing> listed = listed_crossings(c);
  s += "crossings (input speed at which a harmonic meets a natural frequency):\n";
  s += "  input [rpm]  frequency [Hz]  harmonic  meshes\n";
  for (const Crossing& x : listed)
    s += fmt::format("  {:>11}  {:>14}  {:>8}  {}\n", six_digits(x.input_rpm), six_digits(x.natural_hz), x.harmonic, joined(x.meshes));
  if (const std::string note = unlisted_note(c, listed.size()); !note.empty()) s += "  " + note + "\n";
  return s;
}

std::string campbell_markdown(const CampbellDiagram& c) {
  std::string s = fmt::format("\n## Campbell diagram\n\n{}; 0 to {} rpm, harmonics 1 to {}.\n\n", line_description(c),
                              six_digits(c.max_rpm), c.harmonics);
  s += "| mesh | Hz per rpm | teeth | wheel | frame |\n|---|---|---|---|---|\n";
  for (const MeshLine& m : c.meshes)
    s += fmt::format("| {} | {} | {} | {} | {} |\n", m.mesh, six_digits(m.hz_per_rpm), m.teeth, m.wheel, m.frame);
  if (!c.without_teeth.empty()) s += "\nWithout tooth counts (not drawn): " + joined(c.without_teeth) + ".\n";
  const std::vector<Crossing> listed = listed_crossings(c);
  s += "\n| input [rpm] | frequency [Hz] | mesh | harmonic |\n|---|---|---|---|\n";
  for (const Crossing& x : listed)
    s += fmt::format("| {} | {} | {} | {} |\n", six_digits(x.input_rpm), six_digits(x.natural_hz), joined(x.meshes), x.harmonic);
  if (const std::string note = unlisted_note(c, listed.size()); !note.empty()) s += "\n" + note + ".\n";
  return s;
}

std::string campbell_latex(const CampbellDiagram& c) {
  auto tex = [](const std::string& x) { return latex_text(x); };
  std::string s = "\\section*{Campbell diagram}\n";
  s += fmt::format("Input {}{}{}; 0 to {} rpm, harmonics 1 to {}.\n\n", tex(c.input),
                   c.held.empty() ? "" : ", held " + tex(joined(c.held)),
                   c.engaged.empty() ? "" : ", engaged " + tex(joined(c.engaged)), six_digits(c.max_rpm), c.harmonics);
  // Long tables run over pages, in columns that fit the page.
  const std::vector<std::string> lines_header{"mesh", "Hz per rpm", "teeth", "wheel", "frame"};
  std::vector<std::vector<std::string>> lines;
  for (const MeshLine& m : c.meshes)
    lines.push_back({tex(m.mesh), six_digits(m.hz_per_rpm), fmt::format("{}", m.teeth), tex(m.wheel), tex(m.frame)});
  s += latex_longtable(lines_header, lines, latex_column_widths(lines_header, lines)) + "\n";
  const std::vector<std::string> crossings_header{"input [rpm]", "frequency [Hz]", "mesh", "harmonic"};
  std::vector<std::vector<std::string>> crossings;
  const std::vector<Crossing> listed = listed_crossings(c);
  for (const Crossing& x : listed)
    crossings.push_back({six_digits(x.input_rpm), six_digits(x.natural_hz), tex(joined(x.meshes)), fmt::format("{}", x.harmonic)});
  s += latex_longtable(crossings_header, crossings, latex_column_widths(crossings_header, crossings));
  if (const std::string note = unlisted_note(c, listed.size()); !note.empty()) s += "\n" + tex(note) + ".\n";
  return s;
}

std::string campbell_json_member(const CampbellDiagram& c) {
  auto strings = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + json_string(x);
    return "[" + s + "]";
  };
  std::string s = "\"campbell\": {";
  s += fmt::format("\"input\": {}, \"held\": {}, \"engaged\": {}, \"max_rpm\": {}, \"harmonics\": {},\n",
                   json_string(c.input), strings(c.held), strings(c.engaged), json_number(c.max_rpm), c.harmonics);
  std::string speeds;
  for (std::size_t k = 0; k < c.bodies.size(); ++k)
    speeds += fmt::format("{}{}: {}", k ? ", " : "", json_string(c.bodies[k]), json_number(c.speeds(static_cast<Eigen::Index>(k))));
  s += "  \"speed_per_input\": {" + speeds + "},\n  \"meshes\": [";
  for (std::size_t i = 0; i < c.meshes.size(); ++i) {
    const MeshLine& m = c.meshes[i];
    s += fmt::format("{}{{\"mesh\": {}, \"wheel\": {}, \"teeth\": {}, \"frame\": {}, \"hz_per_rpm\": {}}}", i ? ", " : "",
                     json_string(m.mesh), json_string(m.wheel), m.teeth, json_string(m.frame), json_number(m.hz_per_rpm));
  }
  s += "],\n  \"without_teeth\": " + strings(c.without_teeth) + ",\n  \"crossings\": [";
  for (std::size_t i = 0; i < c.crossings.size(); ++i) {
    const Crossing& x = c.crossings[i];
    s += fmt::format("{}{{\"meshes\": {}, \"harmonic\": {}, \"frequency_hz\": {}, \"input_rpm\": {}}}", i ? ", " : "",
                     strings(x.meshes), x.harmonic, json_number(x.natural_hz), json_number(x.input_rpm));
  }
  return s + "]}";
}

std::string campbell_script(const CampbellDiagram& c) {
  const double top = 1.25 * (c.natural_hz.empty() ? c.meshes.front().hz_per_rpm * c.max_rpm : c.natural_hz.back());
  // Every word is pogear's own or a name the model reader checked to be an identifier.
  std::string s;
  s += gnuplot_svg_preamble(900, 600);
  s += fmt::format("set title 'Campbell diagram of {}: {}' noenhanced\n", c.model, line_description(c));
  s += fmt::format("set xlabel 'speed of {} [rpm]' noenhanced\nset ylabel 'frequency [Hz]'\n", c.input);
  s += fmt::format("set xrange [0:{}]\nset yrange [0:{}]\nset samples 400\n", c.max_rpm, top);
  s += "set datafile separator ','\nset grid\nset key inside left top box opaque\nset rmargin 12\n";
  for (double f : c.natural_hz)  // each natural frequency named at the right end of its line
    s += fmt::format("set label '{} Hz' at {},{} left offset 0.5,0 font ',11'\n", six_digits(f), c.max_rpm, f);
  std::vector<std::vector<double>> points;
  for (const Crossing& x : c.crossings) points.push_back({x.input_rpm, x.natural_hz});
  if (!points.empty()) s += gnuplot_datablock("crossings", points);
  s += "plot ";
  bool first = true;
  auto next = [&] {
    if (!first) s += ", \\\n     ";
    first = false;
  };
  for (std::size_t i = 0; i < c.natural_hz.size(); ++i) {
    next();
    s += fmt::format("{} with lines lw 1.5 dt 3 lc rgb '#404040' {}", c.natural_hz[i],
                     i == 0 ? "title 'natural frequencies'" : "notitle");
  }
  const auto groups = mesh_line_groups(c);
  for (std::size_t k = 0; k < groups.size(); ++k)
    for (int h = 1; h <= c.harmonics; ++h) {
      next();
      // One colour per line of meshes, one dash pattern per harmonic.
      s += fmt::format("x*{} with lines lw 2 dt {} lt {} title '{} {}, {}x' noenhanced", h * groups[k].first,
                       std::min(h, 5), k + 1,
                       groups[k].second.size() == 1 ? "mesh" : "meshes", joined(groups[k].second), h);
    }
  if (!points.empty()) {
    next();
    s += "$crossings using 1:2 with points pt 7 ps 0.9 lc rgb 'black' title 'crossings'";
  }
  return s + "\n";
}

}  // namespace pogear
