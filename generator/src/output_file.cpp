// rename(2) within one directory is atomic, so readers see either the old file or the new one.
// The temporary files of a run are also known to a signal handler, which removes them when the
// run is interrupted, so that Ctrl-C leaves nothing behind either.
#include "output_file.hpp"

#include <array>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace pogear {
namespace {

// Paths the handler may unlink. A signal handler may only touch lock-free atomics and plain
// memory, so each slot is a fixed buffer, published by setting its flag after the path is in.
constexpr std::size_t kSlots = 8;  // the file being written + the simulators' CSVs, with room
constexpr std::size_t kPathMax = 4096;
struct Slot {
  char path[kPathMax];
  volatile std::sig_atomic_t used;
};
std::array<Slot, kSlots> slots{};
constexpr std::size_t kWriting = 0;  // slot of write_file_atomically's temporary

bool publish(std::size_t slot, const std::string& path) {
  if (path.size() >= kPathMax) return false;  // cannot be cleaned up, but still written safely
  slots[slot].used = 0;
  std::memcpy(slots[slot].path, path.c_str(), path.size() + 1);
  slots[slot].used = 1;
  return true;
}

extern "C" void remove_temporaries_and_die(int sig) {
  for (auto& s : slots)
    if (s.used) ::unlink(s.path);
  // Die of the same signal, so that the shell sees an interrupted run (status 128 + sig).
  std::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& contents) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
  publish(kWriting, tmp.string());
  struct Forget {  // once renamed or removed, the path is no business of the handler
    ~Forget() { slots[kWriting].used = 0; }
  } forget;
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    const std::string why = std::strerror(errno);  // before the clean-up can change errno
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // the removal below reuses ec
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
}

void install_interrupt_cleanup() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // e.g. under nohup
    struct sigaction sa {};
    sa.sa_handler = remove_temporaries_and_die;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

void remember_temporary(const std::string& path) {
  for (std::size_t i = kWriting + 1; i < kSlots; ++i)
    if (!slots[i].used) {
      publish(i, path);
      return;
    }
}

void remove_remembered_temporaries() {
  for (std::size_t i = kWriting + 1; i < kSlots; ++i)
    if (slots[i].used) ::unlink(slots[i].path);
}

}  // namespace pogear
