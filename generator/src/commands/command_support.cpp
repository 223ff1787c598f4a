// Every error a command meets reaches the user here, in one of two forms, with exit status 2.
#include "commands/command_support.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "common/input_error.hpp"
#include "common/output_file.hpp"
#include "report/model_errors.hpp"

namespace pogear {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

void refuse_same_file(const std::string& output, const std::string& other, const std::string& what) {
  std::error_code e1, e2;
  const auto a = std::filesystem::weakly_canonical(output, e1), b = std::filesystem::weakly_canonical(other, e2);
  if (!e1 && !e2 && a == b)
    throw InputError(SourceLocation{output, 0, 0}, fmt::format("this output is also {}; write it to another file", what));
}

void emit(const std::string& text, const std::optional<std::string>& output) {
  if (!output) std::fwrite(text.data(), 1, text.size(), stdout);
  else write_file_atomically(*output, text);
}

int exit_status_of(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
  } catch (const GeometryConflict& e) {
    std::cerr << input_error_of(e).what() << "\n";
  } catch (const TiedVelocities& e) {
    std::cerr << input_error_of(e).what() << "\n";
  } catch (const std::exception& e) {
    std::cerr << "pogear: error: " << e.what() << "\n";
  }
  return 2;
}

}  // namespace pogear
