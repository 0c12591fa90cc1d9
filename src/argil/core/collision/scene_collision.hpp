#pragma once
// Collision across every body of a scene: the broad phase picks the pairs
// whose bounds come within eps, the narrow phase runs the query that fits
// each pair (surface-surface or surface-tool).

#include <span>
#include <vector>

#include "argil/core/base/status.hpp"
#include "argil/core/collision/broad_phase.hpp"
#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/implicit_tool.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"

namespace argil {

/// One body: a surface (through its hierarchy) or an implicit tool, never
/// both. The scene does not own them.
struct SceneBody {
  const SurfaceHierarchy* surface = nullptr;
  const ImplicitTool* tool = nullptr;
  /// Fixed bodies do not move relative to each other, so fixed-fixed pairs
  /// are never tested (their contacts cannot change).
  bool fixed = false;
};

/// The contacts between bodies a < b. For a surface-tool pair the surface is
/// side a of every contact whatever the body order, and `surface_side` says
/// which body that is.
struct BodyPairContacts {
  BodyPair bodies;
  int surface_side = 0;  // body index of the contacts' side a
  CollisionResult result;
};

struct SceneCollision {
  std::vector<BodyPairContacts> pairs;  // pairs in contact only, sorted by (a, b)
  long candidate_pairs = 0;             // pairs the broad phase passed on
  QueryCounters counters;               // summed over the narrow phase
};

/// Bounds: a surface's box is its element block tree's root box (around
/// every control point, refreshed lazily after deformation); a tool's is
/// ImplicitTool::bounding_box(). Pairs of two tools and pairs of two fixed
/// bodies are skipped. Each candidate pair gets the narrow-phase query with
/// `request` (its tolerance is also the broad-phase margin), so a pair the
/// broad phase drops has no contact within eps.
/// Errors: a body with no surface and no tool, or with both; a request outside
/// the documented range for a candidate pair's surface (check_request()).
Result<SceneCollision> collide_scene(std::span<const SceneBody> bodies,
                                     const CollisionRequest& request = {});

}  // namespace argil
