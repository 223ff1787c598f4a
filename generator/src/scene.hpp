// Scene files: what to simulate on a model — effects, inputs, initial state, parameter
// overrides and tunables, outputs, horizon, solver — read and checked against the model.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "topology.hpp"

namespace pogear {

struct Effects {
  bool mesh_compliance = false;  // the elastic model; without it the rigid model
  bool mesh_damping = false;     // B_K (needs compliance)
  bool bearing_friction = false; // B_J
  bool mesh_forces = false;      // force outputs
};

enum class SignalKind { constant, step, ramp, sine, table };

// A torque signal in SI units; which fields matter depends on the kind.
struct SignalSpec {
  SignalKind kind = SignalKind::constant;
  double value = 0;      // constant value; step: value after; ramp: slope (N m / s); sine: amplitude
  double before = 0;     // step: value before; ramp: value before the start
  double time = 0;       // step time, ramp start
  double frequency = 0;  // sine, Hz
  double phase = 0;      // sine, rad
  double offset = 0;     // sine
  std::string table_file;
  std::vector<double> table_t, table_v;
  SourceLocation where;
  bool identically_zero() const;
};

struct InputSpec {
  std::string body;  // the driven body; the input is tau_<body>
  SignalSpec signal;
};

enum class Solver { exact, rk4, dopri5, implicit };

struct Scene {
  std::string file;
  std::string name;
  std::string model_file;  // resolved relative to the scene file
  std::string model_ref;   // as the scene file writes it
  Effects effects;
  std::vector<std::string> keep;  // empty: the model's default
  bool compare_rigid = false;
  std::vector<InputSpec> inputs;
  std::map<std::string, double> initial;  // omega_<body> [rad/s], F_<mesh> [N]
  std::vector<Parameter> overrides;
  std::vector<std::string> tunable;
  std::vector<std::string> outputs;  // empty: every velocity, and every force with mesh_forces
  double horizon = 1.0;
  double sample = 1e-3;
  Solver solver = Solver::exact;
  double tolerance = 1e-8;  // adaptive methods, relative
  double step = 1e-4;       // fixed-step methods
  long max_steps = 10000000;  // adaptive methods: a stiff scene stops with an error, not a hang
  SourceLocation solver_where, outputs_where, keep_where, tunable_where, sample_where;
};

// Reads a scene and checks it against its model (bodies, meshes, parameter names).
Scene parse_scene(const std::string& path);
Scene parse_scene_text(const std::string& text, const std::string& path);

// The model with the scene's parameter overrides applied.
Topology apply_overrides(Topology topology, const Scene& scene);

Solver parse_solver(const std::string& name, const SourceLocation& where);
const char* solver_name(Solver s);

}  // namespace pogear
