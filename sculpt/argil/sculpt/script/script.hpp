#pragma once
// Scripted haptic input (docs/formats.md, "argil.script" version 1): timestamped
// tool poses with engage and release events, read from JSON or CSV, and sampled
// at the haptic rate (linear in position, slerp in orientation). A live device
// would deliver the same DeviceSample stream.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/geometry/pose.hpp"
#include "argil/core/haptic/device_sample.hpp"

namespace argil::sculpt {

inline constexpr std::string_view kScriptFormatName = "argil.script";
inline constexpr int kScriptFormatVersion = 1;

/// What happens at a keyframe: the tool starts (engage) or stops (release)
/// acting on the models; `none` only moves it; `undo` and `redo` (between
/// strokes only) take back the last finished stroke or restore the last one
/// taken back, and `tool` (between strokes only) puts another of the scene's
/// tools in the device's hand (Keyframe::tool), before the tick at or after
/// the keyframe.
enum class ScriptEvent { none, engage, release, undo, redo, tool };
const char* to_string(ScriptEvent event);

/// A device pose at a time: X_WD, the device handle D in the world [mm], a
/// unit quaternion (w, x, y, z) for its rotation ("position" and
/// "orientation" in the file formats). A script drives the device; where
/// the tool ends up (the proxy X_WT) is the tick's answer.
struct Keyframe {
  double t = 0.0;  // [s], >= 0
  Pose X_WD;
  ScriptEvent event = ScriptEvent::none;
  std::string tool{};  // ScriptEvent::tool: the scene tool the device takes
};

/// The event as the file formats write it: "engage", ..., "tool:NAME".
std::string event_text(const Keyframe& keyframe);

/// Keyframes in strictly increasing time; `tool` names the scene tool the
/// device holds first (empty: the scene's first tool).
struct Script {
  std::string tool;
  std::vector<Keyframe> keyframes;
};

/// Largest quaternion norm error accepted on input; within it the quaternion
/// is normalised (values already unit to 1e-12 are kept bit for bit, so
/// recorded scripts replay exactly).
inline constexpr double kQuaternionNormTolerance = 1e-3;

/// Parsers. `source_name` starts every error, followed by the field
/// ("keyframes[3].orientation") or, for CSV, the line and column.
Result<Script> parse_script_json(std::string_view text, const std::string& source_name);
Result<Script> parse_script_csv(std::string_view text, const std::string& source_name);
/// Reads .json or .csv (by extension, case-insensitive).
Result<Script> read_script(const std::filesystem::path& path);

/// Writers: every number in its shortest round-trip text, so reading gives the same bits.
std::string script_to_json(const Script& script);
std::string script_to_csv(const Script& script);
/// Writes .json or .csv atomically.
Status write_script(const Script& script, const std::filesystem::path& path);

/// Checks what the parsers check (times finite, >= 0, strictly increasing;
/// finite positions; unit quaternions; at least one keyframe; engage and
/// release alternating; undo, redo and tool only while not engaged; tool names
/// one word), naming the keyframe. Whether a tool is the scene's is the
/// runner's check.
Status validate(const Script& script, const std::string& source_name = "script");

/// The device's path during each engaged interval: the keyframe positions
/// from an engage through the next release (or the last keyframe), in order;
/// the device moves linearly between them. Where the tool can touch anything.
std::vector<std::vector<Eigen::Vector3d>> engaged_paths(const Script& script);

/// The tools the device holds over the script: `tool` (empty: the scene's
/// first), then each tool event's, without repeats, in order.
std::vector<std::string> tools_held(const Script& script);

/// An engaged interval: ticks first..last inclusive.
struct Stroke {
  long long first_tick = 0;
  long long last_tick = 0;
};

/// Samples a script at a fixed rate: tick k is at t_k = k / rate. Keyframe
/// times are hit exactly when they equal t_k (so a recorded stream replays bit
/// for bit); between keyframes the position is interpolated linearly and the
/// orientation by slerp; after the last keyframe it holds. The engaged state at t is set by the
/// last event at or before t. Pure: sample(k) depends on k only.
class ScriptSampler {
 public:
  /// Precondition: validate(script).ok() and rate > 0.
  ScriptSampler(Script script, double rate_hz);

  /// Ticks 0 .. tick_count() - 1 cover [0, last keyframe time]: the last tick
  /// is the first at or after the last keyframe (a keyframe up to 1e-6 tick
  /// after a tick counts as at it), so the final event is always seen.
  long long tick_count() const { return tick_count_; }
  double rate() const { return rate_; }
  DeviceSample sample(long long tick) const;
  /// An undo, redo or tool keyframe: applied before stepping `tick`, the
  /// first tick at or after its time (with the same rounding as tick_count()).
  struct Command {
    long long tick = 0;
    ScriptEvent event = ScriptEvent::undo;
    std::size_t keyframe = 0;
    std::string tool{};  // ScriptEvent::tool: the tool taken
  };
  /// The undo, redo and tool keyframes, in order.
  const std::vector<Command>& commands() const { return commands_; }
  /// The engaged intervals, in order.
  const std::vector<Stroke>& strokes() const { return strokes_; }
  const Script& script() const { return script_; }

 private:
  Script script_;
  double rate_ = 1000.0;
  long long tick_count_ = 0;
  std::vector<bool> engaged_after_;  // engaged state from keyframe k on
  std::vector<Stroke> strokes_;
  std::vector<Command> commands_;
};

/// Time of tick k at `rate_hz`, the same expression everywhere: k / rate.
inline double tick_time(long long tick, double rate_hz) {
  return static_cast<double>(tick) / rate_hz;
}

/// A script holding one keyframe per sample (with engage/release where the
/// engaged state changes) that replays the samples exactly at the same rate,
/// and each command as a keyframe midway between the tick it came before and
/// the previous one (at the previous one's pose).
Script record_script(const std::vector<DeviceSample>& samples, const std::string& tool,
                     const std::vector<ScriptSampler::Command>& commands = {});

}  // namespace argil::sculpt
