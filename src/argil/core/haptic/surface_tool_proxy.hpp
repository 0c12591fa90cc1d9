#pragma once
// A god-object proxy for a rigid B-spline tool surface: its hierarchy is
// built once in the tool's frame T and placed by each query's pose X_WT
// (bounds move rigidly, none is rebuilt), advanced towards the device only as far as it
// does not cross any model surface (surface-surface collide), and sliding
// along the surface after it stops.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/pose.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// Contacts of the posed tool with every surface, and whether any crosses.
struct [[nodiscard]] ToolContacts {
  /// Not ok when a collision query failed (its status; the contacts of the
  /// surfaces before it are kept).
  Status status;
  /// Contacts of surface b (its side a), on its material only (set_materials),
  /// regions numbered densely.
  std::vector<std::vector<Contact>> per_surface;
  /// Any crossing, on the material or off it.
  bool crosses = false;
  /// Mean unit normal of the contacts, oriented from the surfaces towards the
  /// tool's control-point centre: of those on the material and of every
  /// crossing, or, where the tool touches neither, of the touches off the
  /// material (held up over a hole by the trimmed-away surface); zero
  /// without any.
  Eigen::Vector3d outward_normal = Eigen::Vector3d::Zero();
};

/// Where a move stopped, and the tool's contacts there. Not ok when a
/// collision query failed: the proxy then stops at the last pose known not to
/// cross (its contacts are not known).
struct [[nodiscard]] ToolMove {
  Status status;
  Pose X_WT;
  ToolContacts contacts;
};

/// Conservative advancement: a move from a pose that crosses nothing goes in
/// substeps of at most max(tool size / 4, 10 eps), each turning the tool
/// little enough that its points' arcs stay within eps / 4 of straight lines,
/// and each tested swept (collide_swept: a crossing anywhere on the substep
/// counts, so a thin tool cannot pass through a surface between two tested
/// poses). A substep that crosses is searched (eps / 2 into it, doubling,
/// then bisection, testing poses) until the last pose that does not cross is
/// within eps / 2 of one that does; one swept query from the substep's start
/// confirms the way there (the search runs again with swept tests when it
/// does not), and the proxy stops there. The rest of the move, less its
/// component into the surface, is tried once more the same way (sliding). So
/// the tool crosses no surface on its way (touching within eps counts as
/// contact, not crossing). A start pose that crosses (the surface moved into
/// the tool) is first pushed out along the contact normal. A null surface is
/// out of the tool's reach this tick: every query skips it (its contacts stay
/// empty). Where the tool lies on a surface, the yes/no crossing test costs
/// about what the full contact query costs (both examine every leaf pair
/// within eps), so the last substep of a move is tested with the contact
/// query, whose contacts the move then returns; that query stops at the
/// first crossing (CollisionRequest::stop_at_crossing), so a substep that
/// ends deep in a surface costs no more than the yes/no test.
class SurfaceToolProxy {
 public:
  /// `tool` in its own frame T; fails when it does not validate, or with
  /// invalid_argument when eps is outside the range its queries allow for it
  /// (check_request): a tool smaller than eps would pass through surfaces.
  /// A contact query keeps at most `max_contacts` (>= 1) per surface.
  static Result<SurfaceToolProxy> create(const BSplineSurface& tool, double eps,
                                         OperatorCache& cache, int max_contacts);

  /// The material of the surfaces the queries name, by their position in the
  /// list (null or empty: the whole surface), until cleared (an empty list).
  /// A surface's contacts are its material's, kept to max_contacts after
  /// those off it are set apart (CollisionRequest::material_a); crossings are
  /// the whole surface's, and so is the normal where no material is touched
  /// (ToolContacts::outward_normal). The caller keeps the regions alive while
  /// they are set.
  void set_materials(std::vector<const TrimRegion*> materials) {
    materials_ = std::move(materials);
  }

