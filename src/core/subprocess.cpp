// A child process with pipes, a deadline and an output cap (core/subprocess.h).
#include "core/subprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

extern char** environ;

namespace penumbra {
namespace {

// A pipe whose ends close on exec, so a child spawned by another thread inherits none.
bool makePipe(int fds[2]) { return ::pipe2(fds, O_CLOEXEC) == 0; }

void closeFd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

}  // namespace

ProcessResult runProcess(const std::string& path, const std::vector<std::string>& args, const std::string& input,
                         const ProcessLimits& limits) {
  ProcessResult out;
  int in[2] = {-1, -1}, outPipe[2] = {-1, -1};
  if (!makePipe(in) || !makePipe(outPipe)) {
    out.error = std::strerror(errno);
    closeFd(in[0]), closeFd(in[1]), closeFd(outPipe[0]), closeFd(outPipe[1]);
    return out;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, outPipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> argvStrings = {path};
  argvStrings.insert(argvStrings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : argvStrings) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, path.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  closeFd(in[0]);
  closeFd(outPipe[1]);
  if (spawned != 0) {
    out.error = std::strerror(spawned);
    closeFd(in[1]), closeFd(outPipe[0]);
    return out;
  }
  out.started = true;
  // Its stdin is written as it reads, non-blocking, beside its stdout: a child that
  // answers before reading all its input never deadlocks against this process. Writing
  // to a child that has exited raises SIGPIPE, blocked here and consumed below.
  ::fcntl(in[1], F_SETFL, ::fcntl(in[1], F_GETFL) | O_NONBLOCK);
  sigset_t pipeSignal, previous;
  sigemptyset(&pipeSignal);
  sigaddset(&pipeSignal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipeSignal, &previous);
  if (input.empty()) closeFd(in[1]);

  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                         std::chrono::duration<double>(limits.seconds));
  char buffer[1 << 16];
  size_t written = 0;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      out.timedOut = true;
      break;
    }
    pollfd p[2] = {{outPipe[0], POLLIN, 0}, {in[1], POLLOUT, 0}};
    const int ready = ::poll(p, in[1] >= 0 ? 2 : 1, int(std::min<long long>(left, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    if (in[1] >= 0 && p[1].revents) {
      const ssize_t n = ::write(in[1], input.data() + written, input.size() - written);
      if (n > 0) written += size_t(n);
      if ((n < 0 && errno != EAGAIN && errno != EINTR) || written == input.size()) closeFd(in[1]);
    }
    if (!p[0].revents) continue;
    const ssize_t n = ::read(outPipe[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of its output
    if (limits.maxOutputBytes && out.output.size() + size_t(n) > limits.maxOutputBytes) {
      out.outputCapped = true;
      break;
    }
    out.output.append(buffer, size_t(n));
  }
  closeFd(in[1]);
  const timespec none{0, 0};
  while (sigtimedwait(&pipeSignal, nullptr, &none) > 0) {
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  // Killed while its stdout is still open, so it ends by this signal and no other.
  if (out.timedOut || out.outputCapped) ::kill(pid, SIGKILL);
  closeFd(outPipe[0]);
  // Its output ended; it may still run (a closed stdout is no exit): wait up to the
  // deadline, then kill it.
  int status = 0;
  for (;;) {
    if (out.timedOut || out.outputCapped) ::kill(pid, SIGKILL);
    const pid_t done = ::waitpid(pid, &status, out.timedOut || out.outputCapped ? 0 : WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) break;
    if (done == 0) {
      if (Clock::now() >= deadline) {
        out.timedOut = true;
      } else {
        ::usleep(2000);
      }
    }
  }
  if (WIFEXITED(status)) out.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) out.signal = WTERMSIG(status);
  return out;
}

}  // namespace penumbra
