// JSON text that pogear writes: every string passes json_string, every number json_number.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace pogear {

std::string json_string(const std::string& s);  // quoted and escaped
std::string json_number(double v);              // shortest round-trip form; null when not finite

// Arrays: ["a", "b"]; rows of them, one per line under `indent`; [1.5, 2]; [[1, 2], [3, 4]].
std::string json_strings(const std::vector<std::string>& v);
std::string json_string_matrix(const std::vector<std::vector<std::string>>& m, const std::string& indent);
std::string json_numbers(const Eigen::VectorXd& v);
std::string json_number_matrix(const Eigen::MatrixXd& m);

}  // namespace pogear
