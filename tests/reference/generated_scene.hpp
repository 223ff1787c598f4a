// The generated systems of one scene behind one interface, so that a single test compares every
// scene of models/scenes/ (each compiled in its own translation unit, generated_scene.cpp).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "pogear/driveline.hpp"

namespace pogear::test {

// A generated struct (Elastic or Rigid) at the given Params (by default the scene's values).
struct GeneratedSystem {
  std::vector<std::string> states, outputs;
  std::function<Eigen::VectorXd(const Eigen::VectorXd& x, const Eigen::VectorXd& u)> rhs, output_values;
  std::function<void(Eigen::MatrixXd& M, Eigen::MatrixXd& N)> matrices;
  // A nonlinear system's quadratic loads (columns, speeds, coefficients), as the hybrid runs take them.
  std::function<void(Eigen::MatrixXd& columns, Eigen::MatrixXd& speeds, Eigen::VectorXd& c)> quadratic_loads;
  // A system's engine and converter, as the hybrid runs take them.
  std::function<rt::DrivelineData()> driveline;
};

struct GeneratedScene {
  GeneratedSystem main;
  std::optional<GeneratedSystem> rigid;  // the comparison, when the scene asks for it
};

template <class System>
GeneratedSystem generated_system(const typename System::Params& params = {}) {
  using State = typename System::State;
  using Input = typename System::Input;
  GeneratedSystem g;
  for (const auto name : System::state_names) g.states.emplace_back(name);
  for (const auto name : System::output_names) g.outputs.emplace_back(name);
  g.rhs = [params](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
    const State xs = x;
    const Input us = u;
    State dx = xs;
    System::rhs(params, xs, us, dx);
    return Eigen::VectorXd(dx);
  };
  g.output_values = [params](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
    typename System::Output y;
    System::outputs(params, State(x), Input(u), y);
    return Eigen::VectorXd(y);
  };
  g.matrices = [params](Eigen::MatrixXd& M, Eigen::MatrixXd& N) {
    typename System::StateMatrix Ms;
    typename System::InputMatrix Ns;
    System::matrices(params, Ms, Ns);
    M = Ms;
    N = Ns;
  };
  if constexpr (requires(Eigen::MatrixXd& A, Eigen::VectorXd& c) { System::quadratic_loads(params, A, A, c); })
    g.quadratic_loads = [params](Eigen::MatrixXd& columns, Eigen::MatrixXd& speeds, Eigen::VectorXd& c) {
      System::quadratic_loads(params, columns, speeds, c);
    };
  if constexpr (requires { System::driveline(params); })
    g.driveline = [params] { return System::driveline(params); };
  return g;
}

}  // namespace pogear::test
