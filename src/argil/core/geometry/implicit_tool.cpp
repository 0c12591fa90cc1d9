#include "argil/core/geometry/implicit_tool.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "argil/core/geometry/triangle_distance.hpp"

namespace argil {

double ImplicitTool::lower_bound_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                             const Eigen::Vector3d& c) const {
  const Eigen::Vector3d centroid = (a + b + c) / 3.0;
  const double reach =
      std::max({(a - centroid).norm(), (b - centroid).norm(), (c - centroid).norm()});
  return distance(centroid).value - lipschitz() * reach;
}

Box3 ImplicitTool::bounding_box() const {
  const double inf = std::numeric_limits<double>::infinity();
  return {Eigen::Vector3d::Constant(-inf), Eigen::Vector3d::Constant(inf)};
}

namespace {

/// The world box of a tool-frame box [-half, half] posed by R and c: each
/// world half extent is sum_j |R_ij| half_j.
Box3 posed_box(const Eigen::Matrix3d& R, const Eigen::Vector3d& c, const Eigen::Vector3d& half) {
  const Eigen::Vector3d extent = R.cwiseAbs() * half;
  return {c - extent, c + extent};
}

/// Distance to a point c minus r: the sphere; also the capsule near its segment.
DistanceSample ball_distance(const Eigen::Vector3d& x, const Eigen::Vector3d& c, double r) {
  DistanceSample s;
  const Eigen::Vector3d d = x - c;
  const double length = d.norm();
  s.value = length - r;
  if (length > 0.0) {
    s.gradient = d / length;
    s.hessian = (Eigen::Matrix3d::Identity() - s.gradient * s.gradient.transpose()) / length;
  }
  return s;
}

class Plane final : public ImplicitTool {
 public:
  Plane(const Eigen::Vector3d& n, double offset) : n_(n.normalized()), offset_(offset) {}
  DistanceSample distance(const Eigen::Vector3d& p) const override {
    DistanceSample s;
    s.value = n_.dot(p) - offset_;
    s.gradient = n_;
    return s;
  }
  double value(const Eigen::Vector3d& p) const override { return n_.dot(p) - offset_; }
  double lower_bound_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) const override {
    return std::min({n_.dot(a), n_.dot(b), n_.dot(c)}) - offset_;
  }
  bool exact_triangle_bound() const override { return true; }

 private:
  Eigen::Vector3d n_;
  double offset_;
};

class Sphere final : public ImplicitTool {
 public:
  Sphere(const Eigen::Vector3d& c, double r) : c_(c), r_(r) {}
  DistanceSample distance(const Eigen::Vector3d& p) const override {
    return ball_distance(p, c_, r_);
  }
  double value(const Eigen::Vector3d& p) const override { return (p - c_).norm() - r_; }
  double lower_bound_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) const override {
    return (closest_point_on_triangle(c_, a, b, c) - c_).norm() - r_;
  }
  bool exact_triangle_bound() const override { return true; }
  Box3 bounding_box() const override {
    return {c_ - Eigen::Vector3d::Constant(r_), c_ + Eigen::Vector3d::Constant(r_)};
  }

 private:
  Eigen::Vector3d c_;
  double r_;
};

class Capsule final : public ImplicitTool {
 public:
  Capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r) : a_(a), b_(b), r_(r) {}
  DistanceSample distance(const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d ab = b_ - a_;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a_).dot(ab) / length2, 0.0, 1.0) : 0.0;
    DistanceSample s = ball_distance(p, a_ + t * ab, r_);
    if (t > 0.0 && t < 1.0 && length2 > 0.0) {
      // Along the segment the distance does not change: remove that curvature.
      const Eigen::Vector3d axis = ab / std::sqrt(length2);
      const Eigen::Vector3d d = p - (a_ + t * ab);
      const double rho = d.norm();
      if (rho > 0.0) {
        const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - axis * axis.transpose();
        s.hessian = (across - s.gradient * s.gradient.transpose()) / rho;
      }
    }
    return s;
  }
  double lower_bound_on_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) const override {
    return segment_triangle_distance(a_, b_, a, b, c) - r_;
  }
  bool exact_triangle_bound() const override { return true; }
  Box3 bounding_box() const override {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(r_);
    return {a_.cwiseMin(b_) - r, a_.cwiseMax(b_) + r};
  }

 private:
  Eigen::Vector3d a_, b_;
  double r_;
};

