#include "argil/sculpt/output/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "argil/core/geometry/evaluate.hpp"

namespace argil::sculpt {
namespace {

/// A sample along a direction: a parameter and the width of the cell it
/// stands for (a node: the wider of the cells beside it).
struct Cell {
  double centre = 0.0;
  double width = 0.0;
};

/// `per_span` equal cells on every non-empty knot span of direction d.
std::vector<Cell> cells_along(const BSplineSurface& s, Direction d, int per_span) {
  const Eigen::VectorXd& t = s.knots_in(d);
  std::vector<Cell> cells;
  for (int k = s.degree_in(d); k < s.count(d); ++k) {
    const double a = t[k], b = t[k + 1];
    if (!(b > a)) continue;
    const double w = (b - a) / per_span;
    for (int c = 0; c < per_span; ++c) cells.push_back({a + (c + 0.5) * w, w});
  }
  return cells;
}

/// The cells' corners: every cell's start, then the domain's end.
std::vector<Cell> nodes_of(const std::vector<Cell>& cells) {
  std::vector<Cell> nodes;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const double before = k > 0 ? cells[k - 1].width : 0.0;
    nodes.push_back({cells[k].centre - 0.5 * cells[k].width, std::max(before, cells[k].width)});
  }
  if (!cells.empty())
    nodes.push_back({cells.back().centre + 0.5 * cells.back().width, cells.back().width});
  return nodes;
}

/// The face's outward unit normal before the run, from first derivatives, or
/// its limit where the surface collapses (a pole).
Eigen::Vector3d face_normal(const SculptedFace& f, const SurfaceDerivatives& d, double u,
                            double v) {
  Eigen::Vector3d n = unit_normal(d);
  if (n.isZero()) n = unit_normal(f.before, u, v);
  return f.reversed ? Eigen::Vector3d(-n) : n;
}

/// d = (S_after - S_before) . n at (u, v) [mm], with the point before the run.
double displacement_at(const SculptedFace& f, const Eigen::Vector2d& uv, Eigen::Vector3d* p_W) {
  const SurfaceDerivatives d = evaluate_derivatives(f.before, uv[0], uv[1], 1);
  if (p_W != nullptr) *p_W = d.point;
  return (evaluate(f.after, uv[0], uv[1]) - d.point).dot(face_normal(f, d, uv[0], uv[1]));
}

bool unchanged(const SculptedFace& f) {
  return f.before.control_points == f.after.control_points && f.before.weights == f.after.weights;
}

/// The best sample so far in one direction (sign -1: inward, +1: outward).
struct Candidate {
  double signed_value = 0.0;  // sign * d; > 0 when found
  int face = -1;              // index in the faces given
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector2d reach = Eigen::Vector2d::Zero();  // the widths of the cells about it
};

void consider(Candidate& c, double value, int face, const Eigen::Vector2d& uv,
              const Eigen::Vector2d& reach) {
  if (value > c.signed_value) c = {value, face, uv, reach};
}

/// Refines a candidate by a shrinking 9 x 9 grid search about it (first over
/// the cells about its corner), inside the domain and the trims; returns the
/// extreme it ends at.
DisplacementExtreme refine(const std::vector<SculptedFace>& faces, Candidate c, double sign,
                           int rounds) {
  DisplacementExtreme e;
  if (c.face < 0) return e;
  const SculptedFace& f = faces[static_cast<std::size_t>(c.face)];
  const Eigen::Vector2d lo(f.before.domain_start(Direction::u),
                           f.before.domain_start(Direction::v));
  const Eigen::Vector2d hi(f.before.domain_end(Direction::u), f.before.domain_end(Direction::v));
  Eigen::Vector2d window = c.reach;
  for (int r = 0; r < rounds; ++r) {
    const Eigen::Vector2d centre = c.uv;
    for (int i = 0; i <= 8; ++i) {
      for (int j = 0; j <= 8; ++j) {
        const Eigen::Vector2d step(static_cast<double>(i - 4) / 4.0,
                                   static_cast<double>(j - 4) / 4.0);
        const Eigen::Vector2d uv = (centre + step.cwiseProduct(window)).cwiseMax(lo).cwiseMin(hi);
        if (!f.trim.empty() && !f.trim.contains(uv)) continue;
        consider(c, sign * displacement_at(f, uv, nullptr), c.face, uv, c.reach);
      }
    }
    window *= 0.5;
  }
  e.displacement = sign * c.signed_value;
  e.model = f.model;
  e.face = f.face;
  e.uv = c.uv;
  displacement_at(f, c.uv, &e.p_W);
  return e;
}

std::string format(const char* pattern, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, x);
  return buffer;
}

