#pragma once
// Internal to argil_io: runs a model reader in a child process, so that a crash,
// hang or memory blow-up inside a third-party parser (OpenCASCADE on a
// malformed file) becomes an error status instead of taking the caller down.

#include <cstddef>
#include <functional>
#include <string>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"

namespace argil::io::detail {

struct IsolationLimits {
  double time_limit_s = 600.0;         // wall clock; the child is killed after it
  std::size_t memory_limit_mb = 8192;  // child address space; 0: none
};

/// Forks, runs `read` in the child and returns its result to the parent through
/// a pipe as argil JSON (bit-exact doubles; invalid UTF-8 in names and metadata
/// is replaced, as to_json() does). `what` names the input in messages ("file.step").
/// A child killed by a signal, over the time limit or unable to report gives
/// StatusCode::external_failure naming the signal or the limit.
Result<Model> read_in_child_process(const std::function<Result<Model>()>& read,
                                    const IsolationLimits& limits, const std::string& what);

}  // namespace argil::io::detail
