// Local solves inside a face (docs/deformation.md, Local solves): a step whose
// loads lie inside the active window solves only the window's poles. The
// pieces agree with the whole-net solve to the last bit (a factorisation
// spread over steps, the stencil product on a window's rows, a window that
// would cover the net); a press on a 64 x 64 panel dents as deep and pushes
// back as hard as the whole-net solve within 1%; no pole outside the window
// moves; the window slides ahead of a moving load, leaving the trail behind
// once it rests (in time at 1 m/s, with a trail within 1% of the whole-net
// solve's), and is dropped once the load is gone and the window has come to
// rest.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <tuple>

#include "argil/core.hpp"
#include "support/point_load.hpp"
#include "support/sphere_press.hpp"
#include "support/test_plates.hpp"

namespace {

using argil::BSplineSurface;
using argil::ControlNet;
using argil::Direction;
using argil::PoleWindow;
using argil::test::pattern_at;

argil::DeformableBody make_body(const BSplineSurface& s, const argil::Material& m) {
  static argil::OperatorCache cache;
  auto b = argil::DeformableBody::create(s, m, {}, cache);
  INFO(b.status().message);
  REQUIRE(b.ok());
  return std::move(b).value();
}

/// The poles a pattern loads.
PoleWindow loaded(const BSplineSurface& s, const Eigen::VectorXd& pattern) {
  const int nv = s.count(Direction::v);
  PoleWindow w;
  for (Eigen::Index p = 0; p < pattern.size(); ++p)
    if (pattern[p] != 0.0) {
      const int i = static_cast<int>(p / nv), j = static_cast<int>(p % nv);
      w = w.united({i, i + 1, j, j + 1});
    }
  return w;
}

PoleWindow whole(const BSplineSurface& s) {
  return {0, s.count(Direction::u), 0, s.count(Direction::v)};
}

}  // namespace

