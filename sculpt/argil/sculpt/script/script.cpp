#include "argil/sculpt/script/script.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "argil/core/base/number_text.hpp"
#include "argil/io/base/atomic_write.hpp"
#include "argil/io/base/text_file.hpp"
#include "argil/sculpt/detail/json_reader.hpp"

namespace argil::sculpt {
namespace {

using internal::Json;
using internal::JsonReader;

// Exactly unit within rounding: such quaternions are kept bit for bit.
constexpr double kUnitNormRounding = 1e-12;
// A keyframe within this many ticks after a tick counts as at that tick
// (rounding of times written in decimal or computed by sums).
constexpr double kTickRounding = 1e-6;

/// The event text of a file ("engage", "tool:pin") into the keyframe; false
/// when it is none of them.
bool parse_event(std::string_view text, Keyframe& out) {
  ScriptEvent& e = out.event;
  if (text.empty() || text == "none")
    e = ScriptEvent::none;
  else if (text == "engage")
    e = ScriptEvent::engage;
  else if (text == "release")
    e = ScriptEvent::release;
  else if (text == "undo")
    e = ScriptEvent::undo;
  else if (text == "redo")
    e = ScriptEvent::redo;
  else if (text.substr(0, 5) == "tool:" && text.size() > 5) {
    e = ScriptEvent::tool;
    out.tool = std::string(text.substr(5));
  } else {
    return false;
  }
  return true;
}

constexpr const char* kEventsExpected = "engage, release, undo, redo, tool:NAME, none or nothing";

/// Checks the norm and normalises when it is not unit already; error text or "".
std::string normalise_quaternion(Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (!std::isfinite(norm) || std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    return "not a unit quaternion (w, x, y, z): norm " + number_text(norm);
  }
  if (std::abs(norm - 1.0) > kUnitNormRounding) q.coeffs() /= norm;
  return "";
}

/// What is wrong with a tool name ("" when nothing): it must be one word of
/// valid UTF-8 without spaces or control characters, so that both formats
/// (the CSV header line reads one word) carry it unchanged.
std::string tool_name_problem(const std::string& name) {
  for (std::size_t i = 0; i < name.size();) {
    const auto byte = static_cast<unsigned char>(name[i]);
    if (byte <= 0x20 || byte == 0x7f)
      return "tool name must be one word without control characters";
    // Length of the UTF-8 sequence from its lead byte; continuation bytes are 10xxxxxx.
    const std::size_t length = byte < 0x80           ? 1
                               : (byte >> 5) == 0x6  ? 2
                               : (byte >> 4) == 0xe  ? 3
                               : (byte >> 3) == 0x1e ? 4
                                                     : 0;
    if (length == 0 || i + length > name.size()) return "tool name is not valid UTF-8";
    for (std::size_t k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(name[i + k]) >> 6) != 0x2)
        return "tool name is not valid UTF-8";
    }
    // Overlong forms and surrogates are not valid UTF-8 either.
    const auto next = static_cast<unsigned char>(length > 1 ? name[i + 1] : 0);
    if ((length == 2 && byte < 0xc2) || (length == 3 && byte == 0xe0 && next < 0xa0) ||
        (length == 3 && byte == 0xed && next >= 0xa0) ||
        (length == 4 && byte == 0xf0 && next < 0x90) || (length == 4 && byte > 0xf4) ||
        (length == 4 && byte == 0xf4 && next >= 0x90)) {
      return "tool name is not valid UTF-8";
    }
    i += length;
  }
  return "";
}

