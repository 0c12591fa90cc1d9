#include "argil/sculpt/session/journal.hpp"

#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "argil/io/base/text_file.hpp"
#include "argil/sculpt/detail/fnv_hash.hpp"

namespace argil::sculpt {

namespace {

constexpr std::string_view kMagic = "argil.journal 1";
constexpr std::string_view kCheckTag = " check=";

std::string hex64(std::uint64_t value) {
  char buffer[20];
  std::snprintf(buffer, sizeof buffer, "%016" PRIx64, value);
  return buffer;
}

bool parse_hex64(const std::string& text, std::uint64_t& out) {
  if (text.size() != 16) return false;
  char* end = nullptr;
  out = std::strtoull(text.c_str(), &end, 16);
  return end == text.c_str() + text.size();
}

/// Hexadecimal floating point ("%a"): exact and locale-free.
void append_double(std::string& out, double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  out += buffer;
}

bool parse_double(const std::string& text, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(out);
}

std::string sample_text(const DeviceSample& s) {
  std::string out = std::to_string(s.tick);
  const double values[] = {s.t,          s.X_WD.p.x(), s.X_WD.p.y(), s.X_WD.p.z(),
                           s.X_WD.R.w(), s.X_WD.R.x(), s.X_WD.R.y(), s.X_WD.R.z()};
  for (const double v : values) {
    out += ' ';
    append_double(out, v);
  }
  out += s.engaged ? " 1" : " 0";
  return out;
}

/// Parses a record body (the line without its check); false when malformed.
bool parse_record(const std::string& body, JournalRecord& out) {
  std::istringstream in(body);
  std::string kind;
  in >> kind;
  if (kind == "undo" || kind == "redo") {
    out.kind = kind == "undo" ? JournalRecord::Kind::undo : JournalRecord::Kind::redo;
  } else if (kind == "tool") {
    out.kind = JournalRecord::Kind::tool;
    if (!(in >> out.tool) || out.tool < 0) return false;
  } else if (kind == "stroke") {
    out.kind = JournalRecord::Kind::stroke;
    long long count = 0;
    if (!(in >> count) || count < 0 || count > 100000000) return false;
    out.samples.resize(static_cast<std::size_t>(count));
    for (DeviceSample& s : out.samples) {
      std::string t[9];
      int engaged = 0;
      if (!(in >> s.tick)) return false;
      for (std::string& word : t) {
        if (!(in >> word)) return false;
      }
      double v[8];
      for (int k = 0; k < 8; ++k) {
        if (!parse_double(t[k], v[k])) return false;
      }
      engaged = t[8] == "1" ? 1 : (t[8] == "0" ? 0 : -1);
      if (engaged < 0) return false;
      s.t = v[0];
      s.X_WD.p = Eigen::Vector3d(v[1], v[2], v[3]);
      s.X_WD.R = Eigen::Quaterniond(v[4], v[5], v[6], v[7]);
      s.engaged = engaged == 1;
    }
    for (std::size_t k = 1; k < out.samples.size(); ++k) {
      if (out.samples[k].tick != out.samples[k - 1].tick + 1) return false;
    }
  } else {
    return false;
  }
  std::string state;
  if (!(in >> state) || state.rfind("state=", 0) != 0 ||
      !parse_hex64(state.substr(6), out.state_hash)) {
    return false;
  }
  std::string rest;
  return !(in >> rest);
}

std::string record_body(const JournalRecord& record) {
  std::string body;
  if (record.kind == JournalRecord::Kind::stroke) {
    body = "stroke " + std::to_string(record.samples.size());
    for (const DeviceSample& s : record.samples) body += "  " + sample_text(s);
  } else if (record.kind == JournalRecord::Kind::tool) {
    body = "tool " + std::to_string(record.tool);
  } else {
    body = record.kind == JournalRecord::Kind::undo ? "undo" : "redo";
  }
  return body + " state=" + hex64(record.state_hash);
}

std::string header_body(const JournalHeader& h) {
  std::string body = std::string(kMagic) + " scene=" + hex64(h.scene_hash) +
                     " script=" + hex64(h.script_hash) + " rate=";
  append_double(body, h.haptic_rate);
  return body;
}

bool parse_header(const std::string& body, JournalHeader& out) {
  std::istringstream words(body);
  std::string magic, version, scene, script, rate;
  words >> magic >> version >> scene >> script >> rate;
  return magic + " " + version == kMagic && scene.rfind("scene=", 0) == 0 &&
         script.rfind("script=", 0) == 0 && rate.rfind("rate=", 0) == 0 &&
         parse_hex64(scene.substr(6), out.scene_hash) &&
         parse_hex64(script.substr(7), out.script_hash) &&
         parse_double(rate.substr(5), out.haptic_rate);
}

/// Splits "body check=XXXXXXXXXXXXXXXX" and verifies the checksum.
bool checked_body(const std::string& line, std::string& body) {
  const std::size_t at = line.rfind(kCheckTag);
  if (at == std::string::npos) return false;
  std::uint64_t check = 0;
  if (!parse_hex64(line.substr(at + kCheckTag.size()), check)) return false;
  body = line.substr(0, at);
  return fnv1a64(body) == check;
}

}  // namespace

const char* to_string(JournalFault fault) {
  switch (fault) {
    case JournalFault::none:
      return "none";
    case JournalFault::unreadable:
      return "unreadable";
    case JournalFault::torn_header:
      return "torn_header";
    case JournalFault::not_a_journal:
      return "not_a_journal";
    case JournalFault::damaged_record:
      return "damaged_record";
    case JournalFault::malformed_record:
      return "malformed_record";
    case JournalFault::record_after_end:
      return "record_after_end";
  }
  return "unknown";
}

JournalRead read_journal(const std::filesystem::path& path) {
  const Result<std::string> content = io::read_text_file(path);
  if (!content.ok()) return {JournalFault::unreadable, content.status(), {}};
  const std::string& text = content.value();
  JournalRead out;
  JournalContents& contents = out.contents;
  std::size_t pos = 0;
  int line_number = 0;
  auto fail = [&](JournalFault fault, const std::string& what) {
    out.fault = fault;
    out.status =
        Status::error(StatusCode::parse_error,
                      path.string() + ": line " + std::to_string(line_number) + ": " + what);
    return out;
  };
  while (pos < text.size()) {
    const std::size_t newline = text.find('\n', pos);
    ++line_number;
    std::string body;
    const bool complete = newline != std::string::npos;
    const std::string line = text.substr(pos, complete ? newline - pos : std::string::npos);
    const bool intact = complete && checked_body(line, body);
    const bool last = !complete || newline + 1 == text.size();
    if (!intact) {
      // Only the last line can be torn by a crash; damage before it is corruption.
      if (!last) {
        return fail(JournalFault::damaged_record,
                    "damaged record (checksum mismatch) before intact ones");
      }
      contents.dropped_torn_record = true;
      break;
    }
    if (line_number == 1) {
      if (!parse_header(body, contents.header)) {
        return fail(JournalFault::not_a_journal, "not an argil journal (expected the header '" +
                                                     std::string(kMagic) +
                                                     " scene=... script=... rate=...')");
      }
    } else if (body == "end") {
      contents.finished = true;
    } else {
      if (contents.finished)
        return fail(JournalFault::record_after_end, "record after the end record");
      JournalRecord record;
      if (!parse_record(body, record))
        return fail(JournalFault::malformed_record, "malformed record");
      contents.records.push_back(std::move(record));
    }
    pos = newline + 1;
    contents.valid_bytes = pos;
  }
  if (contents.valid_bytes == 0) {
    out.fault = JournalFault::torn_header;
    out.status = Status::error(StatusCode::parse_error, path.string() + ": empty or torn header");
  }
  return out;
}

Result<JournalWriter> JournalWriter::create(const std::filesystem::path& path,
                                            const JournalHeader& header) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return Status::error(StatusCode::io_error,
                         path.string() + ": cannot create journal: " + std::strerror(errno));
  }
  JournalWriter writer(file, path);
  const Status written = writer.write_line(header_body(header));
  if (!written.ok()) return written;
  return writer;
}

