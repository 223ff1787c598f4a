// A cached binary is run by pogear, so the cache is as private as the user's own programs: every
// directory and binary on the way is checked to be this user's and writable by nobody else, and a
// binary is never taken from a place another user could have planted it.
#include "run/simulator_cache.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <vector>

#include <fmt/format.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include "build_config.hpp"
#include "common/child_process.hpp"
#include "common/interrupts.hpp"
#include "common/output_file.hpp"
#include "pogear/input_file.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

// The flags of every simulator compile, decided with the runtime library's build (build_config).
std::vector<std::string> compile_flags() {
  return {std::begin(build_config::simulator_flags), std::end(build_config::simulator_flags)};
}

std::uint64_t fnv1a(const std::string& s, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// The runtime's headers by name and content, in a fixed order, so that editing the runtime (or
// installing another version of it) gives new cache entries.
std::uint64_t hash_runtime_headers(const fs::path& include_dir, std::uint64_t h) {
  std::vector<fs::path> headers;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(include_dir / "pogear", ec))
    if (entry.is_regular_file(ec)) headers.push_back(entry.path());
  std::sort(headers.begin(), headers.end());
  for (const fs::path& header : headers) {
    h = fnv1a(header.filename().string(), h);
    h = fnv1a(rt::read_regular_file(header.string(), std::size_t{1} << 24).text, h);
  }
  return h;
}

// The compiler binary itself (behind its symlinks) by size and modification time: an upgraded
// compiler, or another one at the same path, must not reuse binaries built by the old one.
std::uint64_t hash_compiler(const fs::path& compiler, std::uint64_t h) {
  std::error_code ec;
  const fs::path real = fs::canonical(compiler, ec);
  if (ec) return fnv1a(compiler.string(), h);
  const auto size = fs::file_size(real, ec);
  const auto mtime = fs::last_write_time(real, ec).time_since_epoch().count();
  return fnv1a(fmt::format("{}|{}|{}", real.string(), size, mtime), h);
}

// Only this user may have put a file here: owner, no write bits for group and others.
std::string why_not_ours(const struct stat& st) {
  if (st.st_uid != ::geteuid()) return fmt::format("owned by another user (uid {})", st.st_uid);
  if (st.st_mode & (S_IWGRP | S_IWOTH)) return fmt::format("writable by others (mode {:04o})", st.st_mode & 07777);
  return "";
}

// A directory of the cache, made private if it is new.
std::string make_private_directory(const fs::path& dir) {
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) return std::strerror(errno);
  return why_not_private(dir.string());
}

// The compiler's first error with its notes and source excerpt, rather than the start of a log
// that may be a wall of warnings: from the first " error: " line to the next diagnostic that is
// not a note of it.
std::string first_error(const std::string& log) {
  std::size_t start = log.find(" error: ");
  if (start == std::string::npos) return log.substr(0, 4000);
  start = log.rfind('\n', start);
  start = start == std::string::npos ? 0 : start + 1;
  std::size_t end = log.find('\n', start);
  while (end != std::string::npos && end + 1 < log.size()) {
    const std::size_t next = log.find('\n', end + 1);
    const std::string line = log.substr(end + 1, next == std::string::npos ? std::string::npos : next - end - 1);
    const bool new_diagnostic = line.find(": warning: ") != std::string::npos ||
                                line.find(": error: ") != std::string::npos ||
                                line.rfind("In file included from", 0) == 0 || line.find(": In ") != std::string::npos;
    if (new_diagnostic) break;
    end = next;
  }
  return log.substr(start, std::min<std::size_t>(end == std::string::npos ? log.size() - start : end - start, 4000));
}

std::vector<std::string> compile_command(const fs::path& dir, const std::string& main_name, const fs::path& out) {
  std::vector<std::string> argv{build_config::cxx_compiler};
  for (const std::string& f : compile_flags()) argv.push_back(f);
  argv.push_back("-I" + dir.string());
  // The precompiled headers first: GCC takes pogear/simulator_pch.hpp.gch there when it was built
  // with these flags, and reads the headers from the runtime's directory otherwise.
  if (!build_config::simulator_pch.empty()) {
    argv.push_back("-I" + build_config::simulator_pch);
    argv.push_back("-include");
    argv.push_back("pogear/simulator_pch.hpp");
  }
  argv.push_back("-I" + std::string(build_config::runtime_include));
  argv.push_back("-I" + std::string(build_config::eigen_include));
  argv.push_back((dir / main_name).string());
  argv.push_back(build_config::runtime_library);
  argv.push_back("-o");
  argv.push_back(out.string());
  return argv;
}