/// The keyframe checks shared by both parsers and validate(); `where(k)` names
/// keyframe k in messages.
template <class Where>
Status check_keyframes(const std::vector<Keyframe>& keyframes, const std::string& source,
                       const Where& where) {
  auto error = [&](std::size_t k, const std::string& field, const std::string& what) {
    return Status::error(StatusCode::parse_error, source + ": " + where(k, field) + ": " + what);
  };
  if (keyframes.empty()) {
    return Status::error(StatusCode::parse_error, source + ": keyframes: no keyframes");
  }
  bool engaged = false;
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    const Keyframe& f = keyframes[k];
    if (!std::isfinite(f.t)) return error(k, "t", "time must be finite");
    if (f.t < 0.0) return error(k, "t", "time must be >= 0, got " + number_text(f.t));
    if (k > 0 && !(f.t > keyframes[k - 1].t)) {
      return error(k, "t",
                   "time " + number_text(f.t) + " s is not after the previous keyframe's " +
                       number_text(keyframes[k - 1].t) + " s (times must increase)");
    }
    if (!f.X_WD.p.allFinite()) return error(k, "position", "must be finite");
    const double norm = f.X_WD.R.norm();
    if (!std::isfinite(norm) || std::abs(norm - 1.0) > kQuaternionNormTolerance) {
      return error(k, "orientation",
                   "not a unit quaternion (w, x, y, z): norm " + number_text(norm));
    }
    if (f.event == ScriptEvent::engage) {
      if (engaged) return error(k, "event", "engage while already engaged");
      engaged = true;
    } else if (f.event == ScriptEvent::release) {
      if (!engaged) return error(k, "event", "release while not engaged");
      engaged = false;
    } else if (f.event == ScriptEvent::undo || f.event == ScriptEvent::redo ||
               f.event == ScriptEvent::tool) {
      if (engaged) {
        return error(k, "event", std::string(to_string(f.event)) + " while engaged: release first");
      }
      if (f.event == ScriptEvent::tool) {
        if (const std::string problem = tool_name_problem(f.tool); !problem.empty())
          return error(k, "event", problem);
        if (f.tool.find(',') != std::string::npos)
          return error(k, "event", "a tool event's name cannot hold ',' (CSV cells)");
      }
    }
  }
  return Status::success();
}

// ---- JSON -----------------------------------------------------------------

class ScriptJsonReader {
 public:
  explicit ScriptJsonReader(const std::string& source) : r_(source) {}
  Status error() const { return r_.error(); }

  bool script(const Json& root, Script& out) {
    if (!r_.only_known(root, "", {"format", "version", "tool", "keyframes"})) return false;
    if (!r_.format_header(root, kScriptFormatName, kScriptFormatVersion)) return false;
    if (const Json* tool = r_.member(root, "", "tool", false)) {
      if (!r_.string(*tool, "tool", out.tool)) return false;
      if (const std::string problem = tool_name_problem(out.tool); !problem.empty())
        return r_.fail("tool", problem);
    }
    const Json* keyframes = r_.member(root, "", "keyframes");
    if (keyframes == nullptr) return false;
    if (!keyframes->is_array()) return r_.fail("keyframes", "expected an array of keyframes");
    out.keyframes.resize(keyframes->size());
    for (std::size_t k = 0; k < keyframes->size(); ++k) {
      if (!keyframe((*keyframes)[k], JsonReader::index("keyframes", k), out.keyframes[k])) {
        return false;
      }
    }
    return true;
  }

 private:
  bool keyframe(const Json& value, const std::string& path, Keyframe& out) {
    if (!r_.only_known(value, path, {"t", "position", "orientation", "event"})) return false;
    const Json* t = r_.member(value, path, "t");
    const Json* position = r_.member(value, path, "position");
    if (t == nullptr || position == nullptr) return false;
    if (!r_.number(*t, path + ".t", out.t) ||
        !r_.numbers(*position, path + ".position", 3, out.X_WD.p.data())) {
      return false;
    }
    if (const Json* q = r_.member(value, path, "orientation", false)) {
      double wxyz[4];
      if (!r_.numbers(*q, path + ".orientation", 4, wxyz)) return false;
      out.X_WD.R = Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
      const std::string problem = normalise_quaternion(out.X_WD.R);
      if (!problem.empty()) return r_.fail(path + ".orientation", problem);
    }
    if (const Json* event = r_.member(value, path, "event", false)) {
      std::string text;
      if (!r_.string(*event, path + ".event", text)) return false;
      if (!parse_event(text, out)) {
        return r_.fail(path + ".event",
                       "expected " + std::string(kEventsExpected) + ", got \"" + text + "\"");
      }
    }
    return true;
  }

