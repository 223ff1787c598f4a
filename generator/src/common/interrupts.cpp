// The signal handler may only touch lock-free atomics and plain memory: each temporary's path is a
// fixed buffer published by a flag, and the child's process group one sig_atomic_t.
#include "common/interrupts.hpp"

#include <array>
#include <csignal>
#include <cstring>

#include <unistd.h>

namespace pogear {
namespace {

constexpr std::size_t kSlots = 8;  // the file being written + the simulator binary, with room
constexpr std::size_t kPathMax = 4096;
struct Slot {
  char path[kPathMax];
  volatile std::sig_atomic_t used;
};
std::array<Slot, kSlots> slots{};
volatile std::sig_atomic_t child_group = 0;    // > 0 while a child runs
volatile std::sig_atomic_t pending_signal = 0;  // a signal that came while it ran

void remove_temporaries() {
  for (auto& s : slots)
    if (s.used) ::unlink(s.path);
}

[[noreturn]] void die_of(int sig) {
  remove_temporaries();
  // Die of the same signal, so that the shell sees an interrupted run (status 128 + sig).
  std::signal(sig, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);
}

extern "C" void on_interrupt(int sig) {
  if (child_group > 0) {
    // The child cleans up after itself; pogear waits for it and then dies of the signal.
    pending_signal = sig;
    ::kill(-static_cast<pid_t>(child_group), sig);
    return;
  }
  die_of(sig);
}

}  // namespace

void install_interrupt_cleanup() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;  // e.g. under nohup
    struct sigaction sa {};
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
  }
}

int remember_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;  // cannot be cleaned up on a signal, but still written safely
  for (std::size_t i = 0; i < kSlots; ++i)
    if (!slots[i].used) {
      std::memcpy(slots[i].path, path.c_str(), path.size() + 1);
      slots[i].used = 1;
      return static_cast<int>(i);
    }
  return -1;
}

void forget_temporary(int slot) {
  if (slot >= 0 && static_cast<std::size_t>(slot) < kSlots) slots[static_cast<std::size_t>(slot)].used = 0;
}

void remove_remembered_temporaries() { remove_temporaries(); }

ChildSession::ChildSession(pid_t process_group) {
  pending_signal = 0;
  child_group = process_group;
}

void ChildSession::child_ended() {
  child_group = 0;
  if (pending_signal) die_of(pending_signal);
}

ChildSession::~ChildSession() { child_group = 0; }

}  // namespace pogear
