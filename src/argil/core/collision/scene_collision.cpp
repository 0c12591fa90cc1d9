#include "argil/core/collision/scene_collision.hpp"

#include <string>

#include "argil/core/collision/implicit_contact.hpp"
#include "argil/core/collision/surface_intersection.hpp"

namespace argil {

namespace {

void add(QueryCounters& sum, const QueryCounters& part) {
  sum.nodes_visited += part.nodes_visited;
  sum.nodes_refreshed += part.nodes_refreshed;
  sum.leaf_pairs += part.leaf_pairs;
  sum.triangle_tests += part.triangle_tests;
}

}  // namespace

Result<SceneCollision> collide_scene(std::span<const SceneBody> bodies,
                                     const CollisionRequest& request) {
  SceneCollision scene;
  std::vector<Box3> boxes;
  boxes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const SceneBody& body = bodies[i];
    if ((body.surface == nullptr) == (body.tool == nullptr)) {
      return Status::error(
          StatusCode::invalid_argument,
          "scene body " + std::to_string(i) + ": needs exactly one of a surface and a tool");
    }
    boxes.push_back(body.surface != nullptr ? body.surface->block(0, &scene.counters).bound.box
                                            : body.tool->bounding_box());
  }

  for (const BodyPair& pair : overlapping_pairs(boxes, request.tolerance)) {
    const SceneBody& a = bodies[static_cast<std::size_t>(pair.a)];
    const SceneBody& b = bodies[static_cast<std::size_t>(pair.b)];
    if ((a.tool != nullptr && b.tool != nullptr) || (a.fixed && b.fixed)) continue;
    ++scene.candidate_pairs;

    BodyPairContacts contacts{pair, pair.a, {}};
    if (a.surface != nullptr && b.surface != nullptr) {
      contacts.result = collide(*a.surface, *b.surface, request);
    } else if (a.surface != nullptr) {
      contacts.result = collide(*a.surface, *b.tool, request);
    } else {
      contacts.surface_side = pair.b;
      contacts.result = collide(*b.surface, *a.tool, request);
    }
    if (!contacts.result.status.ok()) {
      return Status::error(contacts.result.status.code, "scene bodies " + std::to_string(pair.a) +
                                                            " and " + std::to_string(pair.b) +
                                                            ": " + contacts.result.status.message);
    }
    add(scene.counters, contacts.result.counters);
    if (!contacts.result.contacts.empty() || !contacts.result.curves.empty()) {
      scene.pairs.push_back(std::move(contacts));
    }
  }
  return scene;
}

}  // namespace argil
