// See json_text.hpp.
#include "common/json_text.hpp"

#include <cmath>

#include <fmt/format.h>

#include "common/printer.hpp"

namespace pogear {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", c);
        else out += c;
    }
  }
  return out + "\"";
}

// JSON has no infinity or NaN.
std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{}", v) : "null"; }

std::string json_strings(const std::vector<std::string>& v) {
  std::vector<std::string> q;
  for (const auto& x : v) q.push_back(json_string(x));
  return "[" + joined(q, ", ") + "]";
}

std::string json_string_matrix(const std::vector<std::vector<std::string>>& m, const std::string& indent) {
  std::vector<std::string> rows;
  for (const auto& r : m) rows.push_back(json_strings(r));
  return "[\n" + indent + "  " + joined(rows, ",\n" + indent + "  ") + "\n" + indent + "]";
}

std::string json_numbers(const Eigen::VectorXd& v) {
  std::vector<std::string> s;
  for (Eigen::Index i = 0; i < v.size(); ++i) s.push_back(json_number(v(i)));
  return "[" + joined(s, ", ") + "]";
}

std::string json_number_matrix(const Eigen::MatrixXd& m) {
  std::vector<std::string> rows;
  for (Eigen::Index i = 0; i < m.rows(); ++i) rows.push_back(json_numbers(m.row(i).transpose()));
  return "[" + joined(rows, ", ") + "]";
}

}  // namespace pogear
