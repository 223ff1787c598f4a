// Writing outputs so that a failed or interrupted run never leaves a half-written file where a
// good one was: write a temporary file beside the target, then rename it over the target.
#pragma once

#include <string>

namespace pogear {

// Throws std::runtime_error with a message naming the path when it cannot write.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace pogear
