// JSON text that pogear writes: every string passes json_string, every number json_number.
#pragma once

#include <string>

namespace pogear {

std::string json_string(const std::string& s);  // quoted and escaped
std::string json_number(double v);              // shortest round-trip form; null when not finite

}  // namespace pogear