std::string g4(double x) { return format("%.4g", x); }

std::string extreme_text(const char* way, const DisplacementExtreme& e, double eps) {
  std::string s = std::string("largest ") + way + " displacement: " + g4(e.displacement) + " mm";
  if (e.model.empty()) return s + " (none)";
  // A face the tool never reached moves by rounding (1e-25 mm): say it is no change.
  if (std::abs(e.displacement) <= eps) s += ", within eps";
  return s + " (" + e.model + " face " + std::to_string(e.face) + " at (u, v) = (" +
         format("%.6g", e.uv[0]) + ", " + format("%.6g", e.uv[1]) + "))";
}

nlohmann::ordered_json extreme_json(const DisplacementExtreme& e) {
  nlohmann::ordered_json j;
  j["displacement_mm"] = e.displacement;
  if (e.model.empty()) {
    j["at"] = nullptr;
  } else {
    j["at"] = {{"model", e.model},
               {"face", e.face},
               {"u", e.uv[0]},
               {"v", e.uv[1]},
               {"point_mm", {e.p_W.x(), e.p_W.y(), e.p_W.z()}}};
  }
  return j;
}

}  // namespace

DisplacementSummary summarize_displacement(const std::vector<SculptedFace>& faces, double eps,
                                           const DisplacementOptions& options) {
  DisplacementSummary s;
  Candidate in, out;
  const int per_span = std::max(1, options.cells_per_span);
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const SculptedFace& f = faces[k];
    const bool moved = !unchanged(f);
    const std::vector<Cell> us = cells_along(f.before, Direction::u, per_span);
    const std::vector<Cell> vs = cells_along(f.before, Direction::v, per_span);
    // The area and the affected area at the cells' centres.
    for (const Cell& cu : us) {
      for (const Cell& cv : vs) {
        const Eigen::Vector2d uv(cu.centre, cv.centre);
        if (!f.trim.empty() && !f.trim.contains(uv)) continue;
        const SurfaceDerivatives d = evaluate_derivatives(f.before, uv[0], uv[1], 1);
        const double area = d.du.cross(d.dv).norm() * cu.width * cv.width;
        s.area += area;
        ++s.samples;
        if (moved &&
            std::abs(
                (evaluate(f.after, uv[0], uv[1]) - d.point).dot(face_normal(f, d, uv[0], uv[1]))) >
                eps) {
          s.affected_area += area;
        }
      }
    }
    if (!moved) continue;
    // The extremes' start at the cells' corners, which reach the domain's edges
    // (where an extreme often lies) and the knot lines (where a C0 face creases).
    for (const Cell& nu : nodes_of(us)) {
      for (const Cell& nv : nodes_of(vs)) {
        const Eigen::Vector2d uv(nu.centre, nv.centre);
        if (!f.trim.empty() && !f.trim.contains(uv)) continue;
        const double disp = displacement_at(f, uv, nullptr);
        ++s.samples;
        const Eigen::Vector2d reach(nu.width, nv.width);
        consider(in, -disp, static_cast<int>(k), uv, reach);
        consider(out, disp, static_cast<int>(k), uv, reach);
      }
    }
  }
  s.inward = refine(faces, in, -1.0, options.refine_rounds);
  s.outward = refine(faces, out, 1.0, options.refine_rounds);
  return s;
}

PeakForce peak_force(const TickLog& log) {
  PeakForce p;
  for (std::size_t k = 0; k < log.size(); ++k) {
    const double f = log.forces()[k].norm();
    if (p.tick < 0 || f > p.force) p = {f, log.ticks()[k], log.times()[k]};
  }
  return p;
}

long long contact_ticks(const TickLog& log) {
  return static_cast<long long>(std::count_if(
      log.contact_counts().begin(), log.contact_counts().end(), [](int n) { return n > 0; }));
}

long long count_over_budget(const std::vector<double>& durations, double budget) {
  return static_cast<long long>(
      std::count_if(durations.begin(), durations.end(), [budget](double t) { return t > budget; }));
}

