// See engagement.hpp.
#include "derive/engagement.hpp"

#include <algorithm>
#include <sstream>

#include <fmt/format.h>

namespace pogear {

GiNaC::matrix engagement_rows(const Topology& t, const std::vector<int>& engaged) {
  GiNaC::matrix E(engaged.size(), t.bodies.size());
  for (std::size_t r = 0; r < engaged.size(); ++r) {
    const FrictionElement& e = t.friction_elements.at(engaged[r]);
    E(r, e.first) = t.bodies[e.first].arrow;
    if (!e.is_brake()) E(r, e.second) = -t.bodies[e.second].arrow;
  }
  return E;
}

GiNaC::matrix stacked(const GiNaC::matrix& R, const GiNaC::matrix& E) {
  GiNaC::matrix C(R.rows() + E.rows(), R.cols());
  for (unsigned i = 0; i < R.rows(); ++i)
    for (unsigned j = 0; j < R.cols(); ++j) C(i, j) = R(i, j);
  for (unsigned i = 0; i < E.rows(); ++i)
    for (unsigned j = 0; j < E.cols(); ++j) C(R.rows() + i, j) = E(i, j);
  return C;
}

Eigen::MatrixXd stacked_for_rank(const Eigen::MatrixXd& Rn, const GiNaC::matrix& E) {
  const double scale = Rn.size() ? Rn.cwiseAbs().maxCoeff() : 1.0;
  Eigen::MatrixXd C(Rn.rows() + E.rows(), Rn.cols());
  C.topRows(Rn.rows()) = Rn;
  for (unsigned i = 0; i < E.rows(); ++i)
    for (unsigned j = 0; j < E.cols(); ++j)
      C(Rn.rows() + i, j) = scale * GiNaC::ex_to<GiNaC::numeric>(E(i, j)).to_double();
  return C;
}

std::string engaged_names(const Topology& t, const std::vector<int>& engaged, const std::string& separator) {
  std::string s;
  for (std::size_t i = 0; i < engaged.size(); ++i) s += (i ? separator : "") + t.friction_elements.at(engaged[i]).name;
  return s;
}

std::vector<int> parse_engaged(const Topology& t, const std::string& list, const SourceLocation& where) {
  std::string known;
  for (const auto& e : t.friction_elements) known += (known.empty() ? "" : ", ") + e.name;
  if (t.friction_elements.empty())
    throw InputError(where, "--engaged names brakes or clutches, and the model has none; add [[brake]] or [[clutch]] "
                            "tables to it, or leave --engaged out");
  std::vector<int> engaged;
  std::stringstream ss(list);
  std::string name;
  while (std::getline(ss, name, ',')) {
    const int k = find_friction_element(t, name);
    if (k < 0)
      throw InputError(where, fmt::format("--engaged names '{}', which is not a brake or clutch of the model; its elements "
                                          "are {}", name, known));
    if (std::find(engaged.begin(), engaged.end(), k) != engaged.end())
      throw InputError(where, fmt::format("--engaged names '{}' twice; name each element once", name));
    engaged.push_back(k);
  }
  if (engaged.empty())
    throw InputError(where, fmt::format("--engaged is empty; name the engaged elements, e.g. --engaged {}",
                                        t.friction_elements[0].name));
  std::sort(engaged.begin(), engaged.end());
  return engaged;
}

}  // namespace pogear
