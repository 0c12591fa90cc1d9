// Broad phase and scene collision against brute force: every pair of bodies
// tested directly must give the same contacts as the scene query.

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "argil/core/collision/broad_phase.hpp"
#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/collision/scene_collision.hpp"
#include "argil/core/collision/surface_intersection.hpp"
#include "support/random_surface.hpp"

using namespace argil;

namespace {

bool boxes_within(const Box3& a, const Box3& b, double eps) {
  for (int k = 0; k < 3; ++k) {
    if (a.min[k] > b.max[k] + eps || b.min[k] > a.max[k] + eps) return false;
  }
  return true;
}

Box3 random_box(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> where(-100.0, 100.0), size(0.0, 15.0);
  Eigen::Vector3d lo(where(rng), where(rng), where(rng));
  Eigen::Vector3d extent(size(rng), size(rng), size(rng));
  return {lo, lo + extent};
}

ControlNet translated(const ControlNet& points, const Eigen::Vector3d& offset) {
  ControlNet moved = points;
  moved.rowwise() += offset.transpose();
  return moved;
}

}  // namespace

TEST_CASE("overlapping_pairs equals the all-pairs box test") {
  std::mt19937_64 rng(7);
  const double inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Box3> boxes;
    const int count = 1 + trial % 60;
    for (int i = 0; i < count; ++i) boxes.push_back(random_box(rng));
    // Extremes: a point box, a box sharing a face, an unbounded tool, a slab.
    if (trial % 3 == 0) boxes.push_back({Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3)});
    if (trial % 4 == 0) {
      boxes.push_back({boxes[0].max, boxes[0].max + Eigen::Vector3d::Constant(5)});
    }
    if (trial % 5 == 0) {
      boxes.push_back({Eigen::Vector3d::Constant(-inf), Eigen::Vector3d::Constant(inf)});
    }
    if (trial % 7 == 0) {
      boxes.push_back({Eigen::Vector3d(-inf, -inf, -1), Eigen::Vector3d(inf, inf, 1)});
    }
    const double eps = trial % 2 == 0 ? 0.0 : 2.0;

    std::vector<BodyPair> expected;
    for (int a = 0; a < static_cast<int>(boxes.size()); ++a) {
      for (int b = a + 1; b < static_cast<int>(boxes.size()); ++b) {
        if (boxes_within(boxes[static_cast<std::size_t>(a)], boxes[static_cast<std::size_t>(b)],
                         eps)) {
          expected.push_back({a, b});
        }
      }
    }
    INFO("trial " << trial << ", " << boxes.size() << " boxes, eps " << eps);
    CHECK(overlapping_pairs(boxes, eps) == expected);
  }
}

TEST_CASE("a box with a NaN bound pairs with nothing") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Box3> boxes{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()},
                          {Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d::Ones()},
                          {Eigen::Vector3d::Constant(0.5), Eigen::Vector3d::Constant(2)}};
  CHECK(overlapping_pairs(boxes, 0.0) == std::vector<BodyPair>{{0, 2}});
}

TEST_CASE("tool bounding boxes hold every point inside the tool") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), positive(0.5, 20.0);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d c(unit(rng) * 50, unit(rng) * 50, unit(rng) * 50);
    std::vector<std::unique_ptr<ImplicitTool>> tools;
    tools.push_back(make_sphere(c, positive(rng)));
    tools.push_back(
        make_capsule(c, c + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 30, positive(rng)));
    tools.push_back(make_box(R, c, Eigen::Vector3d(positive(rng), positive(rng), positive(rng))));
    tools.push_back(
        make_ellipsoid(R, c, Eigen::Vector3d(positive(rng), positive(rng), positive(rng))));
    tools.push_back(make_torus(R, c, 20.0 + positive(rng), positive(rng)));
    for (const auto& tool : tools) {
      const Box3 box = tool->bounding_box();
      // Points sampled around the box: those inside the tool must be inside the box,
      // and the box must not be loose by more than its own size (it is tight or near).
      const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
      const Eigen::Vector3d half = 0.5 * box.extent();
      int inside = 0;
      for (int s = 0; s < 4000; ++s) {
        const Eigen::Vector3d x =
            centre + 1.3 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(half);
        if (tool->value(x) > 0.0) continue;
        ++inside;
        const double slack = 1e-9 * (1.0 + box.diagonal());
        CHECK((x.array() >= box.min.array() - slack).all());
        CHECK((x.array() <= box.max.array() + slack).all());
      }
      CHECK(inside > 0);
    }
  }
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(make_plane(Eigen::Vector3d::UnitZ(), 0.0)->bounding_box().max.x() == inf);
}