  JsonReader r_;
};

// ---- CSV ------------------------------------------------------------------

constexpr const char* kCsvColumns[] = {"t", "x", "y", "z", "qw", "qx", "qy", "qz", "event"};
constexpr std::size_t kCsvColumnCount = 9;

std::string trim(std::string_view s) {
  const std::size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return "";
  const std::size_t e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split_csv(std::string_view line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? line.npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

/// Parses a whole cell as a finite double; error text or "".
std::string parse_csv_number(const std::string& cell, double& out) {
  if (cell.empty()) return "empty cell where a number belongs";
  errno = 0;
  char* end = nullptr;
  out = std::strtod(cell.c_str(), &end);
  if (end == cell.c_str() || *end != '\0') return "expected a number, got '" + cell + "'";
  if (!std::isfinite(out) || errno == ERANGE) {
    if (std::isfinite(out)) return "";  // underflow to a subnormal or zero is fine
    return "'" + cell + "' is not allowed (finite numbers only)";
  }
  return "";
}

/// Reads a CSV script line by line: "# ..." lines declare the schema or the
/// tool, the first other line is the header, every later one a keyframe.
class CsvScriptReader {
 public:
  explicit CsvScriptReader(std::string source) : source_(std::move(source)) {}

  Result<Script> read(std::string_view text) {
    if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) {
      return Status::error(StatusCode::parse_error, source_ + ": empty file");
    }
    for (std::size_t pos = 0; pos <= text.size();) {
      const std::size_t newline = text.find('\n', pos);
      const std::string_view raw =
          text.substr(pos, newline == std::string_view::npos ? text.npos : newline - pos);
      pos = newline == std::string_view::npos ? text.size() + 1 : newline + 1;
      ++line_number_;
      if (const std::string problem = line(trim(raw)); !problem.empty()) return error(problem);
    }
    if (!header_seen_) {
      return Status::error(StatusCode::parse_error,
                           source_ + ": missing the header 't,x,y,z,qw,qx,qy,qz,event'");
    }
    const Status check =
        check_keyframes(script_.keyframes, source_, [&](std::size_t k, const std::string& field) {
          return "line " + std::to_string(lines_[k]) + ": " + field;
        });
    if (!check.ok()) return check;
    return script_;
  }

 private:
  Status error(const std::string& what) const {
    return Status::error(StatusCode::parse_error,
                         source_ + ": line " + std::to_string(line_number_) + ": " + what);
  }

  /// One trimmed line; error text or "".
  std::string line(const std::string& text) {
    if (text.empty()) return "";
    if (text[0] == '#') return comment(text);
    const std::vector<std::string> cells = split_csv(text);
    if (header_seen_) return keyframe(cells);
    header_seen_ = true;
    return header(cells, text);
  }

  /// "# argil.script version N" declares the schema; "# tool: NAME" the tool.
  std::string comment(const std::string& text) {
    std::istringstream words(text.substr(1));
    std::string first, second;
    words >> first >> second;
    if (first == kScriptFormatName) {
      long long version = -1;
      if (second != "version" || !(words >> version)) return "expected '# argil.script version 1'";
      if (version != kScriptFormatVersion) {
        return "unknown schema version " + std::to_string(version) + " (this build reads version " +
               std::to_string(kScriptFormatVersion) + ")";
      }
    } else if (first == "tool:") {
      if (second.empty()) return "tool: missing name";
      std::string rest;
      if (words >> rest) return "tool: name must be one word, got more after '" + second + "'";
      if (const std::string problem = tool_name_problem(second); !problem.empty())
        return "tool: " + problem;
      script_.tool = second;
    }
    return "";
  }

  static std::string header(const std::vector<std::string>& cells, const std::string& text) {
    bool matches = cells.size() == kCsvColumnCount || cells.size() == kCsvColumnCount - 1;
    for (std::size_t c = 0; matches && c < cells.size(); ++c) matches = cells[c] == kCsvColumns[c];
    if (matches) return "";
    return "expected the header 't,x,y,z,qw,qx,qy,qz,event', got '" + text + "'";
  }

  std::string keyframe(const std::vector<std::string>& cells) {
    if (cells.size() != kCsvColumnCount && cells.size() != kCsvColumnCount - 1) {
      return "expected 8 or 9 columns (t,x,y,z,qw,qx,qy,qz[,event]), got " +
             std::to_string(cells.size());
    }
    Keyframe f;
    double values[8];
    for (std::size_t c = 0; c < 8; ++c) {
      const std::string problem = parse_csv_number(cells[c], values[c]);
      if (!problem.empty()) return std::string(kCsvColumns[c]) + ": " + problem;
    }
    f.t = values[0];
    f.X_WD.p = Eigen::Vector3d(values[1], values[2], values[3]);
    f.X_WD.R = Eigen::Quaterniond(values[4], values[5], values[6], values[7]);
    const std::string problem = normalise_quaternion(f.X_WD.R);
    if (!problem.empty()) return "qw..qz: " + problem;
    if (cells.size() == kCsvColumnCount && !parse_event(cells[8], f)) {
      return "event: expected " + std::string(kEventsExpected) + ", got '" + cells[8] + "'";
    }
    script_.keyframes.push_back(f);
    lines_.push_back(line_number_);
    return "";
  }

  std::string source_;
  Script script_;
  std::vector<std::size_t> lines_;  // line number of each keyframe
  std::size_t line_number_ = 0;
  bool header_seen_ = false;
};

Result<Script> parse_csv(std::string_view text, const std::string& source) {
  return CsvScriptReader(source).read(text);
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::string keyframe_path(std::size_t k, const std::string& field) {
  return "keyframes[" + std::to_string(k) + "]." + field;
}

}  // namespace

const char* to_string(ScriptEvent event) {
  switch (event) {
    case ScriptEvent::none:
      return "none";
    case ScriptEvent::engage:
      return "engage";
    case ScriptEvent::release:
      return "release";
    case ScriptEvent::undo:
      return "undo";
    case ScriptEvent::redo:
      return "redo";
    case ScriptEvent::tool:
      return "tool";
  }
  return "none";
}

std::string event_text(const Keyframe& keyframe) {
  if (keyframe.event == ScriptEvent::tool) return "tool:" + keyframe.tool;
  return to_string(keyframe.event);
}

Result<Script> parse_script_json(std::string_view text, const std::string& source_name) {
  Result<Json> root = internal::parse_json_text(text, source_name);
  if (!root.ok()) return root.status();
  ScriptJsonReader reader(source_name);
  Script script;
  if (!reader.script(root.value(), script)) return reader.error();
  const Status check = check_keyframes(script.keyframes, source_name, keyframe_path);
  if (!check.ok()) return check;
  return script;
}

Result<Script> parse_script_csv(std::string_view text, const std::string& source_name) {
  return parse_csv(text, source_name);
}

Result<Script> read_script(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".json" && ext != ".csv") {
    return Status::error(StatusCode::unsupported,
                         path.string() + ": unknown script extension (expected .json or .csv)");
  }
  const Result<std::string> content = io::read_text_file(path);
  if (!content.ok()) return content.status();
  return ext == ".json" ? parse_script_json(content.value(), path.string())
                        : parse_script_csv(content.value(), path.string());
}

