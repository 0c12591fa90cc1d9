// The run summary: displacement extremes and affected area against a dense
// brute-force sampling, the sign convention (inward is negative, reversed
// faces flip it), trims honoured, peak force and ticks over budget against the
// logs, the warnings of a run that never touches, and summary.json.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <tuple>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/sculpt/output/run_summary.hpp"
#include "argil/sculpt/run/session_runner.hpp"
#include "support/random_surface.hpp"
#include "support/trim_loops.hpp"

namespace argil::sculpt {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kData = fs::path(ARGIL_SOURCE_DIR) / "tests/data/sculpt";
const fs::path kWork = fs::path(ARGIL_BINARY_DIR) / "summary-test";

/// The asymmetric 10 x 10 mm plate in z = 0 (x = 10 u, y = 10 v), and the same
/// plate moved by `dz` [mm] along z, its normal.
SculptedFace moved_plate(double dz, bool reversed = false) {
  SculptedFace f{.model = "plate", .face = 3, .before = test::asymmetric_plate(10.0, 0.0)};
  f.after = f.before;
  f.after.control_points.col(2).array() += dz;
  f.reversed = reversed;
  return f;
}

TEST_CASE("a plate moved along its normal has that displacement everywhere, inward negative",
          "[summary]") {
  const DisplacementSummary down = summarize_displacement({moved_plate(-0.3)}, 0.01);
  CHECK(down.inward.displacement == Approx(-0.3).epsilon(1e-12));
  CHECK(down.inward.model == "plate");
  CHECK(down.inward.face == 3);
  CHECK(down.inward.p_W.z() == Approx(0.0).margin(1e-12));
  CHECK(down.outward.displacement == 0.0);
  CHECK(down.outward.model.empty());
  // |S_u x S_v| = 100 mm^2 per unit parameter area: the midpoint rule is exact.
  CHECK(down.area == Approx(100.0).epsilon(1e-12));
  CHECK(down.affected_area == Approx(100.0).epsilon(1e-12));
  CHECK(down.max_abs() == Approx(0.3).epsilon(1e-12));

  // A move within eps affects nothing.
  CHECK(summarize_displacement({moved_plate(-0.3)}, 0.31).affected_area == 0.0);

  // The reversed face's outward normal is -z: the same move is outward.
  const DisplacementSummary flipped = summarize_displacement({moved_plate(-0.3, true)}, 0.01);
  CHECK(flipped.outward.displacement == Approx(0.3).epsilon(1e-12));
  CHECK(flipped.inward.model.empty());
  const DisplacementSummary up = summarize_displacement({moved_plate(0.2)}, 0.01);
  CHECK(up.outward.displacement == Approx(0.2).epsilon(1e-12));
  CHECK(up.inward.displacement == 0.0);
}

TEST_CASE("the summary says when the largest displacement is within eps", "[summary]") {
  // A pressed plate (0.3 mm in) beside one the tool never reached, moved by
  // rounding (1e-25 mm out): the outward extreme is printed, and is no change.
  RunSummary s;
  s.tolerance = 0.01;
  s.displacement = summarize_displacement({moved_plate(-0.3), moved_plate(1e-25)}, s.tolerance);
  const std::vector<std::string> lines = summary_lines(s);
  REQUIRE(lines.size() >= 2);
  CHECK(lines[0].find("largest inward displacement: -0.3 mm (plate face 3") == 0);
  CHECK(lines[1].find("largest outward displacement: 1e-25 mm, within eps (plate face 3") == 0);
}

TEST_CASE("only the material inside a face's trims is sampled", "[summary]") {
  SculptedFace f = moved_plate(-0.3);
  // An elliptic hole of semi-axes 0.2 x 0.15 (2 x 1.5 mm) in the plate.
  std::vector<TrimLoop> loops = {test::rectangle_loop({0, 0}, {1, 1}, true),
                                 test::ellipse_loop({0.45, 0.55}, 0.2, 0.15, false)};
  Result<TrimRegion> trim = TrimRegion::create(loops);
  REQUIRE(trim.ok());
  f.trim = trim.value();
  const DisplacementSummary s = summarize_displacement({f}, 0.01);
  const double hole = M_PI * 2.0 * 1.5;  // [mm^2]
  // The cells are 1/16 of a span: at most 10/64 x 10/48 mm. Cells cut by the
  // ellipse (perimeter < 12 mm) are counted whole or not at all: at most a
  // band of 12 mm times a cell diagonal (0.26 mm) errs.
  CHECK(std::abs(s.area - (100.0 - hole)) < 12.0 * 0.26);
  CHECK(s.area < 100.0 - 0.5 * hole);
  CHECK(s.affected_area == s.area);
  // The hole's centre is no material: the extremes lie outside the ellipse.
  const Eigen::Vector2d q =
      (s.inward.uv - Eigen::Vector2d(0.45, 0.55)).cwiseQuotient(Eigen::Vector2d(0.2, 0.15));
  CHECK(q.norm() >= 1.0 - 1e-9);
}

/// The smallest of `g` over a 401 x 401 grid of the rectangle `half` about
/// `centre`, clamped to [lo, hi]: a brute-force zoom on a dense sample.
template <class G>
double zoom_min(const G& g, const Eigen::Vector2d& centre, const Eigen::Vector2d& half,
                const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  double best = g(centre);
  for (int i = -200; i <= 200; ++i) {
    for (int j = -200; j <= 200; ++j) {
      const Eigen::Vector2d uv =
          (centre + Eigen::Vector2d(i * half[0], j * half[1]) / 200.0).cwiseMax(lo).cwiseMin(hi);
      best = std::min(best, g(uv));
    }
  }
  return best;
}

double displacement(const SculptedFace& f, const Eigen::Vector2d& uv) {
  const SurfaceDerivatives s = evaluate_derivatives(f.before, uv[0], uv[1], 1);
  return (evaluate(f.after, uv[0], uv[1]) - s.point).dot(unit_normal(s));
}

/// The brute-force oracle: the signed displacement on a uniform grid of n x n
/// cells over the domain.
struct DenseSampling {
  /// The extremes [mm] of the cells' corners (the domain's edges included),
  /// each zoomed into over the two cells about it.
  double min = 0.0, max = 0.0;
  double affected_area = 0.0;  // [mm^2] of the cells whose centre moved more than eps
};

DenseSampling dense_sampling(const SculptedFace& f, int n, double eps) {
  DenseSampling d;
  const Eigen::Vector2d lo(f.before.domain_start(Direction::u),
                           f.before.domain_start(Direction::v));
  const Eigen::Vector2d hi(f.before.domain_end(Direction::u), f.before.domain_end(Direction::v));
  const Eigen::Vector2d h = (hi - lo) / n;
  Eigen::Vector2d lowest = lo, highest = lo;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector2d corner = (lo + Eigen::Vector2d(i * h[0], j * h[1])).cwiseMin(hi);
      const double disp = displacement(f, corner);
      if (disp < d.min) std::tie(d.min, lowest) = std::pair(disp, corner);
      if (disp > d.max) std::tie(d.max, highest) = std::pair(disp, corner);
      if (i == n || j == n) continue;
      const Eigen::Vector2d uv = corner + 0.5 * h;
      const SurfaceDerivatives s = evaluate_derivatives(f.before, uv[0], uv[1], 1);
      const double centre = (evaluate(f.after, uv[0], uv[1]) - s.point).dot(unit_normal(s));
      if (std::abs(centre) > eps) d.affected_area += s.du.cross(s.dv).norm() * h[0] * h[1];
    }
  }
  const auto inward = [&](const Eigen::Vector2d& uv) { return displacement(f, uv); };
  const auto outward = [&](const Eigen::Vector2d& uv) { return -displacement(f, uv); };
  d.min = zoom_min(inward, lowest, 2.0 * h, lo, hi);
  d.max = -zoom_min(outward, highest, 2.0 * h, lo, hi);
  return d;
}