TEST_CASE("a factorisation spread over row chunks is the one-shot factor to the bit",
          "[deformation][local]") {
  const int n = 60, b = 7;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  argil::SymmetricBandMatrix a(n, b);
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - b); j < i; ++j) a.at(i, j) = uniform(rng);
    a.at(i, i) = 4.0 * (b + 1);
  }
  auto whole_factor = argil::BandedCholesky::factorize(a);
  REQUIRE(whole_factor.ok());
  argil::SymmetricBandMatrix chunked = a;
  for (int row = 0; row < n; row += 11)
    REQUIRE(argil::BandedCholesky::factorize_rows(chunked, row, std::min(n, row + 11)).ok());
  const argil::BandedCholesky pieces = argil::BandedCholesky::from_factor(std::move(chunked));
  argil::RowMajorMatrix x = argil::RowMajorMatrix::Random(n, 3), y = x;
  whole_factor.value().solve_in_place(x);
  pieces.solve_in_place(y);
  CHECK((x - y).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("the stencil product on a window's rows is the whole product's rows to the bit",
          "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(100.0, 9);
  const argil::DeformableBody body = make_body(s, *argil::material_preset("clay"));
  const argil::PoleStencilMatrix& k = body.stiffness();
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(k.size(), 3);
  const Eigen::MatrixXd full = k.multiply(x);
  Eigen::MatrixXd part = Eigen::MatrixXd::Constant(k.size(), 3, 7.0);
  k.multiply_rows(x, 2, 6, 3, 9, part);
  const int nv = k.count_v();
  for (int i = 0; i < k.count_u(); ++i)
    for (int j = 0; j < nv; ++j) {
      const Eigen::Index r = static_cast<Eigen::Index>(i) * nv + j;
      if (i >= 2 && i < 6 && j >= 3 && j < 9) {
        CHECK((part.row(r) - full.row(r)).cwiseAbs().maxCoeff() == 0.0);
      } else {
        CHECK((part.row(r).array() == 7.0).all());
      }
    }
}

TEST_CASE("where the window would cover the net, local solves step as the whole net to the bit",
          "[deformation][local]") {
  // A 40 mm panel of 8 x 8 poles: the clay's influence margin covers it.
  const BSplineSurface s = argil::test::flat_bicubic_panel(40.0, 5);
  argil::Material m = *argil::material_preset("clay");
  m.yield = 0.05;
  argil::DeformableBody local = make_body(s, m), full = make_body(s, m);
  full.set_local_solves(false);
  const Eigen::VectorXd pattern = pattern_at(s, 0.4, 0.55);
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3d force(0.0, 0.0, t < 120 ? -2.0 : 0.0);
    const Eigen::VectorXd& g = t < 120 ? pattern : Eigen::VectorXd();
    REQUIRE(local.begin_step(1e-3, {}, g).ok());
    REQUIRE(full.begin_step(1e-3, {}, g).ok());
    local.finish_step(force);
    full.finish_step(force);
    CHECK(local.solved_window() == whole(s));
  }
  CHECK((local.control_points() - full.control_points()).cwiseAbs().maxCoeff() == 0.0);
  CHECK((local.rest_control_points() - full.rest_control_points()).cwiseAbs().maxCoeff() == 0.0);
  CHECK((local.velocities() - full.velocities()).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("no pole outside the active window moves, and the loads stay well inside it",
          "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);  // 64 x 64, 10 mm pitch
  argil::Material m = *argil::material_preset("clay");
  argil::DeformableBody body = make_body(s, m);
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  ControlNet frozen;
  PoleWindow window;
  int local_steps = 0;
  for (int t = 0; t < 300; ++t) {
    // The load travels along u over 0.3 of the panel.
    const Eigen::VectorXd g = pattern_at(s, 0.3 + 0.001 * t, 0.5);
    REQUIRE(body.begin_step(1e-3, {}, g).ok());
    body.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
    const PoleWindow w = body.solved_window();
    if (w == whole(s)) {
      CHECK(local_steps == 0);  // the whole net only until the first window is ready
      continue;
    }
    ++local_steps;
    CHECK(w.contains(loaded(s, g)));
    // Slides with the load: the trail, once at rest, is left behind.
    CHECK(w.count_u() <=
          loaded(s, g).count_u() + 2 * body.window_margin(0) + body.window_slack(0) + 1);
    if (!(w == window)) {
      window = w;
      frozen = body.control_points();
      continue;
    }
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) {
        if (w.contains(i, j)) continue;
        const Eigen::Index r = s.pole_index(i, j);
        REQUIRE((body.control_points().row(r) - frozen.row(r)).cwiseAbs().maxCoeff() == 0.0);
        REQUIRE(body.velocities().row(r).isZero(0.0));
      }
  }
  CHECK(local_steps > 250);
  CHECK(window.count_u() * window.count_v() < nu * nv / 3);
}

TEST_CASE(
    "a window opened on a body at rest is kept once the load is gone: the body settles in it "
    "and the poles outside never move",
    "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);
  argil::DeformableBody body = make_body(s, *argil::material_preset("clay"));
  const Eigen::VectorXd g = pattern_at(s, 0.5, 0.5);
  for (int t = 0; t < 100; ++t) {
    REQUIRE(body.begin_step(1e-3, {}, g).ok());
    body.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
  }
  const PoleWindow w = body.solved_window();
  REQUIRE(!(w == whole(s)));
  for (int t = 0; t < 2000; ++t) {
    REQUIRE(body.step(1e-3).ok());
    REQUIRE(body.solved_window() == w);
  }
  // Unloaded, the equilibrium is the (plastic) rest net: inside the window the
  // body creeps towards it; outside it every pole is still exactly where it was.
  const ControlNet stretch = body.control_points() - body.rest_control_points();
  CHECK(stretch.rowwise().norm().maxCoeff() < 1e-3);  // [mm] of a dent of about 0.2 mm
  double outside = 0.0;
  for (int i = 0; i < s.count(Direction::u); ++i)
    for (int j = 0; j < s.count(Direction::v); ++j)
      if (!w.contains(i, j)) {
        const Eigen::Index r = s.pole_index(i, j);
        outside =
            std::max(outside, (body.control_points().row(r) - s.control_points.row(r)).norm());
      }
  CHECK(outside == 0.0);
  // Put to sleep, the body drops its window: the next load opens one where it lands.
  body.halt();
  REQUIRE(body.step(1e-3).ok());
  CHECK(body.solved_window().empty());
}

TEST_CASE(
    "a body exactly at rest with no load solves nothing; the first load gets a window at once",
    "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);
  argil::DeformableBody body = make_body(s, *argil::material_preset("clay"));
  const ControlNet before = body.control_points();
  for (int t = 0; t < 3; ++t) REQUIRE(body.step(1e-3).ok());
  CHECK(body.solved_window().empty());
  CHECK((body.control_points() - before).cwiseAbs().maxCoeff() == 0.0);
  // The first window has no slack and is factorised within the step that
  // would otherwise have solved the whole net.
  const Eigen::VectorXd g = pattern_at(s, 0.5, 0.5);
  REQUIRE(body.begin_step(1e-3, {}, g).ok());
  body.finish_step(Eigen::Vector3d(0.0, 0.0, -1.0));
  const PoleWindow w = body.solved_window();
  CHECK(!w.empty());
  CHECK(!(w == whole(s)));
  CHECK(w == loaded(s, g).grown(body.window_margin(0), body.window_margin(1), s.count(Direction::u),
                                s.count(Direction::v)));
}

TEST_CASE(
    "a sphere press on a 64 x 64 panel solved locally dents and pushes back as the whole "
    "net does, within 1%",
    "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);
  argil::test::SpherePress press;
  press.uv = {0.43, 0.57};
  press.radius = 5.0;
  press.depth = 2.0;
  press.approach = 1.0;
  press.approach_time = 0.05;
  press.press_time = 0.3;
  press.release_time = 0.05;
  press.material = *argil::material_preset("clay");
  press.check_every = 1000;
  press.samples = 9;
  const argil::test::PressOutcome local = argil::test::press_sphere(s, press);
  press.options.local_solves = false;
  const argil::test::PressOutcome full = argil::test::press_sphere(s, press);
  REQUIRE(local.error.empty());
  REQUIRE(full.error.empty());
  INFO("dent local " << local.dent << " full " << full.dent << "; force local " << local.peak_force
                     << " full " << full.peak_force);
  REQUIRE(full.dent > 0.1);
  CHECK(std::abs(local.dent - full.dent) < 0.01 * full.dent);
  CHECK(std::abs(local.peak_force - full.peak_force) < 0.01 * full.peak_force);
}

TEST_CASE(
    "a load dragged at 1 m/s across a 64 x 64 panel: the window slides ahead of it in time, "
    "dropping the trail once it rests, and the trail matches the whole-net solve's within 1% of "
    "its depth, loaded and after release",
    "[deformation][local]") {
  // Clay keeps the dent; foam springs back (its trail has come back to rest
  // by the time the window leaves it).
  const std::string preset = GENERATE("clay", "foam");
  INFO(preset);
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);  // 10 mm pitch
  argil::Material m = *argil::material_preset(preset);
  argil::DeformableBody local = make_body(s, m);
  argil::DeformableBody full = make_body(s, m);
  full.set_local_solves(false);
  const double du = 1.0 / 630.0;  // 1 mm a 1 ms step along u
  PoleWindow last;
  int windows = 0;
  int widest = 0;
  for (int t = 0; t < 300; ++t) {
    const Eigen::VectorXd g = pattern_at(s, 0.25 + du * t, 0.5);
    for (argil::DeformableBody* body : {&local, &full}) {
      REQUIRE(body->begin_step(1e-3, {}, g).ok());
      body->finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
    }
    const PoleWindow w = local.solved_window();
    INFO("step " << t);
    // The first window is factorised in the first step; each later one is
    // ready before the load leaves the window it grows from.
    REQUIRE(!(w == whole(s)));
    REQUIRE(w.contains(loaded(s, g)));
    widest = std::max(widest, w.count_u());
    if (!(w == last)) ++windows, last = w;
  }
  CHECK(windows >= 3);  // the load crossed 30 poles: the window moved on the way
  // The window slides when the trail rests: only the way the load travels
  // gets slack, one pole behind it, and sideways the margin.
  const PoleWindow load = loaded(s, pattern_at(s, 0.25 + du * 299, 0.5));
  const int sliding = load.count_u() + 2 * local.window_margin(0) + local.window_slack(0) + 1;
  CHECK(widest <= sliding);
  CHECK(last.count_v() == load.count_v() + 2 * local.window_margin(1));
  CHECK(!last.contains(loaded(s, pattern_at(s, 0.25, 0.5))));  // it left the start behind
  // The trail: every pole's sink, local against whole, loaded and then after
  // 300 steps without the load.
  for (const char* phase : {"loaded", "released"}) {
    INFO(phase);
    if (std::string(phase) == "released")
      for (int t = 0; t < 300; ++t)
        for (argil::DeformableBody* body : {&local, &full}) REQUIRE(body->step(1e-3).ok());
    const ControlNet sink_local = local.control_points() - s.control_points;
    const ControlNet sink_full = full.control_points() - s.control_points;
    const double depth = sink_full.col(2).cwiseAbs().maxCoeff();
    const double difference = (sink_local - sink_full).cwiseAbs().maxCoeff();
    INFO("trail depth " << depth << " mm, largest difference " << difference << " mm");
    if (std::string(phase) == "loaded") REQUIRE(depth > 0.05);
    CHECK(difference < 0.01 * std::max(depth, 0.05));
  }
}

