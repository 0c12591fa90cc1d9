#include "argil/sculpt/run/detail/run_outputs.hpp"

#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <variant>

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

/// The sculpted models, each the whole of its file with the named faces as
/// sculpted, exported in the formats asked for; a format that fails does not
/// stop the others. STEP and IGES edges are built at the scene's eps.
void write_models(const RunInputs& in, const Session& session, RunOutputs& outputs) {
  io::WriteOptions options;
  options.cad.tolerance_mm = in.scene.tolerance;
  options.cad.warnings = &outputs.warnings;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    const std::string& name = session.models()[static_cast<std::size_t>(m)].spec.name;
    const io::Model after = session.current_file_model(m);
    for (const auto& [wanted, extension] :
         {std::pair{in.outputs.step, ".step"}, std::pair{in.outputs.iges, ".iges"},
          std::pair{in.outputs.json, ".json"}}) {
      if (!wanted) continue;
      const std::filesystem::path path = in.out / (name + extension);
      record(outputs, path, io::write_model(after, path, options));
    }
  }
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
         write_script(record_script(state.received, in.script.tool, state.commands), recorded));
}

/// Pictures of the faces the scene names, before and after: where the tool
/// works (the whole of a large file would shrink the change to a few pixels).
void write_pictures(const RunInputs& in, const Session& session,
                    const std::vector<io::Model>& before, const RunState& state,
                    RunOutputs& outputs) {
  SessionPicturesRequest pictures;
  pictures.times = state.log.times();
  pictures.forces = state.log.forces();
  pictures.title = in.scene_name;
  pictures.tolerance_mm = in.scene.tolerance;
  for (int t = 0; t < static_cast<int>(session.scene().tools.size()); ++t) {
    PictureTool& drawn = pictures.tools.emplace_back();
    const ToolShape* shape = session.tool_shape(t);  // null: never held, never drawn
    if (const auto* sphere = shape ? std::get_if<SphereToolShape>(shape) : nullptr) {
      drawn.radius_mm = sphere->radius;
    } else if (const auto* surface = shape ? std::get_if<SurfaceToolShape>(shape) : nullptr) {
      drawn.surface = surface->surface;
    }
  }
  pictures.tool_index = state.log.tools();
  for (std::size_t m = 0; m < before.size(); ++m) {
    for (const io::FaceRecord& f : before[m].faces) pictures.before.faces.push_back(f);
    for (const io::FaceRecord& f : session.current_faces(static_cast<int>(m)).faces)
      pictures.after.faces.push_back(f);
  }
  for (const DeviceSample& s : state.received) {
    pictures.path.positions.push_back(s.X_WD.p);
    pictures.path.engaged.push_back(s.engaged);
    pictures.rotations.push_back(s.X_WD.R);
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
  write_models(in, session, outputs);
  write_logs(in, session, state, wall, cpu, outputs);
  // The path as given is relative to where the run started; the absolute one
  // lets `argil view` find the scene from anywhere.
  std::error_code failed;
  const std::filesystem::path absolute = std::filesystem::absolute(in.scene_path, failed);
  write_file(in.out / "summary.json",
             summary_json(summary, in.scene_path.string(),
                          failed ? std::string() : absolute.lexically_normal().string()),
             outputs);
  if (in.outputs.pictures) write_pictures(in, session, before, state, outputs);
  return outputs;
}

}  // namespace argil::sculpt::detail
