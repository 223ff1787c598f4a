// The Campbell diagram of a gear given by its tooth counts: along one operating line (an input body
// turning, chosen bodies held, brakes and clutches stuck), each mesh's tooth-passing frequency and
// its harmonics against the natural frequencies, and the input speeds at which they meet.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "derive/derivation.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear {

// Tooth passing of one mesh: Z |omega_w - omega_F| / 2 pi for either of its wheels w, F being the
// frame in which both axes stand still (the planet's carrier, or the housing).
struct MeshLine {
  std::string mesh;
  std::string wheel;        // the wheel whose tooth count is used
  int teeth = 0;
  std::string frame;        // the carrier body, or "housing"
  double hz_per_rpm = 0;    // first-harmonic mesh frequency [Hz] per rpm of the input
};

// A harmonic of a mesh frequency meeting a natural frequency within the speed range.
struct Crossing {
  std::vector<std::string> meshes;  // the meshes of one line (equal frequencies), e.g. ssps, pspl
  int harmonic = 1;
  double natural_hz = 0;
  double input_rpm = 0;
};

struct CampbellDiagram {
  std::string model;
  std::string input;                    // the input body
  std::vector<std::string> held;        // bodies held at rest
  std::vector<std::string> engaged;     // brakes and clutches stuck
  Eigen::VectorXd speeds;               // every body's speed per unit input speed
  std::vector<std::string> bodies;
  double max_rpm = 0;
  int harmonics = 3;
  std::vector<double> natural_hz;       // the distinct elastic natural frequencies, ascending
  std::vector<MeshLine> meshes;         // meshes with a tooth count, in model order
  std::vector<std::string> without_teeth;  // meshes neither of whose wheels gives a tooth count
  std::vector<Crossing> crossings;      // ascending input speed
};

// Up to this many harmonics of each mesh frequency (gear whine shows the first three or four).
inline constexpr int max_harmonics = 10;

// The diagram along the operating line on which `input` turns, the `held` bodies stand still and the
// modes' engaged elements are stuck (indices into the topology); `max_rpm` <= 0 picks the speed at
// which the slowest mesh line's first harmonic reaches 1.2 times the highest natural frequency.
// Throws std::domain_error when the line is not one degree of freedom, when the input cannot turn
// on it, and when no mesh has a tooth count.
CampbellDiagram campbell_diagram(const Derivation& d, const GiNaC::exmap& values, const VibrationModes& modes,
                                 const std::vector<int>& engaged, int input, const std::vector<int>& held,
                                 double max_rpm, int harmonics);

// Meshes of one frequency per input speed (to 1e-12; the meshes of one planetary train pass teeth
// alike) as one line: (Hz per rpm, its meshes), in the order of their first mesh.
std::vector<std::pair<double, std::vector<std::string>>> mesh_line_groups(const CampbellDiagram& c);

// The crossings the reports list: those from 1 % of the speed axis up. Below it a mode meets a
// harmonic at a speed the gear only passes through (a 3 Hz mode at 2.6 rpm of an 8000 rpm axis),
// where the meshes' excitation carries almost no power; the reports count them in one line, and
// the JSON keeps every crossing.
inline constexpr double listed_crossing_fraction = 0.01;
std::vector<Crossing> listed_crossings(const CampbellDiagram& c);

// The mesh lines and the crossings, as a section of each report format.
std::string campbell_text(const CampbellDiagram& c);
std::string campbell_markdown(const CampbellDiagram& c);
std::string campbell_latex(const CampbellDiagram& c);
std::string campbell_json_member(const CampbellDiagram& c);  // "campbell": {...}, no trailing comma

// A gnuplot script that writes the diagram as SVG on its standard output: natural frequencies as
// horizontal lines, each mesh's harmonics as lines through the origin, the crossings marked.
std::string campbell_script(const CampbellDiagram& c);

}  // namespace pogear
