// Figures of a simulated scene, drawn by gnuplot from the CSV files the run wrote: the data reach
// gnuplot inside its script (no path is ever part of gnuplot syntax), and its SVG comes back on its
// standard output and is written by pogear like any other output.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "specialize/specialization.hpp"

namespace pogear {

// At most this many time buckets per figure; each keeps the first, last, smallest and largest
// value of every curve, so that no peak of a long run is lost to the thinning.
inline constexpr std::size_t plot_buckets = 2000;

// Rows of a CSV as numbers (the header and "# incomplete" marks skipped), thinned to plot_buckets
// buckets over [t_first, t_last] by the rule above. Throws std::runtime_error when `path` cannot be
// read or holds no row.
std::vector<std::vector<double>> thinned_csv_rows(const std::string& path, double horizon);

// gnuplot's path, when it is installed.
std::optional<std::string> gnuplot_program();
// Runs `script` (which writes an SVG to gnuplot's standard output) and writes the SVG to `svg` once
// gnuplot has succeeded and the SVG is whole. Throws std::runtime_error otherwise, ending the message
// with `already_written` (what the user still has).
void draw_svg(const std::string& gnuplot, const std::string& script, const std::string& svg,
              const std::string& already_written);
// The same SVG, returned instead of written (for a command that writes several files only once all
// of them are made).
std::string render_svg(const std::string& gnuplot, const std::string& script, const std::string& svg,
                       const std::string& already_written);
// The SVG terminal on white and ten line colours that stay apart on it (no yellow, no pale hue),
// cycling: every figure's script starts with it.
std::string gnuplot_svg_preamble(int width, int height);

// `$name << EOD` with the rows as comma-separated numbers.
std::string gnuplot_datablock(const std::string& name, const std::vector<std::vector<double>>& rows);
// omega_c -> {/Symbol w}_{c}, F_ps -> F_{ps} (enhanced text).
std::string gnuplot_label(const std::string& name);

// DIR/<scene>.velocities.svg and, with forces, DIR/<scene>.forces.svg: elastic solid, rigid dashed
// on top, as in the paper's Figs. 8-9; with brakes or clutches, DIR/<scene>.shift.svg (speeds,
// element torques, slips). Returns the files written.
std::vector<std::string> plot_scene(const SpecializedScene& model, const std::string& dir);

}  // namespace pogear
