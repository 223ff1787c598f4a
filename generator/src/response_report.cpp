// See response_report.hpp. The figure's data are numbers and its words pogear's own or validated
// identifiers (scene, body and mesh names), so nothing a user writes becomes gnuplot syntax.
#include "response_report.hpp"

#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "output_file.hpp"
#include "plot.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

double db(std::complex<double> h) { return 20 * std::log10(std::abs(h)); }

std::vector<double> unwrapped_phase_deg(const std::vector<std::complex<double>>& h) {
  std::vector<double> phase;
  for (const auto& v : h) {
    double p = std::arg(v) * 180 / std::numbers::pi;
    if (!phase.empty()) p += 360 * std::round((phase.back() - p) / 360);
    phase.push_back(p);
  }
  return phase;
}

std::string bode_script(const std::string& scene_name, const TransferFunction& t) {
  const std::vector<double> phase = unwrapped_phase_deg(t.value);
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 0; k < t.frequency_hz.size(); ++k) rows.push_back({t.frequency_hz[k], db(t.value[k]), phase[k]});
  std::string s;
  s += "set terminal svg size 900,700 dynamic enhanced font 'Helvetica,13' background rgb 'white'\n";
  s += gnuplot_datablock("elastic", rows);
  if (!t.rigid.empty()) {
    const std::vector<double> rigid_phase = unwrapped_phase_deg(t.rigid);
    std::vector<std::vector<double>> r;
    for (std::size_t k = 0; k < t.frequency_hz.size(); ++k) r.push_back({t.frequency_hz[k], db(t.rigid[k]), rigid_phase[k]});
    s += gnuplot_datablock("rigid", r);
  }
  s += "set datafile separator ','\nset logscale x\nset grid\nset key outside right top\nset format x '10^{%L}'\n";
  s += "set multiplot layout 2,1\n";
  s += fmt::format("set title '{}: {} to {}{}' noenhanced\n", scene_name, t.input_name, t.output_name,
                   t.rigid.empty() ? "" : " (rigid model dashed)");
  s += fmt::format("set ylabel '|{}/{}| [dB of {}]' noenhanced\n", t.output_name, t.input_name, t.unit);
  const std::string rigid_mag = t.rigid.empty() ? "" : ", $rigid using 1:2 with lines dt 2 lw 1.5 lc rgb 'red' title 'rigid'";
  s += "plot $elastic using 1:2 with lines lw 2 title 'magnitude'" + rigid_mag + "\n";
  s += "unset title\nset xlabel 'f [Hz]'\nset ylabel 'phase [deg]'\n";
  const std::string rigid_phase = t.rigid.empty() ? "" : ", $rigid using 1:3 with lines dt 2 lw 1.5 lc rgb 'red' title 'rigid'";
  s += "plot $elastic using 1:3 with lines lw 2 title 'phase'" + rigid_phase + "\n";
  return s + "unset multiplot\n";
}

}  // namespace

std::string response_csv(const TransferFunction& t) {
  std::string s = fmt::format("f [Hz],magnitude [{}],magnitude [dB],phase [deg]\n", t.unit);
  const std::vector<double> phase = unwrapped_phase_deg(t.value);
  for (std::size_t k = 0; k < t.frequency_hz.size(); ++k)
    s += fmt::format("{},{},{},{}\n", t.frequency_hz[k], std::abs(t.value[k]), db(t.value[k]), phase[k]);
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
    if (t.peaks.empty()) s += "no resonance peak in the range\n";
    else s += fmt::format("{} resonance peak{}\n", t.peaks.size(), t.peaks.size() == 1 ? "" : "s");
    for (const ResonancePeak& p : t.peaks) {
      s += fmt::format("  {:.6g} Hz: |H| = {:.6g} ({:.4g} dB)", p.frequency_hz, p.magnitude, 20 * std::log10(p.magnitude));
      if (p.over_rigid) s += fmt::format(", {:.4g} times the rigid model's", *p.over_rigid);
      s += "\n";
    }
  }
  return s;
}

}  // namespace pogear
