// Wheels given by tooth count and module: their pitch radii m Z / 2 as parameters of the model, the
// modules of meshing wheels checked, and the substitution that writes ratios in tooth counts.
#pragma once

#include <ginac/ginac.h>

#include <optional>

#include "names/symbols.hpp"
#include "read/topology.hpp"

namespace pogear {

// Adds each toothed wheel's pitch radius to t.parameters (after the file's parameters are
// evaluated: a module may name one). Throws InputError for a wheel without a module, meshing wheels
// of different modules, or a radius given twice.
void add_pitch_radii(Topology& t);

// For each mesh with a centre distance a (wheels of Z_1 and Z_2 teeth), its operating pitch radii
// rw_<wheel>_<mesh> = a Z_k / (Z_2 + Z_1), or / (Z_ring - Z_pinion) for an internal mesh, as
// parameters, which the mesh's contact uses (contact_radius): a ratio across it stays Z_1 / Z_2.
// Throws InputError when a wheel has no teeth, or a is not within one module of the reference
// centre distance m (Z_2 +- Z_1) / 2 (profile shifts move it by a fraction of a module).
void add_operating_radii(Topology& t);
// The same checks of every centre distance at the parameters' present values (after a scene's
// overrides, which the operating radii follow through their texts).
void check_centre_distances(const Topology& t);

// r_w -> m Z_w / 2 for every toothed wheel, with one module symbol per set of wheels joined by
// meshes (`m` when there is one set, else m_1, m_2, ... in the order of the wheels) and Z_w named
// after the wheel. Empty when no wheel has teeth. The symbols are for printing only.
GiNaC::exmap tooth_count_substitutions(const Topology& t, const SymbolTable& s);

// e, written in tooth counts by tooth_count_substitutions, with each Z_w replaced by wheel w's
// tooth count: the exact value of a ratio of teeth, where the pitch radii m Z / 2 were rounded to
// doubles. Nothing when e keeps another symbol (a module that did not cancel).
std::optional<GiNaC::ex> in_tooth_numbers(const GiNaC::ex& e, const Topology& t);

}  // namespace pogear
