#pragma once
// A god-object proxy for a rigid B-spline tool surface: posed per tick by
// moving its control points, advanced towards the device only as far as it
// does not cross any model surface (surface-surface collide), and sliding
// along the surface after it stops.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// A rigid pose X_WT: p_W = orientation * p_T + position [mm].
struct ToolPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

/// Contacts of the posed tool with every surface, and whether any crosses.
struct ToolContacts {
  std::vector<std::vector<Contact>> per_surface;  // contacts of surface b (its side a)
  bool crosses = false;
  /// Mean unit normal of the contacts, oriented from the surfaces towards the
  /// tool's control-point centre (zero without contacts).
  Eigen::Vector3d outward_normal = Eigen::Vector3d::Zero();
};

/// Conservative advancement: a move from a pose that crosses nothing goes in
/// substeps of at most max(tool size / 4, 10 eps); a substep whose end crosses
/// a surface is bisected until the last pose that does not cross is within
/// eps / 2 of one that does, and the proxy stops there; the rest of the move,
/// less its component into the surface, is tried once more the same way
/// (sliding). So after a move the tool crosses no surface (touching within
/// eps counts as contact, not crossing). A start pose that crosses (the
/// surface moved into the tool) is first pushed out along the contact normal.
class SurfaceToolProxy {
 public:
  /// `tool` in its own frame T; fails when it does not validate.
  static Result<SurfaceToolProxy> create(const BSplineSurface& tool, double eps,
                                         OperatorCache& cache);

  /// The tool posed at X_WT, collided with every surface.
  ToolContacts contacts(const std::vector<SurfaceHierarchy*>& surfaces, const ToolPose& pose);
  /// Moves from `from` towards `to` (orientation interpolated by slerp).
  ToolPose move(const std::vector<SurfaceHierarchy*>& surfaces, const ToolPose& from,
                const ToolPose& to);
  /// The tool's hierarchy at the last pose used.
  SurfaceHierarchy& hierarchy() { return posed_; }
  double size() const { return size_; }
  static constexpr int kMaxBisections = 12;

 private:
  SurfaceToolProxy(const BSplineSurface& tool, SurfaceHierarchy posed, double eps);
  void place(const ToolPose& pose);
  bool crosses(const std::vector<SurfaceHierarchy*>& surfaces, const ToolPose& pose);
  /// From a pose that does not cross towards `to`: the last pose that does not.
  ToolPose advance(const std::vector<SurfaceHierarchy*>& surfaces, const ToolPose& from,
                   const ToolPose& to, bool& blocked);

  ControlNet tool_points_;  // in T
  SurfaceHierarchy posed_;
  double eps_;
  double size_;
};

}  // namespace argil
