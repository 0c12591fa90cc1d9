#include "argil/sculpt/run/detail/run_outputs.hpp"

#include <string>
#include <utility>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/output/session_pictures.hpp"

namespace argil::sculpt::detail {
namespace {

/// Records one output: written, or failed with why.
void record(RunOutputs& outputs, const std::filesystem::path& path, const Status& written) {
  if (written.ok()) {
    outputs.files.push_back(path);
  } else {
    outputs.failures.push_back({path, written});
  }
}

/// The sculpted models, each exported in the formats asked for; a format that
/// fails does not stop the others. STEP and IGES edges are built at the scene's eps.
std::vector<io::Model> write_models(const RunInputs& in, Session& session, RunOutputs& outputs) {
  io::WriteOptions options;
  options.cad.tolerance_mm = in.scene.tolerance;
  std::vector<io::Model> after;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    const std::string& name = session.models()[static_cast<std::size_t>(m)].spec.name;
    after.push_back(session.current_model(m));
    for (const auto& [wanted, extension] :
         {std::pair{in.outputs.step, ".step"}, std::pair{in.outputs.iges, ".iges"},
          std::pair{in.outputs.json, ".json"}}) {
      if (!wanted) continue;
      const std::filesystem::path path = in.out / (name + extension);
      record(outputs, path, io::write_model(after.back(), path, options));
    }
  }
  return after;
}

void write_file(const std::filesystem::path& path, const std::string& bytes, RunOutputs& outputs) {
  record(outputs, path, io::write_bytes_atomically(path, bytes));
}

void write_logs(const RunInputs& in, const Session& session, const RunState& state,
                const TimingSummary& wall, const TimingSummary& cpu, RunOutputs& outputs) {
  std::vector<std::string> model_names;
  for (const LoadedModel& loaded : session.models()) model_names.push_back(loaded.spec.name);
  if (in.outputs.forces) write_file(in.out / "forces.csv", state.log.forces_csv(), outputs);
  if (in.outputs.contacts) {
    write_file(in.out / "contacts.csv", state.log.contacts_csv(model_names), outputs);
  }
  if (in.outputs.timing) {
    write_file(in.out / "timing.json", timing_json(wall, cpu, in.scene_path.string()), outputs);
  }
  const std::filesystem::path recorded = in.out / kRecordedScriptName;
  record(outputs, recorded,
         write_script(record_script(state.received, session.tool().name), recorded));
}

void write_pictures(const RunInputs& in, const std::vector<io::Model>& before,
                    const std::vector<io::Model>& after, const RunState& state,
                    RunOutputs& outputs) {
  SessionPicturesRequest pictures;
  pictures.times = state.log.times();
  pictures.forces = state.log.forces();
  pictures.title = in.scene_name;
  for (std::size_t m = 0; m < after.size(); ++m) {
    for (const io::FaceRecord& f : before[m].faces) pictures.before.faces.push_back(f);
    for (const io::FaceRecord& f : after[m].faces) pictures.after.faces.push_back(f);
  }
  for (const DeviceSample& s : state.received) {
    pictures.path.positions.push_back(s.X_WD.p);
    pictures.path.engaged.push_back(s.engaged);
  }
  const Status drawn = write_session_pictures(pictures, in.out);
  if (!drawn.ok()) {
    // The three pictures are drawn together: the failure is the folder's.
    outputs.failures.push_back({in.out, drawn});
    return;
  }
  for (const char* name : {kBeforePicture, kAfterPicture, kForcePicture}) {
    outputs.files.push_back(in.out / name);
  }
}

}  // namespace

RunOutputs write_run_outputs(const RunInputs& in, Session& session,
                             const std::vector<io::Model>& before, const RunState& state,
                             const TimingSummary& wall, const TimingSummary& cpu,
                             const RunSummary& summary) {
  RunOutputs outputs;
  const std::vector<io::Model> after = write_models(in, session, outputs);
  write_logs(in, session, state, wall, cpu, outputs);
  write_file(in.out / "summary.json", summary_json(summary, in.scene_path.string()), outputs);
  if (in.outputs.pictures) write_pictures(in, before, after, state, outputs);
  return outputs;
}

}  // namespace argil::sculpt::detail
