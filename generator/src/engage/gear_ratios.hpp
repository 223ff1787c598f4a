// The clutch schedule of a gear: for every set of engaged brakes and clutches, how many degrees of
// freedom are left and, with one left, the ratio omega_output / omega_input in closed form.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "derive/derivation.hpp"

namespace pogear {

enum class EngagementStatus {
  ratio,        // one degree of freedom; input and output both turn
  output_held,  // one degree of freedom; the output cannot turn (ratio 0)
  input_held,   // one degree of freedom; the input cannot turn
  free,         // more than one degree of freedom: no ratio
  locked,       // none: nothing turns
};
const char* status_name(EngagementStatus s);  // "ratio", "output held", ..., as the reports write it

// Which way a one-way element of a gear holds. In drive (a positive torque on the input, in the
// common rotation sense, against the output's load) and in coast (a negative one: the load drives
// the input) its torque has opposite signs, and it holds one of them only.
struct OneWayHold {
  int element = -1;
  bool drive = false, coast = false;  // both when it carries no torque in either
};

struct EngagementRatio {
  std::vector<int> engaged;  // friction element indices, ascending
  int freedoms = 0;          // n - rank [R; E_S]
  EngagementStatus status = EngagementStatus::free;
  std::optional<GiNaC::ex> ratio;  // ratio or output_held: omega_out/omega_in in the independent radii
  double value = 0;                // the ratio at the model's values, correctly rounded
  GiNaC::ex exact;                 // the same, exact
  std::vector<OneWayHold> one_way; // of a ratio's one-way elements, in the order of `engaged`
};

// A gear the model names ([gears]), as the engineer writes its ratio: i = omega_in / omega_out,
// negative in reverse.
struct NamedGearRatio {
  std::string name;
  std::vector<int> engaged;    // friction element indices, ascending
  GiNaC::ex i;                 // closed form, in tooth counts when the model gives them
  double value = 0;            // i at the model's values, correctly rounded
  std::optional<double> step;  // i / i of the next gear written, when both are forward gears
};

struct GearRatios {
  std::string model;
  std::string input, output;  // body names
  int gear_freedoms = 0;      // with nothing engaged
  std::vector<EngagementRatio> engagements;
  int redundant_sets = 0;     // sets not listed: one of their elements adds no constraint to the others
  std::vector<NamedGearRatio> gears;  // the model's [gears], in the order written
  std::optional<double> spread;       // largest over smallest forward i, with two forward gears or more
};

// Every set of engaged elements in which each element adds a constraint (a set with one that
// does not moves exactly as the set without it), by size, then in file order. Ratios are of
// rotations in one sense (each omega times its body's arrow), so a reverse gear is negative.
// Throws InputError at `where` when input or output is not a body, or both are the same; at a named
// gear's line when it is no gear between them (free, locked, an element that adds no constraint,
// input or output held).
GearRatios gear_ratios(const Derivation& d, const std::string& input, const std::string& output,
                       const SourceLocation& where);

}  // namespace pogear