Status validate(const Script& script, const std::string& source_name) {
  if (const std::string problem = tool_name_problem(script.tool); !problem.empty())
    return Status::error(StatusCode::parse_error, source_name + ": tool: " + problem);
  return check_keyframes(script.keyframes, source_name, keyframe_path);
}

std::string script_to_json(const Script& script) {
  // Written by hand (not through nlohmann) to control the number format: shortest
  // round-trip text (number_text).
  std::string out = "{\n  \"format\": \"" + std::string(kScriptFormatName) +
                    "\",\n  \"version\": " + std::to_string(kScriptFormatVersion) + ",\n";
  if (!script.tool.empty()) out += "  \"tool\": " + Json(script.tool).dump() + ",\n";
  out += "  \"keyframes\": [";
  for (std::size_t k = 0; k < script.keyframes.size(); ++k) {
    const Keyframe& f = script.keyframes[k];
    out += k == 0 ? "\n" : ",\n";
    out += "    {\"t\": " + number_text(f.t) + ", \"position\": [" + number_text(f.X_WD.p.x()) +
           ", " + number_text(f.X_WD.p.y()) + ", " + number_text(f.X_WD.p.z()) +
           "], \"orientation\": [" + number_text(f.X_WD.R.w()) + ", " + number_text(f.X_WD.R.x()) +
           ", " + number_text(f.X_WD.R.y()) + ", " + number_text(f.X_WD.R.z()) + "]";
    if (f.event != ScriptEvent::none) out += ", \"event\": " + Json(event_text(f)).dump();
    out += "}";
  }
  out += "\n  ]\n}\n";
  return out;
}