TEST_CASE("scene collision gives the same contacts as testing every pair directly") {
  std::mt19937_64 rng(2024);
  OperatorCache cache;
  std::uniform_real_distribution<double> where(-150.0, 150.0), radius(5.0, 40.0);
  test::RandomSurfaceOptions options;
  options.max_degree = 3;
  options.max_extra_poles = 3;
  options.size = 60.0;

  std::size_t pairs_in_contact = 0;
  long candidates = 0;
  long testable = 0;
  for (int scene_index = 0; scene_index < 6; ++scene_index) {
    std::vector<SurfaceHierarchy> surfaces;
    for (int i = 0; i < 12; ++i) {
      BSplineSurface s = test::random_surface(rng, options);
      s.control_points =
          translated(s.control_points, Eigen::Vector3d(where(rng), where(rng), 0.3 * where(rng)));
      auto built = SurfaceHierarchy::build(s, cache);
      REQUIRE(built.ok());
      surfaces.push_back(std::move(built).value());
    }
    std::vector<std::unique_ptr<ImplicitTool>> tools;
    for (int i = 0; i < 4; ++i) {
      tools.push_back(
          make_sphere(Eigen::Vector3d(where(rng), where(rng), 0.3 * where(rng)), radius(rng)));
    }
    tools.push_back(make_plane(Eigen::Vector3d(0.1, 0.2, 1.0), 0.1 * where(rng)));

    std::vector<SceneBody> bodies;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
      bodies.push_back({&surfaces[i], nullptr, i % 4 == 0});
    }
    for (const auto& tool : tools) bodies.push_back({nullptr, tool.get(), false});

    CollisionRequest request;
    request.tolerance = 0.05;
    request.refine = false;
    const auto scene = collide_scene(bodies, request);
    REQUIRE(scene.ok());

    // Brute force: every pair that the scene should test, by the narrow phase alone.
    std::vector<BodyPairContacts> expected;
    for (int a = 0; a < static_cast<int>(bodies.size()); ++a) {
      for (int b = a + 1; b < static_cast<int>(bodies.size()); ++b) {
        const SceneBody& ba = bodies[static_cast<std::size_t>(a)];
        const SceneBody& bb = bodies[static_cast<std::size_t>(b)];
        if ((ba.tool && bb.tool) || (ba.fixed && bb.fixed)) continue;
        ++testable;
        CollisionResult r = ba.surface && bb.surface ? collide(*ba.surface, *bb.surface, request)
                            : ba.surface             ? collide(*ba.surface, *bb.tool, request)
                                                     : collide(*bb.surface, *ba.tool, request);
        if (!r.contacts.empty() || !r.curves.empty()) {
          expected.push_back({{a, b}, ba.surface ? a : b, std::move(r)});
        }
      }
    }
    INFO("scene " << scene_index);
    REQUIRE(scene.value().pairs.size() == expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      const BodyPairContacts& got = scene.value().pairs[k];
      CHECK(got.bodies == expected[k].bodies);
      CHECK(got.surface_side == expected[k].surface_side);
      REQUIRE(got.result.contacts.size() == expected[k].result.contacts.size());
      for (std::size_t c = 0; c < expected[k].result.contacts.size(); ++c) {
        CHECK(got.result.contacts[c].point == expected[k].result.contacts[c].point);
        CHECK(got.result.contacts[c].depth == expected[k].result.contacts[c].depth);
      }
      CHECK(got.result.curves.size() == expected[k].result.curves.size());
    }
    pairs_in_contact += expected.size();
    candidates += scene.value().candidate_pairs;
  }
  // The scenes must exercise contact, and the broad phase must prune.
  WARN("pairs in contact " << pairs_in_contact << ", candidates " << candidates << " of "
                           << testable);
  CHECK(pairs_in_contact >= 10);
  CHECK(candidates < testable / 2);
}

TEST_CASE("scene collision follows deformation and rejects malformed bodies") {
  OperatorCache cache;
  std::mt19937_64 rng(5);
  test::RandomSurfaceOptions options;
  options.max_degree = 3;
  options.size = 10.0;
  const BSplineSurface s = test::random_surface(rng, options);
  auto built = SurfaceHierarchy::build(s, cache);
  REQUIRE(built.ok());
  SurfaceHierarchy surface = std::move(built).value();
  const auto tool = make_sphere(Eigen::Vector3d(500, 0, 0), 1.0);
  std::vector<SceneBody> bodies{{&surface, nullptr, false}, {nullptr, tool.get(), false}};

  CollisionRequest request;
  request.tolerance = 1e-3;
  auto before = collide_scene(bodies, request);
  REQUIRE(before.ok());
  CHECK(before.value().candidate_pairs == 0);
  CHECK(before.value().pairs.empty());

  // Move the surface onto the tool: the root bound must follow the new control points.
  const Eigen::Vector3d centre = s.control_points.colwise().mean().transpose();
  surface.set_control_points(translated(s.control_points, Eigen::Vector3d(500, 0, 0) - centre));
  auto after = collide_scene(bodies, request);
  REQUIRE(after.ok());
  CHECK(after.value().candidate_pairs == 1);

  std::vector<SceneBody> bad{{nullptr, nullptr, false}};
  const auto error = collide_scene(bad, request);
  REQUIRE_FALSE(error.ok());
  CHECK(error.status().message.find("scene body 0") != std::string::npos);
  std::vector<SceneBody> both{{&surface, tool.get(), false}};
  CHECK_FALSE(collide_scene(both, request).ok());
}
