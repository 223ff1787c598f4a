// What a derivation finds wrong with a model, as values: the derivation computes and throws them;
// report/model_errors.hpp makes the messages users read, where expressions are printed.
#pragma once

#include <exception>
#include <string>
#include <variant>
#include <vector>

#include <ginac/ginac.h>

#include "common/input_error.hpp"

namespace pogear {

// A length the model gives that the geometry of a mesh implies otherwise.
struct ContradictedLength {
  std::string parameter;
  std::string text;    // as written
  double given = 0;    // [m]
  std::string mesh;    // the mesh that implies it, described (describe_mesh)
  GiNaC::ex implied;   // in the other lengths
  double implied_value = 0;  // [m]
};

// A pinion's axis distance and the mesh it was derived from ("" when the model gives it).
struct PinionAxis {
  std::string body;
  std::string distance_parameter;
  double distance = 0;  // [m]
  std::string from_mesh;
};

// Two pinions of one carrier whose axes are too near or too far apart for their radii: the centre
// distance must lie between the difference and the sum of their axis distances.
struct PinionsOutOfReach {
  std::string mesh;  // described (describe_mesh)
  std::string carrier;
  PinionAxis first, second;
  GiNaC::ex centre;  // in the radii
  double centre_value = 0, least = 0, most = 0;  // [m]
};

class GeometryConflict : public std::exception {
 public:
  using Kind = std::variant<ContradictedLength, PinionsOutOfReach>;
  GeometryConflict(SourceLocation where, Kind kind) : where_(std::move(where)), kind_(std::move(kind)) {}
  const SourceLocation& where() const { return where_; }
  const Kind& kind() const { return kind_; }
  const char* what() const noexcept override { return "the model's geometry contradicts itself"; }

 private:
  SourceLocation where_;
  Kind kind_;
};

// Kept velocities that do not parametrize the rigid motions, and what ties them.
class TiedVelocities : public std::exception {
 public:
  enum class Tie {
    together,  // no pair singled out: the kept set as a whole
    at_rest,   // the first named is 0 in every rigid motion
    in_ratio,  // relation: omega_second == ratio * omega_first in every rigid motion
  };
  struct Details {
    std::vector<std::string> kept;  // body names, as the user gave them
    Tie tie = Tie::together;
    std::string first, second;      // the bodies of the tie (at_rest: first only)
    std::string first_speed;        // omega_<first>
    GiNaC::ex relation;             // in_ratio
    GiNaC::exset speeds;            // the relation's variables, which print after its parameters
    std::vector<std::vector<std::string>> valid;  // the sets that may be kept, in body order
  };
  TiedVelocities(SourceLocation where, Details details) : where_(std::move(where)), details_(std::move(details)) {}
  const SourceLocation& where() const { return where_; }
  const Details& details() const { return details_; }
  const char* what() const noexcept override { return "the kept velocities do not parametrize the rigid motions"; }

 private:
  SourceLocation where_;
  Details details_;
};

}  // namespace pogear
