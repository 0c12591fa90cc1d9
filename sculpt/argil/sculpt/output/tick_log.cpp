#include "argil/sculpt/output/tick_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "argil/core/base/number_text.hpp"

namespace argil::sculpt {
namespace {

void append(std::string& out, double x) { out += number_text(x); }

void append_row(std::string& out, std::initializer_list<double> values) {
  bool first = true;
  for (const double v : values) {
    if (!first) out += ',';
    append(out, v);
    first = false;
  }
}

}  // namespace

void TickLog::add(const TickReport& report) {
  ticks_.push_back(report.tick);
  times_.push_back(report.time);
  forces_.push_back(report.force);
  proxies_.push_back(report.proxy);
  clamped_.push_back(report.clamped ? 1 : 0);
  contact_counts_.push_back(static_cast<int>(report.contacts.size()));
  tools_.push_back(report.tool);
  max_depths_.push_back(report.max_depth);
  for (const ContactRecord& c : report.contacts) {
    contacts_.emplace_back(report.tick, c);
    contact_times_.push_back(report.time);
  }
}

std::string TickLog::forces_csv() const {
  std::string out = "tick,time,fx,fy,fz,f,clamped,proxy_x,proxy_y,proxy_z,contacts,max_depth\n";
  for (std::size_t k = 0; k < ticks_.size(); ++k) {
    out += std::to_string(ticks_[k]) + ',';
    const Eigen::Vector3d& f = forces_[k];
    append_row(out, {times_[k], f.x(), f.y(), f.z(), f.norm()});
    out += clamped_[k] != 0 ? ",1," : ",0,";
    append_row(out, {proxies_[k].x(), proxies_[k].y(), proxies_[k].z()});
    out += ',' + std::to_string(contact_counts_[k]) + ',';
    append(out, max_depths_[k]);
    out += '\n';
  }
  return out;
}

std::string TickLog::contacts_csv(const std::vector<std::string>& model_names) const {
  std::string out = "tick,time,model,face,u,v,x,y,z,depth,nx,ny,nz\n";
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& [tick, c] = contacts_[k];
    out += std::to_string(tick) + ',';
    append(out, contact_times_[k]);
    const std::size_t m = static_cast<std::size_t>(c.model);
    out += ',' + (m < model_names.size() ? model_names[m] : std::to_string(c.model)) + ',' +
           std::to_string(c.face) + ',';
    append_row(out, {c.uv.x(), c.uv.y(), c.point.x(), c.point.y(), c.point.z(), c.depth,
                     c.normal.x(), c.normal.y(), c.normal.z()});
    out += '\n';
  }
  return out;
}

TimingSummary summarize_timing(std::vector<double> durations, double rate_hz) {
  TimingSummary s;
  s.budget = 1.0 / rate_hz;
  s.ticks = static_cast<long long>(durations.size());
  if (durations.empty()) return s;
  std::sort(durations.begin(), durations.end());
  const auto rank = [&](double q) {
    // Nearest rank: ceil(q n), 1-based.
    const double n = static_cast<double>(durations.size());
    const auto r = static_cast<std::size_t>(std::max(1.0, std::ceil(q * n - 1e-9)));
    return durations[std::min(r, durations.size()) - 1];
  };
  s.p50 = rank(0.50);
  s.p99 = rank(0.99);
  s.p999 = rank(0.999);
  s.max = durations.back();
  s.mean = std::accumulate(durations.begin(), durations.end(), 0.0) / static_cast<double>(s.ticks);
  s.over_budget = static_cast<long long>(
      durations.end() - std::upper_bound(durations.begin(), durations.end(), s.budget));
  return s;
}

std::string timing_json(const TimingSummary& wall, const TimingSummary& thread_cpu,
                        const std::string& scene_name) {
  auto us = [](double seconds) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3f", seconds * 1e6);
    return std::string(buffer);
  };
  auto fields = [&](const TimingSummary& s, const std::string& indent) {
    return indent + "\"p50_us\": " + us(s.p50) + ",\n" + indent + "\"p99_us\": " + us(s.p99) +
           ",\n" + indent + "\"p99_9_us\": " + us(s.p999) + ",\n" + indent +
           "\"max_us\": " + us(s.max) + ",\n" + indent + "\"mean_us\": " + us(s.mean) + ",\n" +
           indent + "\"over_budget\": " + std::to_string(s.over_budget);
  };
  std::string name;
  for (const char c : scene_name) {
    if (c == '"' || c == '\\') name += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) name += c;
  }
  return "{\n  \"format\": \"argil.timing\",\n  \"version\": 1,\n  \"scene\": \"" + name +
         "\",\n  \"measured\": \"each Session::step call (one haptic tick): wall time on the "
         "steady clock; thread_cpu: CLOCK_THREAD_CPUTIME_ID\",\n  \"ticks\": " +
         std::to_string(wall.ticks) + ",\n  \"budget_us\": " + us(wall.budget) + ",\n" +
         fields(wall, "  ") + ",\n  \"thread_cpu\": {\n" + fields(thread_cpu, "    ") +
         "\n  }\n}\n";
}

}  // namespace argil::sculpt
