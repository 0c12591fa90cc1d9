#include "guarded_run.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace argil::bench {
namespace {

// Wall-clock backstop, as a multiple of the CPU limit: for a child that
// blocks instead of computing.
constexpr double kWallFactor = 10.0;

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

GuardedResult run_guarded(const std::function<std::vector<double>()>& work, double limit_s) {
  GuardedResult result;
  int fds[2];
  if (pipe(fds) != 0) {
    result.detail = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  std::fflush(nullptr);  // the child must not flush the parent's buffered output again
  const pid_t child = fork();
  if (child < 0) {
    result.detail = std::string("fork: ") + std::strerror(errno);
    close(fds[0]);
    close(fds[1]);
    return result;
  }
  if (child == 0) {
    close(fds[0]);
    // The limit is CPU time (SIGXCPU), so a loaded machine does not turn a
    // slow peer into a hang; the parent's wall-clock deadline is the backstop.
    const auto seconds = static_cast<rlim_t>(std::ceil(limit_s));
    const rlimit cpu{seconds, seconds + 1};
    setrlimit(RLIMIT_CPU, &cpu);
    // Peers report through their results; SISL also prints its error stack on
    // stderr, which would bury the benchmark's table.
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDERR_FILENO);
    const std::vector<double> payload = work();
    const bool ok = write_all(fds[1], reinterpret_cast<const char*>(payload.data()),
                              payload.size() * sizeof(double));
    _exit(ok ? 0 : 3);
  }
  close(fds[1]);
  // Read while the child writes (a payload larger than the pipe's buffer
  // would otherwise block it), until end of file or the deadline.
  std::vector<char> bytes;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buffer[1 << 16];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    bytes.insert(bytes.end(), buffer, buffer + n);
  }
  close(fds[0]);
  if (timed_out) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  const bool out_of_cpu = WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU;
  if (timed_out || out_of_cpu) {
    result.outcome = GuardedResult::Outcome::timed_out;
    char text[64];
    std::snprintf(text, sizeof text, out_of_cpu ? "no return in %.0f s CPU" : "no return in %.0f s",
                  out_of_cpu ? std::ceil(limit_s) : kWallFactor * limit_s);
    result.detail = text;
  } else if (WIFSIGNALED(status)) {
    result.detail = "signal " + std::to_string(WTERMSIG(status));
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result.detail = "exit " + std::to_string(WEXITSTATUS(status));
  } else {
    result.outcome = GuardedResult::Outcome::returned;
    result.payload.resize(bytes.size() / sizeof(double));
    std::memcpy(result.payload.data(), bytes.data(), result.payload.size() * sizeof(double));
  }
  return result;
}

}  // namespace argil::bench
