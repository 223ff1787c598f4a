// Writing pogear's outputs (reports, generated sources, figures) through rt::OutputFile: a failed,
// interrupted or concurrent run never leaves a half-written file where a good one was, and a
// device, FIFO or symbolic link at the path is never replaced.
#pragma once

#include <cstdint>
#include <string>

namespace pogear {

// The most bytes of CSV files one command writes unless the user opts in: a sample period or a
// frequency grid chosen by mistake would otherwise fill the disk before the run fails.
inline constexpr std::uintmax_t max_csv_bytes = std::uintmax_t{1} << 30;

// Throws std::runtime_error with a message naming the path and what to do when it cannot write.
void write_file_atomically(const std::string& path, const std::string& contents);

// Creates `dir` and its parents if missing; throws std::runtime_error with the system's reason
// (a read-only file system, a file in the way) and what to do.
void ensure_directory(const std::string& dir);

}  // namespace pogear
