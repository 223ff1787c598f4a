// What pogear does when it is interrupted (SIGINT, SIGTERM, SIGHUP): remove its temporary files,
// pass the signal on to the child it is waiting for, and die of the signal as it would have.
#pragma once

#include <string>

#include <sys/types.h>

namespace pogear {

// For the command line's main. While no child runs, a signal removes the remembered temporary
// files and kills pogear with the same signal (the shell sees 128 + N). While a child runs (see
// ChildSession), the signal goes to the child's process group instead and pogear dies of it once
// the child has ended. SIGKILL cannot be caught; outputs are written so that it harms nothing
// (rt::OutputFile), and children die with pogear (PR_SET_PDEATHSIG).
void install_interrupt_cleanup();

// Temporary files that exist by name while pogear works (the simulator being compiled, the
// fallback temporary of an OutputFile), for the handler to remove. Returns a slot for forgetting.
int remember_temporary(const std::string& path);
void forget_temporary(int slot);
void remove_remembered_temporaries();

// The child process group that signals are passed on to while pogear waits for it.
class ChildSession {
 public:
  explicit ChildSession(pid_t process_group);
  ChildSession(const ChildSession&) = delete;
  ChildSession& operator=(const ChildSession&) = delete;
  // Once the child has ended: if a signal came meanwhile, pogear removes its temporaries and dies of
  // it here; the destructor alone only stops passing signals on.
  void child_ended();
  ~ChildSession();
};

}  // namespace pogear
