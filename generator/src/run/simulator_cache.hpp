// Compiling a scene's simulator, and the private cache that keeps the binary for the same sources,
// runtime, compiler and flags, so that running a scene again starts at once.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "codegen/codegen.hpp"

namespace pogear {

// The files write_sources writes into `dir`, as `dir`/NAME: the header, then the main.
std::vector<std::string> source_paths(const GeneratedSources& sources, const std::string& dir);

// Writes the generated sources into `dir` (atomically, file by file).
void write_sources(const GeneratedSources& sources, const std::string& dir);

// The cache key of a simulator: a hash of its sources, the runtime headers under
// `runtime_include`/pogear, the compiler (path, size, modification time), flags and version.
std::uint64_t simulator_cache_key(const GeneratedSources& sources, const std::string& runtime_include);

// Where the cache lives: $POGEAR_CACHE_DIR, else $XDG_CACHE_HOME/pogear, else ~/.cache/pogear with
// the home directory from $HOME or the password database; nullopt when there is no home at all.
std::optional<std::string> simulator_cache_root();

// Empty when `dir` may hold binaries pogear will run: a directory (not a link) owned by this user
// that nobody else can write to. Otherwise why not, e.g. "writable by others (mode 0777)".
std::string why_not_private(const std::string& dir);

// A compiled simulator: in the cache, or, when no private cache can be had, in a private temporary
// directory that goes with this object.
class CompiledSimulator {
 public:
  CompiledSimulator(std::string executable, std::string temporary_dir)
      : executable_(std::move(executable)), temporary_dir_(std::move(temporary_dir)) {}
  CompiledSimulator(CompiledSimulator&& other) noexcept;
  CompiledSimulator(const CompiledSimulator&) = delete;
  CompiledSimulator& operator=(const CompiledSimulator&) = delete;
  ~CompiledSimulator();
  const std::string& executable() const { return executable_; }
  bool cached() const { return temporary_dir_.empty(); }  // else removed with this object

 private:
  std::string executable_, temporary_dir_;
};

// Compiles the scene's simulator unless the cache has a binary for the same key. A cache that is
// not private (see why_not_private) is not used: a note on stderr says why, and the simulator is
// compiled into a private temporary directory instead. Throws std::runtime_error when the compiler
// fails, with its first error and what to do.
CompiledSimulator build_simulator(const GeneratedSources& sources);

}  // namespace pogear