TEST_CASE("the extremes on a curved rational face match a dense brute-force sampling",
          "[summary]") {
  SculptedFace f{.model = "bent", .face = 0, .before = test::asymmetric_surface(true)};
  f.after = f.before;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> move(-1.0, 1.0);  // [mm], on a ~60 x 30 mm net
  for (Eigen::Index k = 0; k < f.after.control_points.rows(); ++k) {
    for (int c = 0; c < 3; ++c) f.after.control_points(k, c) += move(rng);
  }
  const double eps = 0.05;
  const DisplacementSummary s = summarize_displacement({f}, eps);
  const DenseSampling dense = dense_sampling(f, 1200, eps);
  INFO("summary " << s.inward.displacement << " .. " << s.outward.displacement << ", dense "
                  << dense.min << " .. " << dense.max);
  // The dense extremes zoom on a grid 1/100 of a dense cell (about 1e-5 of
  // the domain): where d is flat (inside) or along an edge, that misses the
  // extreme by far less than 1e-6 mm; at a corner it is exact.
  CHECK(s.inward.displacement <= dense.min + 1e-12);
  CHECK(s.inward.displacement >= dense.min - 1e-6);
  CHECK(s.outward.displacement >= dense.max - 1e-12);
  CHECK(s.outward.displacement <= dense.max + 1e-6);
  CHECK(s.inward.displacement < -0.1);
  CHECK(s.outward.displacement > 0.1);
  // Where the summary says the extreme lies, the surfaces give its value.
  const SurfaceDerivatives at = evaluate_derivatives(f.before, s.inward.uv[0], s.inward.uv[1], 1);
  CHECK((evaluate(f.after, s.inward.uv[0], s.inward.uv[1]) - at.point).dot(unit_normal(at)) ==
        Approx(s.inward.displacement).epsilon(1e-12));
  CHECK((at.point - s.inward.p_W).norm() < 1e-12);
  // Both areas are midpoint rules of the same indicator: they differ only in
  // the cells the |d| = eps curve cuts. Most of the face moves (net moves of
  // up to 1.7 mm, eps 0.05), so that band is a small part of the area.
  CHECK(s.affected_area == Approx(dense.affected_area).epsilon(0.02));
  CHECK(s.affected_area < s.area);
}

