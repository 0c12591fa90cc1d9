#pragma once
// Grouping of leaf contacts into connected contact regions, shared by every
// collision query. Private to the collision module.

#include <limits>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/param_rect.hpp"

namespace argil {

/// A contact found on one leaf, with the leaf's parameter rectangle on
/// surface a (the side regions are grouped on).
struct LeafContact {
  Contact contact;
  ParamRect rect;
  /// A lower bound of the tool function on the leaf (-inf when unknown): how
  /// deep anything on the leaf can be, for refining region heads.
  double value_lower_bound = -std::numeric_limits<double>::infinity();
  /// The hierarchy node of the leaf (-1 when none): its Bezier patch
  /// evaluates the leaf without a knot search.
  int node = -1;
};

/// Contacts grouped into regions: ids in [0, region_count).
struct ContactRegions {
  std::vector<Contact> contacts;
  int region_count = 0;
};

/// Groups leaf contacts whose rectangles touch (closed rectangles: sharing an
/// edge or a corner counts) into regions, numbers regions by their deepest
/// contact (deepest first; ties keep first appearance), orders each region
/// deepest first (ties by world point, then parameters: the same order on a
/// surface whose u and v are swapped), and keeps at most max_contacts of
/// them: every region's deepest contact first, then the rest in order, each
/// contact once (the same point and depth, up to rounding, found by two
/// leaves that share an edge or a corner, is one contact). Reorders `leaves`
/// (callers refine region heads from the reordered leaves afterwards).
ContactRegions group_regions(std::vector<LeafContact>& leaves, int max_contacts);

/// The ordering and trimming step of group_regions on contacts that already
/// carry region ids in [0, region_count): for queries that add contacts to
/// regions after grouping (surface-pair penetration).
void rank_regions(std::vector<Contact>& contacts, int region_count, int max_contacts);

}  // namespace argil
