#include "argil/io/cad/detail/isolated_read.hpp"

#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <string_view>

#include "argil/core/base/number_text.hpp"
#include "argil/io/json/json_format.hpp"

// Under AddressSanitizer the process reserves terabytes of shadow address space,
// so an address-space limit would stop the child at once.
#if defined(__SANITIZE_ADDRESS__)
#define ARGIL_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ARGIL_ADDRESS_SANITIZER 1
#endif
#endif

namespace argil::io::detail {
namespace {

// The child's report: one byte, the StatusCode, then the model as JSON (ok) or
// the error message.
void write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

[[noreturn]] void run_child(int fd, const std::function<Result<Model>()>& read,
                            const IsolationLimits& limits) {
  // Die with the parent; crash by the default action, not by handlers the
  // parent installed (they would act on the parent's behalf).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  for (const int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGPIPE}) {
    std::signal(signal, SIG_DFL);
  }
#ifndef ARGIL_ADDRESS_SANITIZER
  if (limits.memory_limit_mb > 0) {
    const rlim_t bytes = static_cast<rlim_t>(limits.memory_limit_mb) << 20;
    const rlimit limit{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &limit);
  }
#else
  (void)limits;
#endif
  std::string report;
  try {
    const Result<Model> model = read();
    if (model.ok()) {
      const Result<std::string> json = to_json(model.value());
      report = json.ok()
                   ? std::string(1, static_cast<char>(StatusCode::ok)) + json.value()
                   : std::string(1, static_cast<char>(json.status().code)) + json.status().message;
    } else {
      report = std::string(1, static_cast<char>(model.status().code)) + model.status().message;
    }
  } catch (const std::bad_alloc&) {
    report = std::string(1, static_cast<char>(StatusCode::parse_error)) + "out of memory (limit " +
             std::to_string(limits.memory_limit_mb) + " MB)";
  } catch (...) {
    report = std::string(1, static_cast<char>(StatusCode::parse_error)) +
             "the reader threw an unknown exception";
  }
  write_all(fd, report);
  ::close(fd);
  ::_exit(0);  // no atexit handlers or destructors of the parent's state
}

/// The reader process failed (crashed, hung, died or garbled its report): the
/// code lets callers tell a contained OpenCASCADE failure from a bad file.
Status child_error(const std::string& what, const std::string& text) {
  return Status::error(StatusCode::external_failure, what + ": " + text);
}

/// What the parent collected from the child's pipe.
struct ChildReport {
  std::string bytes;
  bool timed_out = false;
};

/// Reads the pipe until it closes or the time limit passes.
ChildReport collect_report(int fd, double time_limit_s) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(time_limit_s));
  ChildReport report;
  char buffer[1 << 16];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) {
      report.timed_out = true;
      break;
    }
    pollfd wait{fd, POLLIN, 0};
    const int ready = ::poll(&wait, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of the report (or a read error)
    report.bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return report;
}

/// The model, or the error, the child's report and exit status stand for.
Result<Model> decode_report(const ChildReport& report, int status, const IsolationLimits& limits,
                            const std::string& what) {
  if (report.timed_out) {
    return child_error(what, "OpenCASCADE did not finish reading within " +
                                 number_text(limits.time_limit_s) + " s (stopped)");
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return child_error(what, "OpenCASCADE crashed reading the file (signal " +
                                 std::to_string(signal) + ", " + ::strsignal(signal) +
                                 "): malformed or beyond what it handles");
  }
  if (report.bytes.empty() || WEXITSTATUS(status) != 0) {
    return child_error(what, "the reader process ended without a result (exit status " +
                                 std::to_string(WEXITSTATUS(status)) + ")");
  }
  const auto code = static_cast<StatusCode>(static_cast<unsigned char>(report.bytes[0]));
  if (code > StatusCode::external_failure) {
    return child_error(what, "the reader process sent an unreadable report");
  }
  const std::string_view body = std::string_view(report.bytes).substr(1);
  if (code != StatusCode::ok) return Status::error(code, std::string(body));
  Result<Model> model = parse_json(body, what + " (from the reader process)");
  if (!model.ok()) return child_error(what, "reader process report: " + model.status().message);
  return model;
}

}  // namespace

Result<Model> read_in_child_process(const std::function<Result<Model>()>& read,
                                    const IsolationLimits& limits, const std::string& what) {
  int fds[2];
  if (::pipe(fds) != 0) {
    return Status::error(StatusCode::io_error,
                         what + ": cannot create a pipe: " + std::strerror(errno));
  }
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return Status::error(StatusCode::io_error,
                         what + ": cannot start the reader process: " + std::strerror(errno));
  }
  if (child == 0) {
    ::close(fds[0]);
    run_child(fds[1], read, limits);
  }
  ::close(fds[1]);
  const ChildReport report = collect_report(fds[0], limits.time_limit_s);
  ::close(fds[0]);
  if (report.timed_out) ::kill(child, SIGKILL);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  return decode_report(report, status, limits, what);
}

}  // namespace argil::io::detail