TEST_CASE("peak force, contact ticks and ticks over budget are counted from the log", "[summary]") {
  TickLog log;
  for (int k = 0; k < 5; ++k) {
    TickReport r;
    r.tick = 10 + k;
    r.time = 0.001 * static_cast<double>(r.tick);
    r.force = Eigen::Vector3d(0, 0, k == 2 || k == 3 ? 4.0 : 1.0 * k);  // a tie: first wins
    if (k == 1 || k == 2) r.contacts.resize(static_cast<std::size_t>(k));
    log.add(r);
  }
  const PeakForce p = peak_force(log);
  CHECK(p.force == 4.0);
  CHECK(p.tick == 12);
  CHECK(p.time == Approx(0.012));
  CHECK(contact_ticks(log) == 2);
  CHECK(peak_force(TickLog{}).tick == -1);

  // Budget 1 ms: a tick of exactly 1 ms is within it.
  const std::vector<double> wall = {0.5e-3, 1e-3, 1.5e-3, 2e-3, 0.9e-3};
  const std::vector<double> cpu = {0.5e-3, 0.9e-3, 1.1e-3, 0.9e-3, 0.9e-3};
  const RunSummary s = summarize_run({moved_plate(-0.3)}, log, wall, cpu,
                                     {.tolerance = 0.05, .haptic_rate = 1000.0});
  CHECK(s.ticks == 5);
  CHECK(s.contact_ticks == 2);
  CHECK(s.ticks_timed == 5);
  CHECK(s.over_budget_wall == 2);
  CHECK(s.over_budget_cpu == 1);
  CHECK(s.budget == Approx(1e-3));
  CHECK(s.over_budget_wall == summarize_timing(wall, 1000.0).over_budget);
  CHECK(s.warnings.empty());
  // The contact ticks' CPU time: ticks 11 and 12 only (0.9 and 1.1 ms).
  CHECK(s.contact_cpu.ticks == 2);
  CHECK(s.contact_cpu.p50 == 0.9e-3);
  CHECK(s.contact_cpu.max == 1.1e-3);
  CHECK(s.contact_cpu.over_budget == 1);
  // Resumed: the first ticks were replayed, not timed; the timed ones are
  // the log's last (ticks 12 to 14, of which 12 touched).
  const std::vector<double> late_wall = {1.5e-3, 2e-3, 0.9e-3}, late_cpu = {1.2e-3, 0.8e-3, 0.7e-3};
  const RunSummary resumed = summarize_run({moved_plate(-0.3)}, log, late_wall, late_cpu,
                                           {.tolerance = 0.05, .haptic_rate = 1000.0});
  CHECK(resumed.contact_cpu.ticks == 1);
  CHECK(resumed.contact_cpu.max == 1.2e-3);

  // The pure function warns on what it is given: contact that changed nothing.
  const RunSummary still =
      summarize_run({moved_plate(0.0)}, log, wall, cpu, {.tolerance = 0.05, .haptic_rate = 1000.0});
  REQUIRE(still.warnings.size() == 1);
  CHECK(still.warnings[0].rfind("nothing changed", 0) == 0);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

json read_json(const fs::path& path) {
  const json j = json::parse(read_text(path), nullptr, false);
  REQUIRE_FALSE(j.is_discarded());
  return j;
}

RunReport run_press(const std::string& script, const std::string& name) {
  const fs::path out = kWork / name;
  fs::remove_all(out);
  fs::create_directories(kWork);
  RunOptions o{.scene = kData / "summary_press.json", .script = kData / script, .out = out};
  o.outputs = OutputOptions{.step = false,
                            .iges = false,
                            .json = true,
                            .forces = true,
                            .contacts = false,
                            .timing = true,
                            .pictures = false};
  Result<RunReport> report = run_session(o);
  INFO(report.status().message);
  REQUIRE(report.ok());
  REQUIRE(report.value().failed_outputs.empty());
  return std::move(report).value();
}

/// Column `name` of every row of a CSV file with a header line.
std::vector<double> csv_column(const fs::path& path, const std::string& name) {
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::istringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto column = std::find(header.begin(), header.end(), name) - header.begin();
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (long c = 0; c <= column; ++c) std::getline(row, cell, ',');
    values.push_back(std::stod(cell));
  }
  return values;
}

