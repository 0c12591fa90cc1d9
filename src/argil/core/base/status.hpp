#pragma once
// Status and Result<T>: how argil reports failure at its boundaries (validation,
// loaders, CLI). Hot paths assert preconditions instead.

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace argil {

enum class StatusCode {
  ok,
  invalid_argument,   // a caller-supplied value is outside the documented range
  invalid_surface,    // a surface failed validation
  io_error,           // a file could not be opened, read or written
  parse_error,        // a file was read but its content is malformed
  unsupported,        // well-formed input that argil does not handle
  numerical_failure,  // a computation lost its guarantees (singular system, ...)
  // State found in place prevents the operation, and starting afresh would not
  // (an output folder holding another run's unfinished journal).
  failed_precondition,
  // A contained third-party component crashed, hung or ended without a result.
  external_failure,  // keep last: the CAD reader process checks codes against it
};

/// Name of a status code, for messages ("invalid_surface").
const char* to_string(StatusCode code);

/// Outcome of an operation: ok, or a code and a message that names the file,
/// entity or field at fault and what is wrong with it.
struct [[nodiscard]] Status {
  StatusCode code = StatusCode::ok;
  std::string message;

  bool ok() const { return code == StatusCode::ok; }
  static Status success() { return {}; }
  static Status error(StatusCode code, std::string message) { return {code, std::move(message)}; }
};

/// A value, or the Status that explains why there is none.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}        // NOLINT: implicit by design
  Result(Status status) : data_(std::move(status)) {  // NOLINT: implicit by design
    assert(!std::get<Status>(data_).ok() && "Result needs a value or an error");
  }

  bool ok() const { return std::holds_alternative<T>(data_); }
  const T& value() const& {
    assert(ok());
    return std::get<T>(data_);
  }
  T& value() & {
    assert(ok());
    return std::get<T>(data_);
  }
  T&& value() && {
    assert(ok());
    return std::get<T>(std::move(data_));
  }
  /// The error; a success status when the result holds a value.
  Status status() const { return ok() ? Status::success() : std::get<Status>(data_); }

 private:
  std::variant<T, Status> data_;
};

}  // namespace argil