// Compiles the sources in `dir` to `dir`/simulator (through a temporary name, then rename: a
// concurrent run sees no binary or a whole one).
fs::path compile_into(const fs::path& dir, const GeneratedSources& g) {
  write_sources(g, dir.string());
  const fs::path exe = dir / "simulator";
  const fs::path tmp = dir / fmt::format("simulator.tmp{}", ::getpid());
  const int slot = remember_temporary(tmp.string());
  struct Forget {
    int slot;
    ~Forget() { forget_temporary(slot); }
  } forget{slot};
  ChildRequest request;
  request.argv = compile_command(dir, g.main_name, tmp);
  request.capture_stdout = true;
  request.stderr_to_stdout = true;
  const ChildResult result = run_child(request);
  if (!result.ok()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format(
        "compiling the simulator failed ({}); this is a fault of pogear or of the compiler installation, not of "
        "the scene: report it with the scene and model files. The compiler's first error:\n{}",
        result.describe(), first_error(result.out)));
  }
  fs::rename(tmp, exe);
  return exe;
}

}  // namespace

std::vector<std::string> source_paths(const GeneratedSources& g, const std::string& dir) {
  return {dir + "/" + g.header_name, dir + "/" + g.main_name};
}

void write_sources(const GeneratedSources& g, const std::string& dir) {
  const std::vector<std::string> paths = source_paths(g, dir);
  write_file_atomically(paths[0], g.header);
  write_file_atomically(paths[1], g.main);
}

std::uint64_t simulator_cache_key(const GeneratedSources& g, const std::string& runtime_include) {
  std::uint64_t h = fnv1a(g.header);
  h = fnv1a(g.main, h);
  std::string flags;
  for (const std::string& f : compile_flags()) flags += f + " ";
  h = fnv1a(std::string(build_config::cxx_compiler) + flags + runtime_include + build_config::version, h);
  h = hash_runtime_headers(runtime_include, h);
  // The library the simulator links, by content: a rebuilt runtime gives new entries.
  h = fnv1a(build_config::runtime_library, h);
  h = fnv1a(rt::read_regular_file(build_config::runtime_library, std::size_t{1} << 28).text, h);
  return hash_compiler(build_config::cxx_compiler, h);
}

std::optional<std::string> simulator_cache_root() {
  if (const char* d = std::getenv("POGEAR_CACHE_DIR"); d && *d) return std::string(d);
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return (fs::path(d) / "pogear").string();
  if (const char* d = std::getenv("HOME"); d && *d) return (fs::path(d) / ".cache" / "pogear").string();
  if (const struct passwd* pw = ::getpwuid(::geteuid()); pw && pw->pw_dir && *pw->pw_dir)
    return (fs::path(pw->pw_dir) / ".cache" / "pogear").string();
  return std::nullopt;
}

std::string why_not_private(const std::string& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0) return std::strerror(errno);
  if (S_ISLNK(st.st_mode)) return "a symbolic link";
  if (!S_ISDIR(st.st_mode)) return "not a directory";
  return why_not_ours(st);
}

CompiledSimulator::CompiledSimulator(CompiledSimulator&& other) noexcept
    : executable_(std::move(other.executable_)), temporary_dir_(std::move(other.temporary_dir_)) {
  other.temporary_dir_.clear();
}

CompiledSimulator::~CompiledSimulator() {
  if (temporary_dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(temporary_dir_, ec);
}

CompiledSimulator build_simulator(const GeneratedSources& g) {
  const std::uint64_t h = simulator_cache_key(g, build_config::runtime_include);
  std::string why_no_cache = "there is no cache directory ($POGEAR_CACHE_DIR, $XDG_CACHE_HOME and $HOME are unset)";
  if (const std::optional<std::string> root = simulator_cache_root()) {
    std::error_code ec;
    fs::create_directories(fs::path(*root).parent_path(), ec);  // ~/.cache: the user's own
    const fs::path dir = fs::path(*root) / fmt::format("{:016x}", h);
    const fs::path exe = dir / "simulator";
    std::string checked = *root, why = make_private_directory(*root);
    if (why.empty()) checked = dir.string(), why = make_private_directory(dir);
    if (why.empty()) {
      struct stat st {};
      if (::lstat(exe.c_str(), &st) != 0) return CompiledSimulator(compile_into(dir, g).string(), "");
      checked = exe.string();
      why = S_ISREG(st.st_mode) ? why_not_ours(st) : "not a regular file";
      if (why.empty()) return CompiledSimulator(exe.string(), "");
    }
    why_no_cache = fmt::format("{} is {}", checked, why);
  }
  // No cache to trust: a directory only this process knows, gone when the run is over.
  std::string dir = (fs::temp_directory_path() / "pogear-XXXXXX").string();
  if (!::mkdtemp(dir.data()))
    throw std::runtime_error(fmt::format("cannot create a temporary directory in {}: {}; set TMPDIR to a writable "
                                         "directory", fs::temp_directory_path().string(), std::strerror(errno)));
  std::cerr << "pogear: note: compiling without a cache: " << why_no_cache
            << "; set POGEAR_CACHE_DIR to a directory of your own to keep simulators\n";
  struct RemoveUnlessKept {
    std::string dir;
    bool kept = false;
    ~RemoveUnlessKept() {
      std::error_code ec;
      if (!kept) fs::remove_all(dir, ec);
    }
  } guard{dir};
  const std::string exe = compile_into(dir, g).string();
  guard.kept = true;
  return CompiledSimulator(exe, dir);
}

}  // namespace pogear
