// Pose: composition, inverse and interpolation against Eigen::Isometry3d as
// the independent oracle, on random rotations and offsets.
#include <catch2/catch.hpp>
#include <random>

#include "argil/core.hpp"

namespace {

argil::Pose random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Quaterniond R =
      Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
  return {R, Eigen::Vector3d(unit(rng), unit(rng), unit(rng)) * 250.0};
}

Eigen::Isometry3d isometry(const argil::Pose& X) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = X.R.toRotationMatrix();
  out.translation() = X.p;
  return out;
}

// Poses reach 500 mm from the origin; composing two adds a few roundings of that.
constexpr double kLengthTolerance = 1e-11;  // [mm]

}  // namespace

TEST_CASE("pose composition and apply agree with Eigen's isometries", "[pose]") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const argil::Pose X_AB = random_pose(rng), X_BC = random_pose(rng);
    const Eigen::Vector3d p_C = random_pose(rng).p;
    const Eigen::Vector3d expected = isometry(X_AB) * (isometry(X_BC) * p_C);
    CHECK((argil::apply(X_AB * X_BC, p_C) - expected).norm() < kLengthTolerance);
    CHECK((argil::apply(X_AB, argil::apply(X_BC, p_C)) - expected).norm() < kLengthTolerance);
  }
}

TEST_CASE("a pose composed with its inverse is the identity", "[pose]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const argil::Pose X_AB = random_pose(rng);
    const argil::Pose X_AA = X_AB * argil::inverse(X_AB);
    const argil::Pose X_BB = argil::inverse(X_AB) * X_AB;
    CHECK(X_AA.p.norm() < kLengthTolerance);
    CHECK(X_BB.p.norm() < kLengthTolerance);
    CHECK(X_AA.R.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
    CHECK(X_BB.R.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);
  }
}

TEST_CASE("pose interpolation is linear in position and slerp in rotation", "[pose]") {
  std::mt19937 rng(13);
  const argil::Pose a = random_pose(rng), b = random_pose(rng);
  for (const double t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const argil::Pose m = argil::interpolate(a, b, t);
    CHECK((m.p - ((1.0 - t) * a.p + t * b.p)).norm() < kLengthTolerance);
    // The rotation lies on the shortest arc: angles from a and to b add up.
    const double whole = a.R.angularDistance(b.R);
    CHECK(a.R.angularDistance(m.R) == Approx(t * whole).margin(1e-12));
    CHECK(m.R.angularDistance(b.R) == Approx((1.0 - t) * whole).margin(1e-12));
  }
}
