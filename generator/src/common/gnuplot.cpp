// gnuplot reads the script, data included, from a memory file on its standard input and writes
// the SVG to its standard output; pogear checks its exit status and that the SVG is whole before
// the file is written, so a failed or cut-short drawing never replaces a good figure.
#include "common/gnuplot.hpp"

#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <sys/stat.h>

#include "common/child_process.hpp"
#include "common/csv_rows.hpp"
#include "common/output_file.hpp"

namespace pogear {

std::string gnuplot_label(const std::string& name) {
  // omega_c -> {/Symbol w}_{c}, F_ps -> F_{ps}
  const auto us = name.find('_');
  std::string base = name.substr(0, us), sub = us == std::string::npos ? "" : name.substr(us + 1);
  if (base == "omega") base = "{/Symbol w}";
  // Enhanced text would read a further '_' as another subscript (Tc_engine_speed).
  std::string escaped;
  for (const char c : sub) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
  return sub.empty() ? base : base + "_{" + escaped + "}";
}


std::string gnuplot_datablock(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string s = "$" + name + " << EOD\n";
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) s += fmt::format("{}{}", i ? "," : "", row[i]);
    s += '\n';
  }
  return s + "EOD\n";
}

std::vector<std::vector<double>> thinned_csv_rows(const std::string& path, double horizon) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    throw std::runtime_error(fmt::format("the simulation wrote no {}; run the simulator by hand to see why", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {} for the figures; check its permissions", path));
  std::vector<std::vector<double>> kept, bucket;
  std::vector<std::size_t> lo, hi;  // per column: the bucket rows of the smallest and largest value
  long current = -1;
  auto flush = [&] {
    if (bucket.empty()) return;
    std::vector<bool> keep(bucket.size(), false);
    keep.front() = keep.back() = true;
    for (std::size_t c = 1; c < lo.size(); ++c) keep[lo[c]] = keep[hi[c]] = true;
    for (std::size_t i = 0; i < bucket.size(); ++i)
      if (keep[i]) kept.push_back(std::move(bucket[i]));
    bucket.clear();
  };
  std::string line;
  std::vector<double> row;
  std::size_t width = 0;
  while (std::getline(in, line)) {
    if (!parse_csv_numbers(line, width, row) || row.empty()) continue;
    width = row.size();
    const long b = horizon > 0 ? static_cast<long>(row[0] / horizon * static_cast<double>(plot_buckets)) : 0;
    if (b != current) {
      flush();
      current = b;
      lo.assign(width, 0);
      hi.assign(width, 0);
    }
    const std::size_t i = bucket.size();
    bucket.push_back(row);
    for (std::size_t c = 1; c < width; ++c) {
      if (bucket[i][c] < bucket[lo[c]][c]) lo[c] = i;
      if (bucket[i][c] > bucket[hi[c]][c]) hi[c] = i;
    }
  }
  flush();
  if (kept.empty()) throw std::runtime_error(fmt::format("{} holds no rows to plot", path));
  return kept;
}

std::string gnuplot_svg_preamble(int width, int height) {
  static constexpr const char* colours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b",
                                            "#e377c2", "#17becf", "#ff7f0e", "#7f7f7f", "#000000"};
  std::string s = fmt::format("set terminal svg size {},{} dynamic enhanced font 'Helvetica,13' background rgb 'white'\n",
                              width, height);
  for (std::size_t i = 0; i < std::size(colours); ++i) s += fmt::format("set linetype {} lc rgb '{}'\n", i + 1, colours[i]);
  return s + fmt::format("set linetype cycle {}\n", std::size(colours));
}

std::optional<std::string> gnuplot_program() { return find_program("gnuplot"); }

std::string render_svg(const std::string& gnuplot, const std::string& script, const std::string& svg,
                       const std::string& already_written) {
  ChildRequest request;
  // The script as a file argument: gnuplot reads a script file in blocks, but its standard input
  // a few bytes per call.
  request.argv = {gnuplot, "/dev/stdin"};
  request.input = script;
  request.capture_stdout = true;
  request.capture_stderr = true;
  const ChildResult result = run_child(request);
  const std::size_t end = result.out.rfind("</svg>");
  if (!result.ok() || end == std::string::npos || result.out.find_first_not_of(" \n", end + 6) != std::string::npos)
    throw std::runtime_error(fmt::format("gnuplot failed drawing {} ({}){}{}; {}", svg, result.describe(),
                                         result.err.empty() ? "" : ": ", result.err.substr(0, 2000), already_written));
  return result.out;
}

void draw_svg(const std::string& gnuplot, const std::string& script, const std::string& svg,
              const std::string& already_written) {
  write_file_atomically(svg, render_svg(gnuplot, script, svg, already_written));
}

}  // namespace pogear
