#pragma once
// What every fuzz target asserts about a model a loader accepted: each face
// validates, evaluates to finite points and normals, and survives a JSON round
// trip unchanged. A violation aborts, which libFuzzer reports as a crash.

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/io/json/json_format.hpp"
#include "argil/io/model/model.hpp"
#include "argil/io/model/trim_curve.hpp"

namespace argil::fuzz {

[[noreturn]] inline void fail(const char* what, std::size_t face) {
  std::fprintf(stderr, "argil fuzz check failed: %s (face %zu)\n", what, face);
  std::abort();
}

inline void check_accepted_model(const io::Model& model) {
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const io::FaceRecord& face = model.faces[f];
    if (!io::validate_face(face, f).ok()) fail("accepted face does not validate", f);
    const BSplineSurface& s = face.surface;
    // A 3x3 grid over the domain, ends included.
    for (int i = 0; i <= 2; ++i) {
      for (int j = 0; j <= 2; ++j) {
        const double u = s.domain_start(Direction::u) +
                         0.5 * i * (s.domain_end(Direction::u) - s.domain_start(Direction::u));
        const double v = s.domain_start(Direction::v) +
                         0.5 * j * (s.domain_end(Direction::v) - s.domain_start(Direction::v));
        const SurfaceDerivatives d = evaluate_derivatives(s, u, v, 2);
        const bool finite = d.point.allFinite() && d.du.allFinite() && d.dv.allFinite() &&
                            d.duu.allFinite() && d.duv.allFinite() && d.dvv.allFinite();
        if (!finite) fail("non-finite evaluation of an accepted surface", f);
        if (!unit_normal(d).allFinite()) fail("non-finite normal of an accepted surface", f);
      }
    }
  }
  const Result<std::string> text = io::to_json(model);
  if (!text.ok()) fail("accepted model does not serialise", 0);
  const Result<io::Model> back = io::parse_json(text.value(), "<round trip>");
  if (!back.ok()) fail("serialised model does not parse back", 0);
  if (back.value().faces.size() != model.faces.size()) fail("round trip lost faces", 0);
  for (std::size_t f = 0; f < model.faces.size(); ++f) {
    const BSplineSurface& a = model.faces[f].surface;
    const BSplineSurface& b = back.value().faces[f].surface;
    if (a.degree != b.degree || a.knots[0] != b.knots[0] || a.knots[1] != b.knots[1] ||
        a.control_points != b.control_points || a.weights != b.weights) {
      fail("round trip changed a surface", f);
    }
  }
}

}  // namespace argil::fuzz
