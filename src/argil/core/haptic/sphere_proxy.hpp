#pragma once
// A god-object proxy for a sphere (or point, radius 0) tool: it follows the
// device but never sinks into a surface by more than eps, and never passes
// through one, however fast the device moves.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "argil/core/collision/trimmed_contact.hpp"

namespace argil {

/// The surface nearest to a proxy.
struct [[nodiscard]] ProxyContact {
  /// Not ok when a closest-point query failed (its status; nothing else is set).
  Status status;
  int body = -1;           // index into the surfaces, -1 when there are none
  double clearance = 0.0;  // distance from the centre minus the radius [mm]; < 0 when sinking
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // closest surface point [mm]
  /// Unit vector from the surfaces towards the proxy centre (the side the
  /// proxy is on): the nearest surface's, blended with every surface within
  /// eps of it (weighted by how much closer than nearest + eps it is).
  Eigen::Vector3d outward_normal = Eigen::Vector3d::Zero();
};

/// Moves a sphere of radius r [mm] among surfaces, keeping it on the side of
/// each surface it started on. Only material counts: on a trimmed surface the
/// closest point is that of the material (closest_point on a TrimmedSurface),
/// which lies on the face's edge where the centre is beyond it. Each move goes
/// in straight substeps of at most max(r / 2, 10 eps); after each substep the
/// centre is pushed out of every surface to distance r (closest points
/// certified within eps / 4; on an edge, away from the edge point, so the
/// sphere rolls over it), so the sphere's depth is at most eps / 4 after a
/// move, and a surface the centre crossed (the closest point is interior and
/// on the other side) pushes it back to the side it came from. Sides change
/// only around a surface's boundary: its domain's sides and its trimmed edges
/// (so the sphere passes over a hole's rim and through the hole).
/// Where a move or projection left the centre. Not ok when a closest-point
/// query failed: the centre is then the last one reached before it.
struct [[nodiscard]] SphereMove {
  Status status;
  Eigen::Vector3d p_WT = Eigen::Vector3d::Zero();  // the centre [mm]
};

/// A surface's push on the centre: it must move at least `depth` [mm] along
/// the unit `normal`.
struct PushConstraint {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double depth = 0.0;
};

/// The smallest move x with normal_k . x >= depth_k for every push (the
/// god-object's constraint planes, solved together).
Eigen::Vector3d push_apart(const std::vector<PushConstraint>& pushes);

/// A surface whose hierarchy is null is out of the proxy's reach this tick:
/// every query skips it and its side record is kept.
///
/// Each surface's last closest point is kept with the path the centre has
/// travelled and the surface has moved since (set_surface_motion): while that
/// is shorter than the distance then, less the radius, the surface cannot
/// reach the sphere and is not queried. On a part of many faces, most within
/// a face's bounding box of the tool are still centimetres from it. So the
/// surfaces must move no farther than set_surface_motion tells; a surface
/// whose control points changed (its hierarchy's version) with no motion told
/// for it since (not listed, or 0) is queried afresh.
class SphereProxy {
 public:
  SphereProxy(double radius, double eps) : radius_(radius), eps_(eps) {}
  double radius() const { return radius_; }

  /// Moves the centre from `from` towards `to` and returns where it stops.
  SphereMove move(const std::vector<TrimmedSurface>& surfaces, const Eigen::Vector3d& from,
                  const Eigen::Vector3d& to);
  /// The centre pushed out of every surface: each round takes every surface's
  /// push from the same centre and moves by push_apart() of them (at most
  /// kMaxProjectionRounds rounds; the surfaces are curved, so one round is not
  /// always enough). `travel`: how far the centre moved since it was last
  /// found clear [mm] (0 for where a tick starts): a crossing cannot leave it
  /// farther behind a surface than that allows (push_out).
  SphereMove project(const std::vector<TrimmedSurface>& surfaces, const Eigen::Vector3d& centre,
                     double travel = 0.0);
  /// The nearest surface to `centre` (and updates the side record far from surfaces).
  ProxyContact nearest(const std::vector<TrimmedSurface>& surfaces, const Eigen::Vector3d& centre);
  /// How far each surface moved since the proxy's last queries [mm] (its
  /// body's last step; 0 for a rigid or sleeping body, and for a surface not
  /// listed): a surface that moved into the centre may have crossed it by
  /// that much (push_out). Kept until set again. `travel`, when given, bounds
  /// how far any point of each surface moved (DeformableBody::
  /// last_step_travel); the surfaces passed by rely on it. Not given, `motion`
  /// is taken as that bound.
  void set_surface_motion(std::vector<double> motion, std::vector<double> travel = {});
  /// Forgets which side of surface `index` the centre is on, and what the
  /// last query on it found: the next query records the side from the sign
  /// of the signed distance (for a surface the proxy did not query for a
  /// while, from far away, or whose material changed).
  void forget_side(std::size_t index);
  /// Closest-point queries made so far (a surface passed by, or whose last
  /// closest point still stands, costs none).
  long closest_point_queries() const { return queries_; }
  /// Largest number of substeps in one move (a longer move stops early).
  static constexpr int kMaxSubsteps = 256;
  static constexpr int kMaxProjectionRounds = 8;