std::string script_to_csv(const Script& script) {
  std::string out = "# " + std::string(kScriptFormatName) + " version " +
                    std::to_string(kScriptFormatVersion) + "\n";
  if (!script.tool.empty()) out += "# tool: " + script.tool + "\n";
  out += "t,x,y,z,qw,qx,qy,qz,event\n";
  for (const Keyframe& f : script.keyframes) {
    const double values[8] = {f.t,          f.X_WD.p.x(), f.X_WD.p.y(), f.X_WD.p.z(),
                              f.X_WD.R.w(), f.X_WD.R.x(), f.X_WD.R.y(), f.X_WD.R.z()};
    for (const double v : values) out += number_text(v) + ",";
    if (f.event != ScriptEvent::none) out += event_text(f);
    out += "\n";
  }
  return out;
}

Status write_script(const Script& script, const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".json" && ext != ".csv") {
    return Status::error(StatusCode::unsupported,
                         path.string() + ": unknown script extension (expected .json or .csv)");
  }
  const Status check = validate(script, path.string());
  if (!check.ok()) return check;
  return io::write_bytes_atomically(
      path, ext == ".json" ? script_to_json(script) : script_to_csv(script));
}

ScriptSampler::ScriptSampler(Script script, double rate_hz)
    : script_(std::move(script)), rate_(rate_hz) {
  assert(validate(script_).ok() && rate_hz > 0.0);
  const double last = script_.keyframes.back().t;
  // The last tick is the first at or after the last keyframe, so its event is
  // seen even when k / rate lands a rounding error short of it (0.5 + 0.18 is
  // 0.67999999999999994, tick 680 is 0.68).
  tick_count_ = static_cast<long long>(std::ceil(last * rate_ - kTickRounding)) + 1;
  bool engaged = false;
  engaged_after_.reserve(script_.keyframes.size());
  // A command is applied before the first tick at or after its time, but not
  // before the tick after the release it follows: a release and a command
  // within one tick would otherwise find the stroke still in progress.
  long long released_at = -1;
  for (std::size_t k = 0; k < script_.keyframes.size(); ++k) {
    const Keyframe& f = script_.keyframes[k];
    const long long tick = static_cast<long long>(std::ceil(f.t * rate_ - kTickRounding));
    if (f.event == ScriptEvent::engage) engaged = true;
    if (f.event == ScriptEvent::release) {
      engaged = false;
      released_at = tick;
    }
    engaged_after_.push_back(engaged);
    if (f.event == ScriptEvent::undo || f.event == ScriptEvent::redo ||
        f.event == ScriptEvent::tool) {
      commands_.push_back({std::max(tick, released_at + 1), f.event, k, f.tool});
    }
  }
  long long first = -1;
  for (long long t = 0; t < tick_count_; ++t) {
    const bool on = sample(t).engaged;
    if (on && first < 0) first = t;
    if (!on && first >= 0) {
      strokes_.push_back({first, t - 1});
      first = -1;
    }
  }
  if (first >= 0) strokes_.push_back({first, tick_count_ - 1});
}

