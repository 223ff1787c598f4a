// The figures of a simulated scene: speeds and forces, elastic solid and rigid dashed, and the
// three panels of a shift.
#include "run/plot.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "common/gnuplot.hpp"
#include "names/model_variables.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

// Three panels over time: the bodies' speeds, the brakes' and clutches' torques, and their slips
// (the columns run_hybrid_system writes after the system's outputs: T_, slip_, E_ per element).
std::string shift_script(const SpecializedScene& model, const std::vector<std::vector<double>>& rows) {
  const std::size_t ny = model.main.outputs.size(), ne = model.friction.size();
  std::string script;
  script += gnuplot_svg_preamble(900, 900);
  script += "set datafile separator ','\n";
  script += gnuplot_datablock("run", rows);
  script += "set grid\nset key outside right top\nset multiplot layout 3,1\n";
  script += "set lmargin 12\nset rmargin 22\n";
  auto panel = [&](const std::string& title, const std::string& ylabel, const std::vector<std::size_t>& columns,
                   const std::vector<std::string>& labels, bool last) {
    script += fmt::format("set title '{}' noenhanced\nset ylabel '{}'\n", title, ylabel);
    script += last ? "set xlabel 't [s]'\n" : "unset xlabel\n";
    script += "plot ";
    for (std::size_t i = 0; i < columns.size(); ++i)
      script += fmt::format("{}$run using 1:{} with lines lw 2 title '{}'", i ? ", \\\n     " : "", columns[i],
                            gnuplot_label(labels[i]));
    script += "\n";
  };
  std::vector<std::size_t> speeds, torques, slips;
  std::vector<std::string> speed_names, torque_names, slip_names;
  for (std::size_t i = 0; i < ny; ++i)
    if (const Variable y = model.main.outputs[i].variable; y.kind == VariableKind::velocity) {
      speeds.push_back(i + 2);
      speed_names.push_back(variable_name(model.derivation.symbols, y));
    }
  for (std::size_t k = 0; k < ne; ++k) {
    torques.push_back(ny + k + 2);
    torque_names.push_back(element_torque_name(model.friction[k].name));
    slips.push_back(ny + ne + k + 2);
    slip_names.push_back(element_slip_name(model.friction[k].name));
  }
  // The scene's name and the elements' names are identifiers, checked when the files were read.
  if (!speeds.empty())
    panel(model.scene.name + ": angular velocities", model.scene.speeds_in_rpm ? "n [rpm]" : "{/Symbol w} [rad/s]",
          speeds, speed_names, false);
  panel("brake and clutch torques", "T [N m]", torques, torque_names, false);
  panel("slips", model.scene.speeds_in_rpm ? "slip [rpm]" : "slip [rad/s]", slips, slip_names, true);
  return script + "unset multiplot\n";
}

}  // namespace

std::vector<std::string> plot_scene(const SpecializedScene& model, const std::string& dir) {
  const std::optional<std::string> gnuplot = gnuplot_program();
  if (!gnuplot)
    throw std::runtime_error("gnuplot is not installed, so no figures were drawn (the CSV files are written); "
                             "install gnuplot-nox (scripts/install-deps.sh)");
  std::vector<std::string> written;
  const std::string name = model.scene.name;
  const auto elastic = thinned_csv_rows((fs::path(dir) / (name + ".csv")).string(), model.scene.horizon);
  std::vector<std::vector<double>> rigid;
  if (model.rigid) rigid = thinned_csv_rows((fs::path(dir) / (name + ".rigid.csv")).string(), model.scene.horizon);
  // Like with like: speeds, mesh forces [N], shaft torques [N m], controller torques [N m].
  auto figure_of = [&](Variable y) -> std::string {
    if (y.kind == VariableKind::velocity) return "velocities";
    if (y.kind == VariableKind::controller_torque) return "controllers";
    if (y.kind == VariableKind::vehicle_speed) return "vehicle";
    if (y.kind == VariableKind::vehicle_acceleration) return "vehicle_acceleration";
    if (y.kind == VariableKind::vehicle_jerk) return "vehicle_jerk";
    return model.derivation.topology.meshes[static_cast<std::size_t>(y.index)].shaft ? "shafts" : "forces";
  };
  for (const std::string kind : {"velocities", "forces", "shafts", "controllers", "vehicle"}) {
    std::vector<int> columns;  // 1-based gnuplot columns; column 1 is t
    for (std::size_t i = 0; i < model.main.outputs.size(); ++i)
      if (figure_of(model.main.outputs[i].variable) == kind) columns.push_back(static_cast<int>(i) + 2);
    if (columns.empty()) continue;
    // Every word of the script is pogear's own or a validated name: the scene's name and the
    // outputs' names are identifiers (checked when the files are read), and the data are numbers.
    std::string script;
    script += gnuplot_svg_preamble(900, 560);
    script += "set datafile separator ','\n";
    script += gnuplot_datablock("elastic", elastic);
    if (model.rigid) script += gnuplot_datablock("rigid", rigid);
    script += "set grid\nset key outside right top\n";
    script += fmt::format("set title '{}: {}{}' noenhanced\n", name,
                          kind == "velocities" ? "angular velocities"
                          : kind == "forces"   ? "mesh forces"
                          : kind == "shafts"   ? "shaft torques"
                          : kind == "vehicle"  ? "vehicle speed"
                                               : "controller torques",
                          model.rigid ? " (rigid model dashed, in the same colour)" : "");
    script += "set xlabel 't [s]'\n";
    script += fmt::format("set ylabel '{}'\n", kind == "velocities" ? (model.scene.speeds_in_rpm ? "n [rpm]" : "{/Symbol w} [rad/s]")
                                                : kind == "forces"   ? "F [N]"
                                                : kind == "vehicle"  ? "v [km/h]"
                                                                     : "T [N m]");
    script += "plot ";
    // One colour per quantity; its rigid curve dashed in that colour, one legend entry saying so.
    for (std::size_t k = 0; k < columns.size(); ++k)
      script += fmt::format("{}$elastic using 1:{} with lines lt {} lw 2 title '{}'", k ? ", \\\n     " : "", columns[k],
                            k + 1, gnuplot_label(variable_name(model.derivation.symbols,
                                                               model.main.outputs[columns[k] - 2].variable)));
    if (model.rigid) {
      for (std::size_t k = 0; k < columns.size(); ++k)
        script += fmt::format(", \\\n     $rigid using 1:{} with lines lt {} dt 2 lw 1.5 notitle", columns[k], k + 1);
      script += ", \\\n     NaN with lines dt 2 lw 1.5 lc rgb 'black' title 'rigid model'";
    }
    script += "\n";

    const fs::path svg = fs::path(dir) / fmt::format("{}.{}.svg", name, kind);
    draw_svg(*gnuplot, script, svg.string(), "the CSV files are written");
    written.push_back(svg.string());
  }
  if (!model.friction.empty()) {
    const fs::path svg = fs::path(dir) / fmt::format("{}.shift.svg", name);
    draw_svg(*gnuplot, shift_script(model, elastic), svg.string(), "the CSV files are written");
    written.push_back(svg.string());
  }
  return written;
}

}  // namespace pogear