Result<JournalWriter> JournalWriter::append_to(const std::filesystem::path& path,
                                               const JournalContents& contents) {
  std::error_code ec;
  std::filesystem::resize_file(path, contents.valid_bytes, ec);
  if (ec) {
    return Status::error(StatusCode::io_error,
                         path.string() + ": cannot cut the torn record: " + ec.message());
  }
  std::FILE* file = std::fopen(path.c_str(), "ab");
  if (file == nullptr) {
    return Status::error(StatusCode::io_error,
                         path.string() + ": cannot open journal: " + std::strerror(errno));
  }
  return JournalWriter(file, path);
}

JournalWriter::JournalWriter(JournalWriter&& other) noexcept
    : file_(other.file_), path_(std::move(other.path_)) {
  other.file_ = nullptr;
}

JournalWriter& JournalWriter::operator=(JournalWriter&& other) noexcept {
  if (this != &other) {
    if (file_ != nullptr) std::fclose(file_);
    file_ = other.file_;
    path_ = std::move(other.path_);
    other.file_ = nullptr;
  }
  return *this;
}

JournalWriter::~JournalWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

Status JournalWriter::append(const JournalRecord& record) {
  return write_line(record_body(record));
}

Status JournalWriter::finish() { return write_line("end"); }

Status JournalWriter::write_line(const std::string& body) {
  const std::string line = body + std::string(kCheckTag) + hex64(fnv1a64(body)) + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0 ||
      ::fsync(fileno(file_)) != 0) {
    return Status::error(StatusCode::io_error,
                         path_.string() + ": journal write failed: " + std::strerror(errno));
  }
  return Status::success();
}

}  // namespace argil::sculpt