TEST_CASE("a window moves on from poles at rest only: poles still moving stay in it",
          "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);  // 10 mm pitch
  const argil::Material m = *argil::material_preset("clay");
  // Pressed at one place for 20 steps, left alone for `rest` steps, then
  // pressed at once 0.1 further along u (6 poles: past the margin) until the
  // window the second load needs is ready.
  const auto windows_after = [&](int rest) {
    argil::DeformableBody body = make_body(s, m);
    const Eigen::VectorXd first = pattern_at(s, 0.3, 0.5), second = pattern_at(s, 0.4, 0.5);
    for (int t = 0; t < 20; ++t) {
      REQUIRE(body.begin_step(1e-3, {}, first).ok());
      body.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
    }
    for (int t = 0; t < rest; ++t) REQUIRE(body.step(1e-3).ok());
    const PoleWindow before = body.solved_window();
    const double motion = body.last_step_motion();
    PoleWindow after = before;
    for (int t = 0; t < 200 && after == before; ++t) {
      REQUIRE(body.begin_step(1e-3, {}, second).ok());
      body.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
      after = body.solved_window();
    }
    INFO("left alone " << rest << " steps, last motion " << motion << " mm");
    REQUIRE(!(after == before));
    REQUIRE(after.contains(loaded(s, second)));
    return std::tuple(before, after, motion);
  };
  // Still sinking: the dent's poles move, and the window grows over them.
  const auto [moving_before, moving_after, moving] = windows_after(0);
  CHECK(moving >= argil::kWindowRestMotion);
  CHECK(moving_after.contains(moving_before));
  // Come to rest: the window leaves the dent behind.
  const auto [rested_before, rested_after, rested] = windows_after(1000);
  CHECK(rested < argil::kWindowRestMotion);
  CHECK(!rested_after.contains(rested_before));
  CHECK(rested_after.count_u() < moving_after.count_u());
}

