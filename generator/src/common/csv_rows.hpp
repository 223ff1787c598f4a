// Reading back the numeric rows of the CSV files pogear's runs write: the figures and the shift
// metrics read the same files, with the same rule for what a row is.
#pragma once

#include <string>
#include <vector>

namespace pogear {

// One CSV line of numbers into `row`; false for the header, a comment (`# incomplete: ...`) or a row
// cut short (fewer or more than `width` numbers, when `width` is not 0).
bool parse_csv_numbers(const std::string& line, std::size_t width, std::vector<double>& row);

}  // namespace pogear
