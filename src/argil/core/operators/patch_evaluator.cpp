#include "argil/core/operators/patch_evaluator.hpp"

#include <algorithm>
#include <cassert>

#include "argil/core/geometry/basis.hpp"

namespace argil {

PatchEvaluator::PatchEvaluator(const BSplineSurface& surface, const SurfaceOperators& ops)
    : surface_(surface), ops_(ops) {}

PatchEvaluator::Place PatchEvaluator::place(Direction d, double t, int last_element) const {
  const Eigen::VectorXd& knots = surface_.knots_in(d);
  const std::vector<int>& spans = ops_.in(d).extraction().spans;
  int element = last_element;
  int span = spans[static_cast<std::size_t>(element)];
  // Inside the last element's half-open span, find_span gives that span too
  // (it is non-empty); elsewhere, and at the domain's end, ask it.
  if (!(knots[span] <= t && t < knots[span + 1])) {
    span = find_span(surface_.degree_in(d), knots, surface_.count(d), t);
    element = static_cast<int>(std::lower_bound(spans.begin(), spans.end(), span) - spans.begin());
    assert(spans[static_cast<std::size_t>(element)] == span);
  }
  const double length = knots[span + 1] - knots[span];
  return {element, (t - knots[span]) / length, 1.0 / length};
}

const BezierPatch& PatchEvaluator::patch(int element_u, int element_v) {
  for (const Slot& slot : slots_)
    if (slot.element_u == element_u && slot.element_v == element_v) return slot.patch;
  Slot& slot = slots_[static_cast<std::size_t>(next_slot_)];
  next_slot_ = (next_slot_ + 1) % kSlots;
  slot.element_u = element_u;
  slot.element_v = element_v;
  slot.patch = bezier_patch(surface_, ops_, element_u, element_v);
  return slot.patch;
}

SurfaceDerivatives PatchEvaluator::evaluate(double u, double v, int order) {
  u = std::clamp(u, surface_.domain_start(Direction::u), surface_.domain_end(Direction::u));
  v = std::clamp(v, surface_.domain_start(Direction::v), surface_.domain_end(Direction::v));
  if (order > 1) return evaluate_derivatives(surface_, u, v, order);
  const Place pu = place(Direction::u, u, last_u_);
  const Place pv = place(Direction::v, v, last_v_);
  last_u_ = pu.element;
  last_v_ = pv.element;
  // The patch's derivatives are per unit of its local parameters.
  SurfaceDerivatives d = evaluate_derivatives(patch(pu.element, pv.element), pu.s, pv.s, order);
  d.du *= pu.inverse_length;
  d.dv *= pv.inverse_length;
  return d;
}

}  // namespace argil