RunSummary summarize_run(const std::vector<SculptedFace>& faces, const TickLog& log,
                         const std::vector<double>& wall_s, const std::vector<double>& cpu_s,
                         const RunSummaryOptions& options) {
  RunSummary s;
  s.tolerance = options.tolerance;
  s.displacement = summarize_displacement(faces, options.tolerance, options.sampling);
  s.peak_force = peak_force(log);
  s.ticks = static_cast<long long>(log.size());
  s.contact_ticks = contact_ticks(log);
  s.budget = 1.0 / options.haptic_rate;
  s.ticks_timed = static_cast<long long>(wall_s.size());
  s.over_budget_wall = count_over_budget(wall_s, s.budget);
  s.over_budget_cpu = count_over_budget(cpu_s, s.budget);
  // The live ticks are the log's last ones (a resumed run replays the first).
  std::vector<double> touching;
  const std::vector<int>& counts = log.contact_counts();
  const std::size_t first_live = counts.size() - std::min(counts.size(), cpu_s.size());
  for (std::size_t k = 0; k < cpu_s.size() && first_live + k < counts.size(); ++k)
    if (counts[first_live + k] > 0) touching.push_back(cpu_s[k]);
  s.contact_cpu = summarize_timing(std::move(touching), options.haptic_rate);
  if (s.contact_ticks == 0)
    s.warnings.push_back("the tool never touched anything: no tick had a contact");
  if (s.displacement.max_abs() <= options.tolerance) {
    s.warnings.push_back("nothing changed: no point of the sculpted faces moved more than eps = " +
                         g4(options.tolerance) + " mm");
  }
  return s;
}

std::vector<std::string> summary_lines(const RunSummary& s) {
  const DisplacementSummary& d = s.displacement;
  std::vector<std::string> lines;
  lines.push_back(extreme_text("inward", d.inward, s.tolerance));
  lines.push_back(extreme_text("outward", d.outward, s.tolerance));
  lines.push_back("affected area (|displacement| > eps = " + g4(s.tolerance) +
                  " mm): " + g4(d.affected_area) + " mm^2 of " + g4(d.area) + " mm^2");
  if (s.peak_force.tick >= 0) {
    lines.push_back("peak force: " + g4(s.peak_force.force) + " N at tick " +
                    std::to_string(s.peak_force.tick) + " (t = " + g4(s.peak_force.time) + " s)");
  }
  lines.push_back("ticks: " + std::to_string(s.ticks) + ", " + std::to_string(s.contact_ticks) +
                  " with contact; over the " + g4(s.budget * 1e6) +
                  " us budget: " + std::to_string(s.over_budget_wall) + " by wall time, " +
                  std::to_string(s.over_budget_cpu) + " by thread CPU time (of " +
                  std::to_string(s.ticks_timed) + " timed)");
  const TimingSummary& c = s.contact_cpu;
  if (c.ticks > 0) {
    lines.push_back("ticks with contact, thread CPU time: p50 " + g4(c.p50 * 1e6) + " us, p99 " +
                    g4(c.p99 * 1e6) + " us, p99.9 " + g4(c.p999 * 1e6) + " us, max " +
                    g4(c.max * 1e6) + " us (" + std::to_string(c.ticks) + " timed, " +
                    std::to_string(c.over_budget) + " over budget)");
  }
  return lines;
}

std::string summary_json(const RunSummary& s, const std::string& scene_name,
                         const std::string& scene_absolute) {
  const DisplacementSummary& d = s.displacement;
  nlohmann::ordered_json j;
  j["format"] = "argil.summary";
  j["version"] = 1;
  j["scene"] = scene_name;
  if (!scene_absolute.empty()) j["scene_absolute"] = scene_absolute;
  j["tolerance_mm"] = s.tolerance;
  j["displacement"] = {
      {"sign",
       "(S_after - S_before) . n at equal (u, v), n the face's outward unit normal before the "
       "run: inward is negative"},
      {"inward", extreme_json(d.inward)},
      {"outward", extreme_json(d.outward)},
      {"affected_area_mm2", d.affected_area},
      {"area_mm2", d.area},
      {"samples", d.samples}};
  j["peak_force"] = {
      {"force_n", s.peak_force.force}, {"tick", s.peak_force.tick}, {"time_s", s.peak_force.time}};
  j["ticks"] = s.ticks;
  j["contact_ticks"] = s.contact_ticks;
  j["budget_us"] = s.budget * 1e6;
  j["ticks_timed"] = s.ticks_timed;
  j["over_budget"] = {{"wall", s.over_budget_wall}, {"thread_cpu", s.over_budget_cpu}};
  const TimingSummary& c = s.contact_cpu;
  j["contact_ticks_thread_cpu"] = {{"ticks_timed", c.ticks}, {"p50_us", c.p50 * 1e6},
                                   {"p99_us", c.p99 * 1e6},  {"p99_9_us", c.p999 * 1e6},
                                   {"max_us", c.max * 1e6},  {"over_budget", c.over_budget}};
  j["faces_refined"] = s.refinements;
  j["warnings"] = s.warnings;
  return j.dump(2) + "\n";
}

}  // namespace argil::sculpt
