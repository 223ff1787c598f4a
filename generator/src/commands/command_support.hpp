// What the commands share: lists from the command line, outputs that must not overwrite the inputs,
// text to standard output or a file, and errors printed once with the exit status.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pogear {

// "a,b,,c" -> a, b, c (empty items dropped).
std::vector<std::string> split_list(const std::string& s);

// An output file must not be an input of the command, nor another of its outputs: throws InputError
// at `output` when both name the same file; `what` says what `other` is.
void refuse_same_file(const std::string& output, const std::string& other, const std::string& what);

// `text` to standard output, or written atomically to `output`.
void emit(const std::string& text, const std::optional<std::string>& output);

// Runs a command and returns its exit status: an error is printed to standard error once (bad input
// as FILE:LINE:COL: error: ..., anything else as pogear: error: ...) and gives 2.
int exit_status_of(const std::function<int()>& command);

}  // namespace pogear
