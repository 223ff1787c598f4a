// See csv_rows.hpp: std::from_chars reads exactly the shortest round-trip form the runs write.
#include "common/csv_rows.hpp"

#include <charconv>

namespace pogear {

bool parse_csv_numbers(const std::string& line, std::size_t width, std::vector<double>& row) {
  row.clear();
  const char* p = line.data();
  const char* end = p + line.size();
  while (p < end) {
    double v = 0;
    const auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc()) return false;
    row.push_back(v);
    p = next;
    if (p < end && *p != ',') return false;
    if (p < end) ++p;
  }
  return width == 0 || row.size() == width;
}

}  // namespace pogear
