#pragma once
// Internal to the runner: the files a finished run writes into its output
// folder, each atomically.

#include <filesystem>
#include <string>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/io/model/model.hpp"
#include "argil/sculpt/run/detail/run_inputs.hpp"
#include "argil/sculpt/run/detail/run_state.hpp"
#include "argil/sculpt/session/session.hpp"

namespace argil::sculpt::detail {

/// File name of the recorded script in the output folder.
inline constexpr const char* kRecordedScriptName = "recorded.csv";

/// What a finished run wrote into its output folder, and what it could not.
struct RunOutputs {
  std::vector<std::filesystem::path> files;  // written, in order
  std::vector<OutputFailure> failures;       // not written, in order
  std::vector<std::string> warnings;         // written, but not as asked (a B-rep as loose faces)
};

/// Writes what `in.outputs` asks for into `in.out`: each model's whole file
/// with its named faces as sculpted (Session::current_file_model; STEP, IGES,
/// JSON), forces.csv, contacts.csv, timing.json, always recorded.csv and
/// summary.json (of `summary`), and the pictures of the named faces (`before`
/// holds each model's as loaded: Session::current_faces before the first
/// tick). An output that fails (a face STEP cannot take, a full disk) is
/// recorded and the others are still written.
RunOutputs write_run_outputs(const RunInputs& in, Session& session,
                             const std::vector<io::Model>& before, const RunState& state,
                             const TimingSummary& wall, const TimingSummary& cpu,
                             const RunSummary& summary);

}  // namespace argil::sculpt::detail