TEST_CASE(
    "a ball pressed into a flat plate: the summary measures the dent a dense sampling "
    "measures",
    "[summary][run]") {
  const RunReport report = run_press("summary_press.csv", "press");
  const fs::path out = report.out;
  const json j = read_json(out / "summary.json");
  REQUIRE(j["format"] == "argil.summary");
  REQUIRE(j["version"] == 1);
  for (const char* key :
       {"scene", "tolerance_mm", "displacement", "peak_force", "ticks", "contact_ticks",
        "budget_us", "ticks_timed", "over_budget", "faces_refined", "warnings"}) {
    INFO(key);
    CHECK(j.contains(key));
  }
  const json& d = j["displacement"];
  const double eps = j["tolerance_mm"];
  CHECK(eps == 0.05);

  // The oracle: the plate as read (the run refines it exactly, so its (u, v)
  // are the run's) and as written. It lies in z = 0 with normal +z, so the
  // displacement is the sculpted surface's z at equal (u, v).
  const Result<io::Model> before = io::read_model(kData / "../../../examples/groove/plate.json");
  const Result<io::Model> after = io::read_model(out / "plate.json");
  REQUIRE(before.ok());
  REQUIRE(after.ok());
  const BSplineSurface& s0 = before.value().faces[0].surface;
  const BSplineSurface& s1 = after.value().faces[0].surface;
  REQUIRE(unit_normal(s0, 1.0, 1.0).isApprox(Eigen::Vector3d::UnitZ()));
  // 1700 x 1100 cells over the 17 x 11 spans of the 200 x 120 mm plate.
  const int nu = 1700, nv = 1100;
  const double hx = 200.0 / nu, hy = 120.0 / nv;
  std::vector<double> z(static_cast<std::size_t>(nu * nv));
  const auto at = [&](int i, int k) -> double& { return z[static_cast<std::size_t>(i * nv + k)]; };
  for (int i = 0; i < nu; ++i) {
    for (int k = 0; k < nv; ++k) {
      const double u = 17.0 * (i + 0.5) / nu, v = 11.0 * (k + 0.5) / nv;
      REQUIRE(evaluate(s0, u, v).z() == 0.0);
      at(i, k) = evaluate(s1, u, v).z();
    }
  }
  double lowest = 0.0, highest = 0.0, area = 0.0, slope = 0.0;
  for (int i = 0; i < nu; ++i) {
    for (int k = 0; k < nv; ++k) {
      lowest = std::min(lowest, at(i, k));
      highest = std::max(highest, at(i, k));
      if (std::abs(at(i, k)) > eps) area += hx * hy;
      if (i + 1 < nu) slope = std::max(slope, std::abs(at(i + 1, k) - at(i, k)) / hx);
      if (k + 1 < nv) slope = std::max(slope, std::abs(at(i, k + 1) - at(i, k)) / hy);
    }
  }
  const double inward = d["inward"]["displacement_mm"];
  const double outward = d["outward"]["displacement_mm"];
  const double affected = d["affected_area_mm2"];
  INFO("inward " << inward << " (dense " << lowest << "), outward " << outward << " (dense "
                 << highest << "), area " << affected << " (dense " << area << ") mm^2");
  // The bottom: the lowest dense sample zoomed into over the two cells about
  // it on a grid 1/100 of a cell (1e-3 mm): with the dent's curvature below
  // 1 / mm (the ball's is 0.1 / mm) that misses the bottom by < 1e-6 mm.
  const double half_diagonal = 0.5 * std::hypot(hx, hy);
  const auto lowest_at = std::min_element(z.begin(), z.end()) - z.begin();
  const Eigen::Vector2d bottom(17.0 * (static_cast<double>(lowest_at / nv) + 0.5) / nu,
                               11.0 * (static_cast<double>(lowest_at % nv) + 0.5) / nv);
  const auto height = [&](const Eigen::Vector2d& uv) { return evaluate(s1, uv[0], uv[1]).z(); };
  lowest = zoom_min(height, bottom, Eigen::Vector2d(2.0 * 17.0 / nu, 2.0 * 11.0 / nv),
                    Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(17.0, 11.0));
  CHECK(inward <= lowest + 1e-12);
  CHECK(inward >= lowest - 1e-6);
  // A clearly dented plate, no deeper than the ball went (3 mm below the plate).
  CHECK(inward < -1.0);
  CHECK(inward >= -3.0 - eps);
  CHECK(d["inward"]["at"]["model"] == "plate");
  CHECK(std::abs(double(d["inward"]["at"]["point_mm"][0]) - 100.0) < 1.0);
  CHECK(std::abs(double(d["inward"]["at"]["point_mm"][1])) < 1.0);
  // Pressed from above with its edges held, no point of the plate rises: the
  // outward extreme is the net's rounding at most.
  CHECK(outward >= highest - 1e-12);
  CHECK(outward < 1e-9);
  // Affected area: both are midpoint rules of |d| > eps and differ only in the
  // cells the |d| = eps curve cuts. That curve bounds a dent about as round as
  // the ball (its length at most 1.5 times the circle of the same area), and
  // each rule errs by at most its cell diagonal along it; the summary's cells
  // are 1/16 of a span, the plate's spans at most 200 / 17 x 120 / 11 mm.
  const double perimeter = 1.5 * 2.0 * std::sqrt(M_PI * area);
  const double summary_cell = std::hypot(200.0 / 17.0, 120.0 / 11.0) / 16.0;
  CHECK(std::abs(affected - area) <= perimeter * (summary_cell + 2.0 * half_diagonal));
  // Going out from the bottom, the dent rises at most `slope` per mm (the
  // steepest secant over a cell; 1.1 times it bounds the steepest tangent),
  // so it stays deeper than eps over a disc of radius (|inward| - eps) / slope.
  const double radius = (-inward - eps) / (1.1 * slope);
  CHECK(affected >= M_PI * radius * radius);
  // And the dent is local: a small part of the plate.
  CHECK(affected < 0.1 * double(d["area_mm2"]));

  // Peak force and contact ticks as forces.csv logs them.
  const std::vector<double> f = csv_column(out / "forces.csv", "f");
  const std::vector<double> contacts = csv_column(out / "forces.csv", "contacts");
  const std::vector<double> ticks = csv_column(out / "forces.csv", "tick");
  const auto peak = std::max_element(f.begin(), f.end());
  CHECK(double(j["peak_force"]["force_n"]) == *peak);
  CHECK(double(j["peak_force"]["tick"]) == ticks[static_cast<std::size_t>(peak - f.begin())]);
  CHECK(j["contact_ticks"] ==
        std::count_if(contacts.begin(), contacts.end(), [](double n) { return n > 0; }));
  CHECK(j["ticks"] == f.size());
  // Ticks over budget as timing.json counts them (sorted order statistics).
  const json timing = read_json(out / "timing.json");
  CHECK(j["ticks_timed"] == timing["ticks"]);
  CHECK(j["over_budget"]["wall"] == timing["over_budget"]);
  CHECK(j["over_budget"]["thread_cpu"] == timing["thread_cpu"]["over_budget"]);
  CHECK(j["budget_us"] == 1000.0);
  CHECK(report.summary.over_budget_wall == report.wall_timing.over_budget);

  CHECK(j["faces_refined"].size() == report.refinements.size());
  CHECK(report.refinements.size() == 1);
  CHECK(j["warnings"].empty());
  CHECK(report.summary.warnings.empty());
}

TEST_CASE("a run whose tool never comes near warns that it touched nothing and nothing changed",
          "[summary][run]") {
  const RunReport report = run_press("summary_miss.csv", "miss");
  const std::vector<std::string>& w = report.summary.warnings;
  REQUIRE(w.size() == 2);
  CHECK(w[0].rfind("the tool never touched anything", 0) == 0);
  CHECK(w[1].rfind("nothing changed", 0) == 0);
  CHECK(report.summary.contact_ticks == 0);
  CHECK(report.summary.displacement.affected_area == 0.0);
  const json j = read_json(report.out / "summary.json");
  CHECK(j["warnings"].size() == 2);
  CHECK(j["warnings"][0] == w[0]);
  CHECK(j["displacement"]["inward"]["at"].is_null());
  CHECK(j["displacement"]["inward"]["displacement_mm"] == 0.0);
  CHECK(j["displacement"]["outward"]["at"].is_null());
  CHECK(j["contact_ticks"] == 0);
  CHECK(j["peak_force"]["force_n"] == 0.0);
}

}  // namespace
}  // namespace argil::sculpt