TEST_CASE(
    "a window dropped when its body sleeps serves a load that comes back inside it at once, as "
    "the whole net would; a load elsewhere or at another dt gets a window of its own",
    "[deformation][local]") {
  const BSplineSurface s = argil::test::flat_bicubic_panel(630.0, 61);  // 10 mm pitch
  const argil::Material m = *argil::material_preset("clay");
  const int nu = s.count(Direction::u), nv = s.count(Direction::v);
  argil::DeformableBody local = make_body(s, m);
  argil::DeformableBody full = make_body(s, m);
  full.set_local_solves(false);
  const auto press = [&](double u, int steps, double dt) {
    for (int t = 0; t < steps; ++t) {
      const Eigen::VectorXd g = pattern_at(s, u, 0.5);
      for (argil::DeformableBody* body : {&local, &full}) {
        REQUIRE(body->begin_step(dt, {}, g).ok());
        body->finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
      }
    }
  };
  // A load travelling along u: its window grows ahead of it, larger than a
  // first window where the load ends (which has no slack).
  for (int t = 0; t < 30; ++t) press(0.30 + 0.001 * t, 1, 1e-3);
  const PoleWindow grown = local.solved_window();
  const auto first_window = [&](double u) {
    return loaded(s, pattern_at(s, u, 0.5))
        .grown(local.window_margin(0), local.window_margin(1), nu, nv);
  };
  REQUIRE(!(grown == whole(s)));
  REQUIRE(grown.contains(first_window(0.329)));
  REQUIRE(!(grown == first_window(0.329)));
  // Put to sleep, and pressed again where the load ended: the first step
  // solves the dropped window, factorised long ago (without it, a new window
  // is factorised within that step).
  local.halt();
  full.halt();
  const auto difference = [&] {
    const ControlNet sink_local = local.control_points() - s.control_points;
    const ControlNet sink_full = full.control_points() - s.control_points;
    const double depth = sink_full.col(2).cwiseAbs().maxCoeff();
    INFO("dent " << depth << " mm");
    REQUIRE(depth > 0.05);
    return (sink_local - sink_full).cwiseAbs().maxCoeff() / depth;
  };
  const double before = difference();
  press(0.329, 1, 1e-3);
  CHECK(local.solved_window() == grown);
  CHECK(!local.window_growing());
  // Its first steps move the poles as the whole net's do (a factor of
  // another step would not), and so do a hundred more.
  press(0.329, 4, 1e-3);
  CHECK(difference() < before + 0.001);  // 6e-4 before, 5e-4 after, measured
  press(0.329, 100, 1e-3);
  CHECK(local.solved_window() == grown);
  CHECK(difference() < 0.01);
  // Asleep again and pressed outside it: a first window of its own where it
  // lands (the dropped one stays kept).
  local.halt();
  REQUIRE(local.begin_step(1e-3, {}, pattern_at(s, 0.7, 0.5)).ok());
  local.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
  CHECK(local.solved_window() == first_window(0.7));
  // Pressed where it lies at another dt: not the kept window, factorised for
  // 1 ms steps.
  REQUIRE(local.begin_step(2e-3, {}, pattern_at(s, 0.329, 0.5)).ok());
  local.finish_step(Eigen::Vector3d(0.0, 0.0, -3.0));
  CHECK(!(local.solved_window() == grown));
}
