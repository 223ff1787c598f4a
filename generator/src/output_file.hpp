// Writing outputs so that a failed or interrupted run never leaves a half-written file where a
// good one was: write a temporary file beside the target, then rename it over the target.
#pragma once

#include <string>

namespace pogear {

// Throws std::runtime_error with a message naming the path when it cannot write.
void write_file_atomically(const std::string& path, const std::string& contents);

// For the command line's main: on SIGINT, SIGTERM or SIGHUP, removes the temporary file being
// written (and those remembered below), then dies of the signal as it would have. SIGKILL cannot
// be caught: after it a `.name.tmpPID` or `name.csv.tmp` may stay beside the (intact) target.
void install_interrupt_cleanup();

// Temporary files that something else writes for this run (a simulator's `name.csv.tmp`), for
// the interrupt handler to remove; remove_remembered_temporaries() removes them at once, for
// when a child process died of the signal while pogear waited for it.
void remember_temporary(const std::string& path);
void remove_remembered_temporaries();

}  // namespace pogear