 private:
  /// The centre pushed out of one surface, and whether it moved.
  struct [[nodiscard]] Push {
    Status status;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    bool moved = false;
  };
  /// `travel`: how far the centre moved since it was last found clear [mm].
  Push push_out(const TrimmedSurface& surface, std::size_t index, const Eigen::Vector3d& centre,
                double travel);
  int& side(std::size_t index);

  /// Where a surface stood: its hierarchy's control-point version, the
  /// set_surface_motion calls made before, and its surface_path_ then.
  struct Stance {
    std::uint64_t version = 0;
    std::uint64_t epoch = 0;
    double surface_path = 0.0;
  };
  /// The last centre a push_out passed a surface by at, and the lower bound
  /// on the surface's distance there.
  struct Pass {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    double clear = 0.0;
    Stance stance;
  };
  /// The last closest point found on one surface, and where the centre and
  /// the surface stood then.
  struct Seen {
    const SurfaceHierarchy* hierarchy = nullptr;  // null: nothing seen
    const TrimRegion* trim = nullptr;
    Stance stance;
    double path = 0.0;  // path_ then
    /// push_out found the centre clear of it, on its side: until the
    /// surface can have reached the sphere since, it cannot push.
    bool clear = false;
    /// Set when a push_out passed the surface by since its side was last
    /// read: the side was not followed round an edge meanwhile.
    std::optional<Pass> passed;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    ClosestPoint found;
  };
  Seen& seen(std::size_t index);
  /// Adds the move from the last queried centre to `centre` to path_.
  void walk_to(const Eigen::Vector3d& centre);
  /// Where surface `index` stands now.
  Stance stance(const TrimmedSurface& surface, std::size_t index) const;
  /// How far the surface may have moved since it stood at `then` [mm];
  /// infinite when its control points changed and no motion was told for it
  /// since.
  double surface_moved(const TrimmedSurface& surface, std::size_t index, const Stance& then) const;
  /// The side of the surface where it was last passed by (the sign there,
  /// read now), or 0 when the surface may have reached that centre since or
  /// the sign there is noise.
  int side_where_passed(const TrimmedSurface& surface, std::size_t index, const Pass& pass);
  /// Lower and upper bounds on the distance of the surface's material from
  /// the centre now (after walk_to) [mm]; -inf and +inf when not seen.
  struct DistanceBounds {
    double at_least = -std::numeric_limits<double>::infinity();
    double at_most = std::numeric_limits<double>::infinity();
  };
  DistanceBounds distance_bounds(const TrimmedSurface& surface, std::size_t index);
  /// The closest point to `centre`: the one seen when the centre and the
  /// surface are where they were then, else a query (recorded when `record`).
  ClosestPoint closest(const TrimmedSurface& surface, std::size_t index,
                       const Eigen::Vector3d& centre, bool record);

  double radius_;
  double eps_;
  std::vector<int> sides_;      // +1 / -1 along / against each surface's normal, 0 unknown
  std::vector<double> motion_;  // see set_surface_motion
  std::vector<Seen> seen_;
  /// Length of the polyline through every centre queried so far [mm].
  double path_ = 0.0;
  bool walked_ = false;  // last_centre_ is set
  Eigen::Vector3d last_centre_ = Eigen::Vector3d::Zero();
  /// Per surface, the sum of the travels set_surface_motion was told [mm].
  std::vector<double> surface_path_;
  std::uint64_t epoch_ = 0;
  long queries_ = 0;
};

}  // namespace argil
