// A child process with pipes, a deadline and an output cap (core/subprocess.h).
#include "core/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

extern char** environ;

namespace penumbra {
namespace {

using Clock = std::chrono::steady_clock;

// A deadline beyond any run, and small enough for the clock's nanoseconds.
constexpr double kLongestSeconds = 1e7;

void closeFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

// Everything one run holds, released on every way out (an exception included): the
// pipes closed, a child still running killed and reaped, SIGPIPE's mask restored.
struct Run {
  int in[2] = {-1, -1}, out[2] = {-1, -1};
  pid_t pid = -1;
  bool reaped = false, masked = false;
  sigset_t previousMask{};
  ~Run() {
    for (int* fd : {&in[0], &in[1], &out[0], &out[1]}) closeFd(*fd);
    if (pid > 0 && !reaped) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
    if (masked) {
      // A SIGPIPE raised by writing to a child that had exited: consumed, not delivered.
      sigset_t pipeSignal;
      sigemptyset(&pipeSignal);
      sigaddset(&pipeSignal, SIGPIPE);
      const timespec none{0, 0};
      while (sigtimedwait(&pipeSignal, nullptr, &none) > 0) {
      }
      pthread_sigmask(SIG_SETMASK, &previousMask, nullptr);
    }
  }
};

}  // namespace

ProcessResult runProcess(const std::string& path, const std::vector<std::string>& args, const std::string& input,
                         const ProcessLimits& limits) {
  ProcessResult result;
  std::vector<std::string> argvStrings = {path};
  argvStrings.insert(argvStrings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : argvStrings) argv.push_back(s.data());
  argv.push_back(nullptr);

  Run run;
  // Pipes whose ends close on exec, so a child spawned by another thread inherits none.
  if (::pipe2(run.in, O_CLOEXEC) != 0 || ::pipe2(run.out, O_CLOEXEC) != 0) {
    result.error = std::strerror(errno);
    return result;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, run.in[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, run.out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclosefrom_np(&actions, STDERR_FILENO + 1);  // opened without O_CLOEXEC too
  // The child starts with no signal blocked and every signal at its default action,
  // whatever the calling thread had.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &all);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  const int spawned = ::posix_spawn(&run.pid, path.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  closeFd(run.in[0]);
  closeFd(run.out[1]);
  if (spawned != 0) {
    run.pid = -1;
    result.error = std::strerror(spawned);
    return result;
  }
  result.started = true;
  // Its stdin is written as it reads, non-blocking, beside its stdout: a child that
  // answers before reading all its input never deadlocks against this process.
  ::fcntl(run.in[1], F_SETFL, ::fcntl(run.in[1], F_GETFL) | O_NONBLOCK);
  sigset_t pipeSignal;
  sigemptyset(&pipeSignal);
  sigaddset(&pipeSignal, SIGPIPE);
  run.masked = pthread_sigmask(SIG_BLOCK, &pipeSignal, &run.previousMask) == 0;
  if (input.empty()) closeFd(run.in[1]);

  const double seconds = std::clamp(limits.seconds, 0.0, kLongestSeconds);
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  char buffer[1 << 16];
  size_t written = 0;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      result.timedOut = true;
      break;
    }
    pollfd p[2] = {{run.out[0], POLLIN, 0}, {run.in[1], POLLOUT, 0}};
    const int ready = ::poll(p, run.in[1] >= 0 ? 2 : 1, int(std::min<long long>(left, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    if (run.in[1] >= 0 && p[1].revents) {
      const ssize_t n = ::write(run.in[1], input.data() + written, input.size() - written);
      if (n > 0) written += size_t(n);
      if ((n < 0 && errno != EAGAIN && errno != EINTR) || written == input.size()) closeFd(run.in[1]);
    }
    if (!p[0].revents) continue;
    const ssize_t n = ::read(run.out[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of its output
    if (limits.maxOutputBytes && result.output.size() + size_t(n) > limits.maxOutputBytes) {
      result.outputCapped = true;
      break;
    }
    result.output.append(buffer, size_t(n));
  }
  // Killed while its stdout is still open, so it ends by this signal and no other.
  if (result.timedOut || result.outputCapped) ::kill(run.pid, SIGKILL);
  closeFd(run.in[1]);
  closeFd(run.out[0]);
  // Its output ended; it may still run (a closed stdout is no exit): wait up to the
  // deadline, then kill it.
  int status = 0;
  for (;;) {
    const bool killed = result.timedOut || result.outputCapped;
    const pid_t done = ::waitpid(run.pid, &status, killed ? 0 : WNOHANG);
    if (done == run.pid) {
      run.reaped = true;
      break;
    }
    if (done < 0 && errno == EINTR) continue;
    if (done < 0) {  // ECHILD: someone else reaped it (SIGCHLD ignored); its status is lost
      run.reaped = true;
      return result;
    }
    if (Clock::now() >= deadline) {
      result.timedOut = true;
      ::kill(run.pid, SIGKILL);
    } else {
      ::usleep(2000);
    }
  }
  if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  return result;
}

}  // namespace penumbra
