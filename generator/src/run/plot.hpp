// Figures of a simulated scene, drawn by gnuplot (common/gnuplot.hpp) from the CSV files the run
// wrote.
#pragma once

#include <string>
#include <vector>

#include "specialize/specialization.hpp"

namespace pogear {

// DIR/<scene>.velocities.svg and, with forces, DIR/<scene>.forces.svg (meshes) and .shafts.svg
// (shaft torques), with controllers .controllers.svg: elastic solid, rigid dashed on top, as in the paper's Figs. 8-9; with brakes or clutches, DIR/<scene>.shift.svg (speeds,
// element torques, slips). Returns the files written.
std::vector<std::string> plot_scene(const SpecializedScene& model, const std::string& dir);

}  // namespace pogear
