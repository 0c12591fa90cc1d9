#include "argil/sculpt/run/detail/run_outputs.hpp"

#include <string>
#include <utility>

#include "argil/io/base/atomic_write.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/output/session_pictures.hpp"

namespace argil::sculpt::detail {
namespace {

using Files = std::vector<std::filesystem::path>;

/// The sculpted models, each exported in the formats asked for.
Result<std::vector<io::Model>> write_models(const RunInputs& in, Session& session, Files& files) {
  std::vector<io::Model> after;
  for (int m = 0; m < static_cast<int>(session.models().size()); ++m) {
    const std::string& name = session.models()[static_cast<std::size_t>(m)].spec.name;
    after.push_back(session.current_model(m));
    for (const auto& [wanted, extension] :
         {std::pair{in.outputs.step, ".step"}, std::pair{in.outputs.iges, ".iges"},
          std::pair{in.outputs.json, ".json"}}) {
      if (!wanted) continue;
      const std::filesystem::path path = in.out / (name + extension);
      const Status written = io::write_model(after.back(), path);
      if (!written.ok()) return written;
      files.push_back(path);
    }
  }
  return after;
}

Status write_file(const std::filesystem::path& path, const std::string& bytes, Files& files) {
  const Status written = io::write_bytes_atomically(path, bytes);
  if (written.ok()) files.push_back(path);
  return written;
}

Status write_logs(const RunInputs& in, const Session& session, const RunState& state,
                  const TimingSummary& wall, const TimingSummary& cpu, Files& files) {
  std::vector<std::string> model_names;
  for (const LoadedModel& loaded : session.models()) model_names.push_back(loaded.spec.name);
  Status s = Status::success();
  if (in.outputs.forces) s = write_file(in.out / "forces.csv", state.log.forces_csv(), files);
  if (s.ok() && in.outputs.contacts) {
    s = write_file(in.out / "contacts.csv", state.log.contacts_csv(model_names), files);
  }
  if (s.ok() && in.outputs.timing) {
    s = write_file(in.out / "timing.json", timing_json(wall, cpu, in.scene_path.string()), files);
  }
  if (!s.ok()) return s;
  const std::filesystem::path recorded = in.out / kRecordedScriptName;
  s = write_script(record_script(state.received, session.tool().name), recorded);
  if (s.ok()) files.push_back(recorded);
  return s;
}

Status write_pictures(const RunInputs& in, const std::vector<io::Model>& before,
                      const std::vector<io::Model>& after, const RunState& state, Files& files) {
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
  const Status s = write_session_pictures(pictures, in.out);
  if (!s.ok()) return s;
  for (const char* name : {kBeforePicture, kAfterPicture, kForcePicture}) {
    files.push_back(in.out / name);
  }
  return Status::success();
}

}  // namespace

Result<std::vector<std::filesystem::path>> write_run_outputs(const RunInputs& in, Session& session,
                                                             const std::vector<io::Model>& before,
                                                             const RunState& state,
                                                             const TimingSummary& wall,
                                                             const TimingSummary& cpu) {
  Files files;
  Result<std::vector<io::Model>> after = write_models(in, session, files);
  if (!after.ok()) return after.status();
  const Status logged = write_logs(in, session, state, wall, cpu, files);
  if (!logged.ok()) return logged;
  if (in.outputs.pictures) {
    const Status drawn = write_pictures(in, before, after.value(), state, files);
    if (!drawn.ok()) return drawn;
  }
  return files;
}

}  // namespace argil::sculpt::detail