/// Tools known by value only: gradient and Hessian by central differences.
class ValueTool : public ImplicitTool {
 public:
  explicit ValueTool(double h) : h_(h) {}
  DistanceSample distance(const Eigen::Vector3d& p) const override {
    DistanceSample s;
    s.value = value(p);
    Eigen::Vector3d fp, fm;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(i) * h_;
      fp[i] = value(p + e);
      fm[i] = value(p - e);
      s.gradient[i] = (fp[i] - fm[i]) / (2 * h_);
      s.hessian(i, i) = (fp[i] - 2 * s.value + fm[i]) / (h_ * h_);
    }
    for (int i = 0; i < 3; ++i) {
      for (int j = i + 1; j < 3; ++j) {
        const Eigen::Vector3d ei = Eigen::Vector3d::Unit(i) * h_;
        const Eigen::Vector3d ej = Eigen::Vector3d::Unit(j) * h_;
        const double mixed =
            (value(p + ei + ej) - value(p + ei - ej) - value(p - ei + ej) + value(p - ei - ej)) /
            (4 * h_ * h_);
        s.hessian(i, j) = s.hessian(j, i) = mixed;
      }
    }
    return s;
  }
  double value(const Eigen::Vector3d& p) const override = 0;

 private:
  double h_;
};

class Box final : public ValueTool {
 public:
  Box(const Eigen::Matrix3d& R, const Eigen::Vector3d& c, const Eigen::Vector3d& half)
      : ValueTool(1e-6 * half.maxCoeff()), R_(R), c_(c), half_(half) {}
  double value(const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d q = (R_.transpose() * (p - c_)).cwiseAbs() - half_;
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  }
  Box3 bounding_box() const override { return posed_box(R_, c_, half_); }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d c_, half_;
};

class Ellipsoid final : public ValueTool {
 public:
  Ellipsoid(const Eigen::Matrix3d& R, const Eigen::Vector3d& c, const Eigen::Vector3d& radii)
      : ValueTool(1e-6 * radii.maxCoeff()), R_(R), c_(c), radii_(radii) {}
  double value(const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d x = R_.transpose() * (p - c_);
    return (x.cwiseQuotient(radii_).norm() - 1.0) * radii_.minCoeff();
  }
  /// Exact: the support of the ellipsoid along world axis i is |row i of R diag(radii)|.
  Box3 bounding_box() const override {
    const Eigen::Vector3d extent = (R_ * radii_.asDiagonal()).rowwise().norm();
    return {c_ - extent, c_ + extent};
  }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d c_, radii_;
};

class Torus final : public ValueTool {
 public:
  Torus(const Eigen::Matrix3d& R, const Eigen::Vector3d& c, double major, double minor)
      : ValueTool(1e-6 * (major + minor)), R_(R), c_(c), major_(major), minor_(minor) {}
  double value(const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d x = R_.transpose() * (p - c_);
    const double ring = std::hypot(x.x(), x.y()) - major_;
    return std::hypot(ring, x.z()) - minor_;
  }
  Box3 bounding_box() const override {
    const double reach = major_ + minor_;
    return posed_box(R_, c_, Eigen::Vector3d(reach, reach, minor_));
  }

 private:
  Eigen::Matrix3d R_;
  Eigen::Vector3d c_;
  double major_, minor_;
};

class UserSdf final : public ValueTool {
 public:
  UserSdf(std::function<double(const Eigen::Vector3d&)> f, double lipschitz, double h)
      : ValueTool(h), f_(std::move(f)), lipschitz_(lipschitz) {}
  double value(const Eigen::Vector3d& p) const override { return f_(p); }
  double lipschitz() const override { return lipschitz_; }

 private:
  std::function<double(const Eigen::Vector3d&)> f_;
  double lipschitz_;
};

}  // namespace

std::unique_ptr<ImplicitTool> make_plane(const Eigen::Vector3d& normal_W, double offset) {
  return std::make_unique<Plane>(normal_W, offset);
}
std::unique_ptr<ImplicitTool> make_sphere(const Eigen::Vector3d& p_WC, double radius) {
  return std::make_unique<Sphere>(p_WC, radius);
}
std::unique_ptr<ImplicitTool> make_capsule(const Eigen::Vector3d& a_W, const Eigen::Vector3d& b_W,
                                           double radius) {
  return std::make_unique<Capsule>(a_W, b_W, radius);
}
std::unique_ptr<ImplicitTool> make_box(const Eigen::Matrix3d& R_WT, const Eigen::Vector3d& p_WT,
                                       const Eigen::Vector3d& half_extents) {
  return std::make_unique<Box>(R_WT, p_WT, half_extents);
}
std::unique_ptr<ImplicitTool> make_ellipsoid(const Eigen::Matrix3d& R_WT,
                                             const Eigen::Vector3d& p_WT,
                                             const Eigen::Vector3d& radii) {
  return std::make_unique<Ellipsoid>(R_WT, p_WT, radii);
}
std::unique_ptr<ImplicitTool> make_torus(const Eigen::Matrix3d& R_WT, const Eigen::Vector3d& p_WT,
                                         double major, double minor) {
  return std::make_unique<Torus>(R_WT, p_WT, major, minor);
}
std::unique_ptr<ImplicitTool> make_user_sdf(std::function<double(const Eigen::Vector3d&)> f,
                                            double lipschitz, double h) {
  assert(lipschitz > 0.0);
  return std::make_unique<UserSdf>(std::move(f), lipschitz, h);
}

}  // namespace argil
