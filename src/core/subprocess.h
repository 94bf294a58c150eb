// Runs a helper executable as a child process: bytes in on its stdin, its stdout back,
// under a deadline and an output cap. For readers of untrusted files (the OpenVDB
// reader): whatever the child does, the caller gets an answer, never its crash or hang.
#pragma once
#include <string>
#include <vector>

namespace penumbra {

struct ProcessLimits {
  double seconds = 60.0;       // killed (SIGKILL) when still running after this long
  size_t maxOutputBytes = 0;   // killed when its stdout grows past this (0: no cap)
};

struct ProcessResult {
  bool started = false;      // false: could not be spawned (`error` says why)
  bool timedOut = false;     // killed at the deadline
  bool outputCapped = false; // killed for writing more than maxOutputBytes
  int exitCode = -1;         // its exit status when it exited, else -1 (also when its
                             // status was lost: SIGCHLD ignored)
  int signal = 0;            // the signal that ended it, else 0
  std::string output;        // everything it wrote to stdout
  std::string error;         // why it could not be spawned
};

// Spawns `path` with `args` (argv[1...]), writes `input` to its stdin and closes it,
// collects its stdout; its stderr goes to /dev/null. The child gets no other file
// descriptor, no blocked signal and every signal's default action. Thread-safe; on
// every way out (an exception too) the child is gone and reaped.
ProcessResult runProcess(const std::string& path, const std::vector<std::string>& args, const std::string& input,
                         const ProcessLimits& limits);

}  // namespace penumbra
