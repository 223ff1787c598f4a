// See response_report.hpp. The figure's data are numbers and its words pogear's own or validated
// identifiers (scene, body and mesh names), so nothing a user writes becomes gnuplot syntax.
#include "report/response_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "common/output_file.hpp"
#include "common/gnuplot.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

double db(std::complex<double> h) { return 20 * std::log10(std::abs(h)); }

// The phase of the accurate values, unwrapped across them (the others are skipped).
std::vector<double> unwrapped_phase_deg(const std::vector<std::complex<double>>& h, const std::vector<bool>& accurate) {
  std::vector<double> phase(h.size(), 0.0);
  std::optional<double> previous;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (!accurate[k]) continue;
    double p = std::arg(h[k]) * 180 / std::numbers::pi;
    if (previous) p += 360 * std::round((*previous - p) / 360);
    phase[k] = p;
    previous = p;
  }
  return phase;
}

// Rows of the accurate values: f, dB, phase.
std::vector<std::vector<double>> bode_rows(const std::vector<double>& f, const std::vector<std::complex<double>>& h,
                                           const std::vector<bool>& accurate) {
  const std::vector<double> phase = unwrapped_phase_deg(h, accurate);
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (accurate[k]) rows.push_back({f[k], db(h[k]), phase[k]});
  return rows;
}

// Rows for a figure: a figure shows no more than a thousand or so points across, so a longer
// list keeps, of each run of consecutive rows, the lowest and the highest magnitude (peaks and
// notches survive, in order). The CSV keeps every row.
std::vector<std::vector<double>> thinned_for_figure(std::vector<std::vector<double>> rows) {
  constexpr std::size_t most = 2000;
  if (rows.size() <= most) return rows;
  const std::size_t run = (rows.size() + most / 2 - 1) / (most / 2);
  std::vector<std::vector<double>> kept;
  for (std::size_t begin = 0; begin < rows.size(); begin += run) {
    const std::size_t end = std::min(rows.size(), begin + run);
    std::size_t lo = begin, hi = begin;
    for (std::size_t k = begin; k < end; ++k) {
      if (rows[k][1] < rows[lo][1]) lo = k;
      if (rows[k][1] > rows[hi][1]) hi = k;
    }
    kept.push_back(rows[std::min(lo, hi)]);
    if (lo != hi) kept.push_back(rows[std::max(lo, hi)]);
  }
  return kept;
}

bool any_accurate(const std::vector<bool>& accurate) {
  return std::find(accurate.begin(), accurate.end(), true) != accurate.end();
}

std::string bode_script(const std::string& scene_name, const TransferFunction& t) {
  std::string s;
  s += gnuplot_svg_preamble(900, 700);
  s += gnuplot_datablock("elastic", thinned_for_figure(bode_rows(t.frequency_hz, t.value, t.accurate)));
  const bool rigid = !t.rigid.empty() && any_accurate(t.rigid_accurate);
  if (rigid) s += gnuplot_datablock("rigid", thinned_for_figure(bode_rows(t.frequency_hz, t.rigid, t.rigid_accurate)));
  s += "set datafile separator ','\nset logscale x\nset grid\nset key outside right top\nset format x '10^{%L}'\n";
  s += "set multiplot layout 2,1\n";
  s += fmt::format("set title '{}: {} to {}{}' noenhanced\n", scene_name, t.input_name, t.output_name,
                   rigid ? " (rigid model dashed)" : "");
  s += fmt::format("set ylabel '|{}/{}| [dB of {}]' noenhanced\n", t.output_name, t.input_name, t.unit);
  const std::string rigid_mag = !rigid ? "" : ", $rigid using 1:2 with lines dt 2 lw 1.5 lc rgb 'red' title 'rigid'";
  s += "plot $elastic using 1:2 with lines lw 2 title 'magnitude'" + rigid_mag + "\n";
  s += "unset title\nset xlabel 'f [Hz]'\nset ylabel 'phase [deg]'\n";
  const std::string rigid_phase = !rigid ? "" : ", $rigid using 1:3 with lines dt 2 lw 1.5 lc rgb 'red' title 'rigid'";
  s += "plot $elastic using 1:3 with lines lw 2 title 'phase'" + rigid_phase + "\n";
  return s + "unset multiplot\n";
}

}  // namespace

std::string response_csv(const TransferFunction& t) {
  std::string s = fmt::format("f [Hz],magnitude [{}],magnitude [dB],phase [deg]\n", t.unit);
  const std::vector<double> phase = unwrapped_phase_deg(t.value, t.accurate);
  for (std::size_t k = 0; k < t.frequency_hz.size(); ++k) {
    if (t.accurate[k]) s += fmt::format("{},{},{},{}\n", t.frequency_hz[k], std::abs(t.value[k]), db(t.value[k]), phase[k]);
    else s += fmt::format("{},,,\n", t.frequency_hz[k]);
  }
  return s;
}

std::vector<std::string> write_response_files(const std::string& scene_name, const std::vector<TransferFunction>& h,
                                              const std::string& dir) {
  std::vector<std::string> written;
  for (const TransferFunction& t : h) {
    const fs::path csv = fs::path(dir) / fmt::format("{}.response.{}.{}.csv", scene_name, t.input_name, t.output_name);
    write_file_atomically(csv.string(), response_csv(t));
    written.push_back(csv.string());
  }
  const std::optional<std::string> gnuplot = gnuplot_program();
  if (!gnuplot)
    throw std::runtime_error("gnuplot is not installed, so no Bode figure was drawn (the CSV files are written); "
                             "install gnuplot-nox (scripts/install-deps.sh)");
  for (const TransferFunction& t : h) {
    if (!any_accurate(t.accurate)) continue;  // nothing to draw; response_summary says why
    const fs::path svg = fs::path(dir) / fmt::format("{}.response.{}.{}.svg", scene_name, t.input_name, t.output_name);
    draw_svg(*gnuplot, bode_script(scene_name, t), svg.string(), "the CSV files are written");
    written.push_back(svg.string());
  }
  return written;
}

std::string response_summary(const std::vector<TransferFunction>& h) {
  std::string s;
  for (const TransferFunction& t : h) {
    s += fmt::format("{} to {} [{}]: ", t.input_name, t.output_name, t.unit);
    const std::size_t written = static_cast<std::size_t>(std::count(t.accurate.begin(), t.accurate.end(), true));
    if (written == 0) {
      s += fmt::format("|H| is zero or below rounding at every frequency ({} does not reach {} measurably); no "
                       "figure\n", t.input_name, t.output_name);
      continue;
    }
    if (t.peaks.empty()) s += "no resonance peak in the range\n";
    else s += fmt::format("{} resonance peak{}\n", t.peaks.size(), t.peaks.size() == 1 ? "" : "s");
    for (const ResonancePeak& p : t.peaks) {
      if (std::isinf(p.magnitude)) {
        s += fmt::format("  {:.6g} Hz: |H| unbounded (a natural frequency, and the scene has no damping)\n",
                         p.frequency_hz);
        continue;
      }
      s += fmt::format("  {:.6g} Hz: |H| = {:.6g} ({:.4g} dB)", p.frequency_hz, p.magnitude, 20 * std::log10(p.magnitude));
      if (p.over_rigid) s += fmt::format(", {:.4g} times the rigid model's", *p.over_rigid);
      s += "\n";
    }
    if (written < t.accurate.size())
      s += fmt::format("  {} of {} frequencies left empty: their value is zero or its rounding bound exceeds {:g} of "
                       "it\n", t.accurate.size() - written, t.accurate.size(), response_accuracy);
  }
  return s;
}

}  // namespace pogear