DeviceSample ScriptSampler::sample(long long tick) const {
  DeviceSample s;
  s.tick = tick;
  s.t = tick_time(tick, rate_);
  const std::vector<Keyframe>& frames = script_.keyframes;
  // First keyframe after t; the segment is [next - 1, next].
  const auto next = std::upper_bound(frames.begin(), frames.end(), s.t,
                                     [](double t, const Keyframe& f) { return t < f.t; });
  if (next == frames.begin()) {
    s.X_WD.p = frames.front().X_WD.p;
    s.X_WD.R = frames.front().X_WD.R;
    s.engaged = false;
    return s;
  }
  const std::size_t k = static_cast<std::size_t>(next - frames.begin()) - 1;
  const Keyframe& a = frames[k];
  s.engaged = engaged_after_[k];
  if (next == frames.end() || s.t == a.t) {
    s.X_WD.p = a.X_WD.p;
    s.X_WD.R = a.X_WD.R;
    return s;
  }
  const Keyframe& b = *next;
  const double alpha = (s.t - a.t) / (b.t - a.t);
  s.X_WD.p = a.X_WD.p + alpha * (b.X_WD.p - a.X_WD.p);
  s.X_WD.R = a.X_WD.R.slerp(alpha, b.X_WD.R);
  return s;
}

Script record_script(const std::vector<DeviceSample>& samples, const std::string& tool,
                     const std::vector<ScriptSampler::Command>& commands) {
  Script script;
  script.tool = tool;
  bool engaged = false;
  std::size_t next_command = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const DeviceSample& s = samples[i];
    // Commands before this tick: their own keyframes midway from the previous
    // tick (the sampler maps them to this one), at the previous tick's pose.
    // Before the first tick there is nothing to undo or redo: none is kept;
    // a tool taken then goes on the first keyframe (the first sample is
    // released: a tool event cannot follow an engage).
    double gap = 0.5;  // of the tick interval, halved for each further command
    std::string first_tool;
    for (; next_command < commands.size() && commands[next_command].tick <= s.tick;
         ++next_command, gap *= 0.5) {
      if (i == 0) {
        if (commands[next_command].event == ScriptEvent::tool)
          first_tool = commands[next_command].tool;
        continue;
      }
      Keyframe c;
      c.t = s.t - gap * (s.t - samples[i - 1].t);
      c.X_WD.p = samples[i - 1].X_WD.p;
      c.X_WD.R = samples[i - 1].X_WD.R;
      c.event = commands[next_command].event;
      c.tool = commands[next_command].tool;
      script.keyframes.push_back(c);
    }
    Keyframe f;
    f.t = s.t;
    f.X_WD.p = s.X_WD.p;
    f.X_WD.R = s.X_WD.R;
    if (s.engaged != engaged) f.event = s.engaged ? ScriptEvent::engage : ScriptEvent::release;
    if (!first_tool.empty() && f.event == ScriptEvent::none) {
      f.event = ScriptEvent::tool;
      f.tool = first_tool;
    }
    engaged = s.engaged;
    script.keyframes.push_back(f);
  }
  return script;
}

std::vector<std::string> tools_held(const Script& script) {
  std::vector<std::string> tools = {script.tool};
  for (const Keyframe& k : script.keyframes) {
    if (k.event == ScriptEvent::tool &&
        std::find(tools.begin(), tools.end(), k.tool) == tools.end()) {
      tools.push_back(k.tool);
    }
  }
  return tools;
}

std::vector<std::vector<Eigen::Vector3d>> engaged_paths(const Script& script) {
  std::vector<std::vector<Eigen::Vector3d>> out;
  bool engaged = false;
  for (const Keyframe& k : script.keyframes) {
    if (k.event == ScriptEvent::engage) {
      engaged = true;
      out.emplace_back();
    }
    if (engaged) out.back().push_back(k.X_WD.p);
    if (k.event == ScriptEvent::release) engaged = false;
  }
  return out;
}

}  // namespace argil::sculpt
