#include "argil/core/base/status.hpp"

namespace argil {

const char* to_string(StatusCode code) {
  switch (code) {
    case StatusCode::ok:
      return "ok";
    case StatusCode::invalid_argument:
      return "invalid_argument";
    case StatusCode::invalid_surface:
      return "invalid_surface";
    case StatusCode::io_error:
      return "io_error";
    case StatusCode::parse_error:
      return "parse_error";
    case StatusCode::unsupported:
      return "unsupported";
    case StatusCode::numerical_failure:
      return "numerical_failure";
    case StatusCode::failed_precondition:
      return "failed_precondition";
    case StatusCode::external_failure:
      return "external_failure";
  }
  return "unknown";
}

}  // namespace argil
