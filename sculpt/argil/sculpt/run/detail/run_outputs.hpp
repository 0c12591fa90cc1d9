#pragma once
// Internal to the runner: the files a finished run writes into its output
// folder, each atomically.

#include <filesystem>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/run/detail/run_inputs.hpp"
#include "argil/sculpt/run/detail/run_state.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt::detail {

/// File name of the recorded script in the output folder.
inline constexpr const char* kRecordedScriptName = "recorded.csv";

/// Writes what `in.outputs` asks for into `in.out`: each model's sculpted
/// faces (STEP, IGES, JSON), forces.csv, contacts.csv, timing.json, always
/// recorded.csv, and the pictures (`before` holds each model as loaded).
/// Returns the files written, in that order.
Result<std::vector<std::filesystem::path>> write_run_outputs(const RunInputs& in, Session& session,
                                                             const std::vector<io::Model>& before,
                                                             const RunState& state,
                                                             const TimingSummary& wall,
                                                             const TimingSummary& cpu);

}  // namespace argil::sculpt::detail
