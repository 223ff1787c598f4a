// Reads the CSV files pogear's simulators write: a header line, then numeric rows.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pogear::test {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  bool incomplete = false;
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name || header[i].rfind(name + " [", 0) == 0) return i;
    return header.size();
  }
};

inline Csv read_csv(const std::string& path) {
  Csv c;
  std::ifstream in(path);
  std::string line;
  if (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) c.header.push_back(cell);
  }
  while (std::getline(in, line)) {
    if (line.rfind("# incomplete", 0) == 0) {
      c.incomplete = true;
      continue;
    }
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    c.rows.push_back(std::move(row));
  }
  return c;
}

}  // namespace pogear::test
