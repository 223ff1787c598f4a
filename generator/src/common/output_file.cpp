// See output_file.hpp; the rules for what stands at a path are rt::OutputFile's, shared with the
// simulators' CSV writer.
#include "common/output_file.hpp"

#include <filesystem>
#include <stdexcept>

#include "common/interrupts.hpp"
#include "pogear/output_file.hpp"

namespace pogear {

void ensure_directory(const std::string& dir) {
  namespace fs = std::filesystem;
  if (dir.empty()) throw std::runtime_error("the output directory '' names no directory; give a directory");
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  if (fs::exists(fs::symlink_status(dir, ec)))
    throw std::runtime_error("cannot create the directory " + dir + ": a file of that name is in the way; give "
                             "another directory");
  fs::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error("cannot create the directory " + dir + ": " + ec.message() +
                             "; give a directory you can write to");
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) ensure_directory(parent.string());
  rt::OutputFile out(path);
  // Where the file system has no unnamed temporary files, the named one must go on a signal.
  const int slot = out.temporary_name().empty() ? -1 : remember_temporary(out.temporary_name());
  struct Forget {
    int slot;
    ~Forget() { forget_temporary(slot); }
  } forget{slot};
  if (!out.write(contents) || !out.commit()) throw std::runtime_error(out.error());
}

}  // namespace pogear
