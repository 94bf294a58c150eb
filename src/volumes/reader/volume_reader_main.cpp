// penumbra-volumes: reads one .vdb file for penumbra (core/density_codec.h). The job
// comes on stdin, the grid or the problem in words goes to stdout; OpenVDB's allocations
// run under the job's cap, and whatever else goes wrong ends this process, not penumbra.
#include "core/density_codec.h"
#include "core/density_wire.h"
#include "volumes/reader/capped_allocator.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

namespace {

std::string readAll(int fd) {
  std::string bytes;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return bytes;
    bytes.append(buffer, size_t(n));
  }
}

bool writeAll(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

}  // namespace

int main() {
  // Ends with penumbra, whatever ends penumbra.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() == 1) return 5;
  // The answer goes to a descriptor of its own: anything OpenVDB or its libraries print
  // to stdout goes nowhere.
  const int answerFd = ::dup(STDOUT_FILENO);
  const int devNull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (answerFd < 0 || devNull < 0 || ::dup2(devNull, STDOUT_FILENO) < 0) return 6;
  penumbra::DensityJob job;
  if (!penumbra::decodeJob(readAll(STDIN_FILENO), job)) return 3;  // not run by penumbra
  // Its own deadline too, should penumbra's wait not end it.
  if (job.seconds > 0.0) ::alarm(static_cast<unsigned>(std::min(job.seconds, 1e6)) + 1);
  penumbra::DensityGrid grid;
  std::string problem;
  penumbra::volumes::setAllocationCap(job.memoryCap);
  try {
    problem = penumbra::densityModule().load(job.path, job.request, grid);
  } catch (const std::bad_alloc&) {
    problem = fmt::format("cannot be read (OpenVDB asked for more than the reader's {} MiB)", job.memoryCap >> 20);
  } catch (const std::exception& e) {
    problem = fmt::format("cannot be read ({})", e.what());
  }
  // The lattice passed the voxel budget; its copy on the way out is not OpenVDB's.
  penumbra::volumes::setAllocationCap(0);
  const bool written = writeAll(answerFd, penumbra::encodeAnswer(problem, grid));
  // No exit handlers: nothing of OpenVDB's teardown can change the answer now.
  std::_Exit(written ? 0 : 4);
}