  /// Whether the tool at a pose crosses any surface. A failed query counts as
  /// crossing (with its status): the proxy must not move where it cannot
  /// prove it is clear.
  struct [[nodiscard]] Crossing {
    Status status;
    bool crosses = false;
  };
  /// The yes/no test at X_WT: the descent stops at the first crossing leaf pair.
  Crossing crossing(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT);
  /// The same, swept from `swept_from` when given (collide_swept): a
  /// crossing anywhere on the way counts.
  Crossing crossing(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT,
                    const std::optional<Pose>& swept_from);
  /// The tool posed at X_WT, collided with every surface.
  ToolContacts contacts(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT);
  /// The same, for callers that use the contacts only when nothing crosses:
  /// the queries stop at the first crossing (`crosses`, the contacts partial).
  ToolContacts contacts_unless_crossing(const std::vector<const SurfaceHierarchy*>& surfaces,
                                        const Pose& X_WT) {
    return contacts(surfaces, X_WT, std::nullopt, true);
  }
  /// What the caller knows of a move's start pose.
  enum class Start {
    unknown,  // tested first, and pushed out when it crosses
    clear,    // the caller has just found it crosses nothing, at these surfaces
  };
  /// A short slip in one query: the contacts at X_WT_to, swept from
  /// X_WT_from (the descent stops at the first crossing, which `crosses`
  /// reports). For a translation of at most eps only, else nothing: the
  /// swept leaf test looks for leaves that meet during the motion, not for
  /// leaves that already cross at its start, and within eps a start that
  /// crosses (a surface moved into the tool) and an end that does not is a
  /// contact within the tolerance, not a pass-through.
  std::optional<ToolContacts> slip(const std::vector<const SurfaceHierarchy*>& surfaces,
                                   const Pose& X_WT_from, const Pose& X_WT_to);
  /// Moves from X_WT_from towards X_WT_to (rotation interpolated by slerp);
  /// the contacts where it stopped. `at_from`: the contacts at X_WT_from,
  /// when the caller has just queried them there (Start::clear): a move
  /// blocked where it starts (within the stop's resolution, eps / 2) keeps
  /// them instead of querying the same pose again.
  ToolMove move(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT_from,
                const Pose& X_WT_to, Start start = Start::unknown,
                const ToolContacts* at_from = nullptr);
  /// Collision queries run since the proxy was made, one per surface
  /// queried: contact queries (placed or swept) and yes/no crossing tests.
  /// A tick's cost is mostly these (a contact query of a tool lying on a
  /// face costs hundreds of microseconds, a crossing test a fraction).
  struct QueryCounts {
    std::int64_t contacts = 0;
    std::int64_t crossings = 0;
  };
  const QueryCounts& queries() const { return queries_; }
  /// The tool's hierarchy, in its own frame T.
  const SurfaceHierarchy& hierarchy() const { return hierarchy_; }
  /// Diagonal of the tool's control-point box [mm].
  double size() const { return size_; }
  /// Largest distance of a control point from T's origin [mm]: a turn by
  /// angle a about the origin moves no point of the tool farther than reach a.
  double reach() const { return reach_; }
  static constexpr int kMaxBisections = 12;

 private:
  /// The end of one conservative advance.
  struct [[nodiscard]] Advance {
    Status status;
    Pose X_WT;
    bool blocked = false;
    std::optional<ToolContacts> contacts;  // at X_WT, when the advance queried them
  };
  SurfaceToolProxy(const BSplineSurface& tool, SurfaceHierarchy hierarchy, double eps,
                   int max_contacts);
  /// From a pose that does not cross towards `to`: the last pose that does
  /// not. Its last substep is tested with the contact query.
  Advance advance(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& from,
                  const Pose& to);
  /// The last pose from `clear` (no crossing) towards `crossing_pose` that
  /// is reached without crossing, within eps / 2 of one that crosses.
  Advance stop_before(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& clear,
                      const Pose& crossing_pose);
  /// Bisects between `clear` and `crossing_pose`: tests at poses, or swept
  /// from the last pose found clear.
  Advance bisect(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& clear,
                 const Pose& crossing_pose, bool swept);
  /// An advance's end with its contacts: queried now when it has none,
  /// unless it ends at `known_at`, whose contacts `known` are.
  ToolMove arrive(const std::vector<const SurfaceHierarchy*>& surfaces, Advance end,
                  const Pose& known_at, const ToolContacts* known);
  /// A start pose that crosses pushed out along the contact normal.
  ToolMove push_out(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& from,
                    const Pose& to);

  /// The queries at X_WT; with `swept_from`, swept from there (collide_swept):
  /// a crossing anywhere on the way counts.
  /// `partial_when_crossing`: the descent stops at the first crossing, and
  /// the surfaces after it are not queried (the contacts are then
  /// incomplete), for callers that use them only when nothing crosses.
  ToolContacts contacts(const std::vector<const SurfaceHierarchy*>& surfaces, const Pose& X_WT,
                        const std::optional<Pose>& swept_from, bool partial_when_crossing);

  SurfaceHierarchy hierarchy_;  // in T
  Eigen::Vector3d centre_T_;    // mean of the control points, in T
  double eps_;
  double size_;
  double reach_;  // largest distance of a control point from T's origin [mm]
  int max_contacts_;
  std::vector<const TrimRegion*> materials_;
  QueryCounts queries_;
};

}  // namespace argil
