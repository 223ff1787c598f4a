// A planetary gear as its model file describes it: bodies, toothed wheels, meshes, brakes and
// clutches and parameters (in SI), as plain values; read/topology.hpp reads them from a file.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.hpp"
#include "common/quantity.hpp"

namespace pogear {

enum class AxisKind {
  central,  // the gear's main axis, drawn at height 0
  fixed,    // a separate fixed parallel axis (a countershaft such as the paper's g or m)
  carried,  // a planet axis held by a carrier body at a given distance
};

struct Wheel {
  std::string name;
  std::string radius_parameter;  // the name of the parameter that holds the radius, e.g. r_s1
  bool internal = false;  // teeth on the inside (a ring)
  SourceLocation where;
  // A wheel given by its tooth count (0: by its radius) and module (here, or on one of its meshes):
  // its pitch radius m Z / 2 is the parameter radius_parameter (tooth_counts.hpp).
  int teeth = 0;
  SourceLocation teeth_where;
  std::string module;  // an expression of length, e.g. "2*mm"; empty when the mesh gives it
  SourceLocation module_where;
  int module_column_offset = 1;
};

struct Body {
  std::string name;
  AxisKind axis = AxisKind::central;
  std::string carrier;   // carried: the carrier body's name
  std::string distance_parameter;  // carried: the parameter holding the axis distance, e.g. r_c
  int side = +1;         // carried: +1 drawn above the carrier's axis; fixed: +1 above its mates
  int arrow = +1;        // positive direction of omega as drawn: +1 right, -1 left (the paper's s_k)
  // The parameters holding the inertia and the bearing friction: J_<name> and b_<name> unless set.
  std::string inertia_parameter;
  std::string friction_parameter;
  std::vector<Wheel> wheels;
  SourceLocation where;
  // A planet that stands for `count` identical planets sharing the load equally (lumped): the model
  // multiplies its inertia and friction, and its meshes' stiffness and damping, by the count.
  int count = 1;
  SourceLocation count_where;
  // Held by the housing (`fixed = true`, central bodies only): omega is 0, so it has no velocity,
  // no state and no inertia in the model; its wheels mesh like any other.
  bool fixed = false;
};

struct WheelRef {
  int body = -1;
  int wheel = -1;
};

// A mesh between two toothed wheels, or a shaft (a [[shaft]]: a torsional spring-damper between two
// coaxial bodies): both are a row of R and a force of F (a shaft's is its torque, T_<name>).
struct Mesh {
  std::string name;       // F_<name> is positive from the first terminal to the second
  WheelRef first, second;  // a shaft's name bodies only (wheel -1)
  // A shaft: its row of R is a_first u_first - a_second u_second (arrows as a clutch's slip), its
  // stiffness N m/rad, its damping N m s/rad; shafts come after the meshes, in file order.
  bool shaft = false;
  // A shaft's outputs T_, Tspring_ are its torque times this: a vehicle's half-shafts, which the model
  // carries reflected through the final drive, report the torque at the wheels (scene [vehicle]).
  double output_scale = 1;
  std::string stiffness_parameter;  // K_<name> unless set
  std::string damping_parameter;    // b_<name> unless set
  SourceLocation where;
  std::string module;  // the module of its toothed wheels, when they do not give it
  SourceLocation module_where;
  int module_column_offset = 1;
  // The operating centre distance (profile-shifted wheels), an expression of length; empty: the
  // wheels roll on their pitch circles.
  std::string centre_distance;
  SourceLocation centre_distance_where;
  int centre_distance_column_offset = 1;
};

// A brake (holds a body against the housing) or a clutch (joins two bodies on one axis). Its
// slip is s = a_first omega_first - a_second omega_second (a: the bodies' arrows, so that s is
// in one rotation sense; a brake's second is the housing, at rest); its torque T acts as -T on
// the first body and +T on the second, in that sense.
struct FrictionElement {
  std::string name;
  int first = -1;   // body index
  int second = -1;  // body index; -1 for a brake
  std::string capacity_parameter;  // kinetic torque capacity at full engagement (N m): T_<name> unless set
  std::string static_ratio = "1";  // static / kinetic friction, an expression of the parameters
  SourceLocation where;            // the name
  SourceLocation bodies_where;     // a clutch's second body, as written
  SourceLocation static_ratio_where;
  int static_ratio_column_offset = 0;
  // A one-way element (freewheel, sprag): its slip may be positive freely (no torque); it holds
  // against negative slip only. A one-way brake lets its body turn forward and stops it turning back.
  bool one_way = false;
  // Kinetic friction that varies with slip (friction_curve): the ratio of the kinetic torque to the
  // capacity's at slip speeds |s| [rad/s], ascending from 0, linear between them and held beyond the
  // last. Empty: the ratio is 1 at every slip.
  std::vector<double> curve_slip, curve_ratio;
  SourceLocation friction_curve_where;
  bool is_brake() const { return second < 0; }
};

// A gear the model names in [gears]: the brakes and clutches it engages (`pogear ratios` lists the
// named gears with the engineer's ratio omega_in / omega_out, their steps and spread).
struct NamedGear {
  std::string name;
  std::vector<int> engaged;  // friction element indices, ascending
  SourceLocation where;      // the gear's key
};

struct Parameter {
  std::string name;
  std::string text;  // as written, e.g. "4.8*cm"
  Quantity value;
  SourceLocation where;
  int column_offset = 1;  // where the text starts after `where` (1 past a quote)
};

struct Topology {
  std::string file;
  std::string digest;  // of the model file's text (text_digest)
  std::string name;
  std::string title;
  std::vector<Body> bodies;  // the bodies that turn, in the order of the velocity vector omega
  // The fixed bodies, in file order. A body index past the turning ones (in a WheelRef) names one
  // of them: bodies.size() + k is grounded[k]. Their column of R is the housing's reaction.
  std::vector<Body> grounded;
  std::vector<Mesh> meshes;  // in the order of the force vector F
  std::vector<FrictionElement> friction_elements;  // brakes and clutches, in file order
  std::vector<NamedGear> gears;                    // in the order written
  std::vector<Parameter> parameters;
  std::vector<std::string> default_keep;
  SourceLocation keep_where;
};

int find_body(const Topology& t, const std::string& name);  // a body that turns; -1 when absent
// Any body by index, turning (index < bodies.size()) or fixed (past them).
const Body& body(const Topology& t, int index);
bool is_grounded(const Topology& t, int index);
// Every body, the turning ones then the fixed ones: a body's index in it is its index.
std::vector<const Body*> every_body(const Topology& t);
// For a name that a command or scene expects to turn: why a fixed body does not, or "" when the
// name is no fixed body.
std::string fixed_body_refusal(const Topology& t, const std::string& name, std::string_view what);
// The same for a body's variable, omega_<body> or tau_<body>.
std::string fixed_variable_refusal(const Topology& t, std::string_view variable);
// How many identical planets a mesh stands for: its lumped planet's count, 1 for other meshes. The
// model's F_<mesh> is their sum; the outputs and reports give one planet's share.
int mesh_count(const Topology& t, const Mesh& m);
// Adds a turning body (after the others), keeping the fixed bodies' indices (bodies.size() + k) right.
void add_turning_body(Topology& t, Body b);
// The toothed meshes, the leading part of Topology::meshes (the shafts follow them).
std::size_t toothed_mesh_count(const Topology& t);
bool has_shafts(const Topology& t);
int find_friction_element(const Topology& t, const std::string& name);  // -1 when absent
const Wheel& wheel(const Topology& t, WheelRef w);
// The radius parameter of wheel w's contact in mesh m: the wheel's own, or with a centre distance
// its operating pitch radius in that mesh, rw_<wheel>_<mesh> (read/tooth_counts.hpp).
std::string contact_radius(const Topology& t, const Mesh& m, WheelRef w);
std::string wheel_label(const Topology& t, WheelRef w);  // "s1 (body s)" or "p"

}  // namespace pogear
