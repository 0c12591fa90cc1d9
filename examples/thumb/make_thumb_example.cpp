// Makes the thumb example's inputs from the bearing (tests/data/bearing.iges):
//  face.json   face 161, a trimmed conical band about 35 x 5 micrometres, refined
//              exactly by knot insertion (29 x 9 poles) so a tool can shape it locally;
//  thumb.json  the "thumb": a bicubic pad 6 x 3 micrometres whose control net is 1.5
//              deep (the surface's lowest point is 0.9 micrometres below the tool
//              frame's origin on -z);
//  drag.json   a script: approach along the face normal, engage, press, drag the
//              thumb along u from 0.22 to 0.45 following the face (position and
//              orientation: the pad's -z along the inward normal, x along S_u),
//              from u = 0.22 (inside the trim) to 0.45 so the far end is out of reach,
//              release and retreat.
// The committed files are this program's output; a test regenerates and compares.
//
// usage: make_thumb_example BEARING_IGES OUT_FOLDER
#include <cmath>
#include <cstdio>
#include <string>

#include "argil/core/geometry/evaluate.hpp"
#include "argil/core/geometry/knot_insertion.hpp"
#include "argil/io/files/model_files.hpp"
#include "argil/io/json/json_format.hpp"
#include "argil/sculpt/script/script.hpp"

namespace {

constexpr int kFace = 161;
constexpr double kPadHalfX = 3e-3, kPadHalfY = 1.5e-3, kPadDepth = 1.5e-3;  // [mm]
constexpr double kApproach = 6e-3;                                          // [mm] above the face
constexpr double kPress = 1.2e-3;  // how far the device goes below the touching pose [mm]

int fail(const std::string& message) {
  std::fprintf(stderr, "make_thumb_example: %s\n", message.c_str());
  return 1;
}

/// Tool frame at (u, v) of the face: origin `height` above the surface along
/// the outward normal, z = outward normal, x = S_u projected on the tangent plane.
argil::sculpt::Keyframe frame_at(const argil::BSplineSurface& s, double u, double v, double height,
                                 double t) {
  const argil::SurfaceDerivatives d = argil::evaluate_derivatives(s, u, v, 1);
  Eigen::Vector3d n = argil::unit_normal(d);
  // Outward: away from the bearing's axis (z) and up, where the thumb comes from.
  if (n.dot(Eigen::Vector3d(d.point.x(), d.point.y(), 0.0)) < 0) n = -n;
  const Eigen::Vector3d x = (d.du - d.du.dot(n) * n).normalized();
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = n.cross(x);
  r.col(2) = n;
  argil::sculpt::Keyframe f;
  f.t = t;
  f.X_WD.p = d.point + height * n;
  f.X_WD.R = Eigen::Quaterniond(r).normalized();
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return fail("usage: make_thumb_example BEARING_IGES OUT_FOLDER");
  const std::filesystem::path out = argv[2];
  const argil::Result<argil::io::Model> bearing = argil::io::read_model(argv[1]);
  if (!bearing.ok()) return fail(bearing.status().message);
  if (bearing.value().faces.size() <= kFace) return fail("the bearing has too few faces");

  // The face, refined without changing its shape.
  argil::io::Model face_model;
  face_model.metadata["description"] =
      "face 161 (IGES D-entry " + bearing.value().faces[kFace].source_id +
      ") of tests/data/bearing.iges, refined by knot insertion at u = k/24, v = k/6 "
      "(made by examples/thumb/make_thumb_example.cpp)";
  argil::io::FaceRecord face = bearing.value().faces[kFace];
  for (int k = 1; k < 24; ++k) {
    auto refined = argil::insert_knot(face.surface, argil::Direction::u, k / 24.0);
    if (!refined.ok()) return fail(refined.status().message);
    face.surface = std::move(refined).value();
  }
  for (int k = 1; k < 6; ++k) {
    auto refined = argil::insert_knot(face.surface, argil::Direction::v, k / 6.0);
    if (!refined.ok()) return fail(refined.status().message);
    face.surface = std::move(refined).value();
  }
  face_model.faces.push_back(face);
  if (auto s = argil::io::write_json(face_model, out / "face.json"); !s.ok())
    return fail(s.message);

  // The thumb pad: z = -depth (1 - (x/a)^2) (1 - (y/b)^2) sampled on 5 x 5 poles.
  argil::io::Model thumb;
  thumb.metadata["description"] =
      "thumb pad, bicubic, 6 x 3 x 1.5 micrometres, lowest point on -z of the tool frame "
      "(made by examples/thumb/make_thumb_example.cpp)";
  argil::io::FaceRecord pad;
  pad.name = "thumb";
  pad.surface.degree = {3, 3};
  Eigen::VectorXd knots(9);
  knots << 0, 0, 0, 0, 0.5, 1, 1, 1, 1;
  pad.surface.knots = {knots, knots};
  pad.surface.control_points.resize(25, 3);
  const Eigen::VectorXd g = argil::greville_abscissae(3, knots);
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const double x = (2 * g[i] - 1), y = (2 * g[j] - 1);
      pad.surface.control_points.row(i * 5 + j) << kPadHalfX * x, kPadHalfY * y,
          -kPadDepth * (1 - x * x) * (1 - y * y);
    }
  }
  thumb.faces.push_back(pad);
  if (auto s = argil::io::write_json(thumb, out / "thumb.json"); !s.ok()) return fail(s.message);

  // The drag, following the face at v = 0.5.
  argil::sculpt::Script script;
  script.tool = "thumb";
  const argil::BSplineSurface& s = face.surface;
  const double v = 0.5;
  const double u0 = 0.22, u1 = 0.45;
  script.keyframes.push_back(frame_at(s, u0, v, kApproach, 0.0));
  auto engage = frame_at(s, u0, v, kPadDepth + 1e-3, 0.1);
  engage.event = argil::sculpt::ScriptEvent::engage;
  script.keyframes.push_back(engage);
  script.keyframes.push_back(frame_at(s, u0, v, kPadDepth - kPress, 0.25));
  const int legs = 8;
  for (int k = 1; k <= legs; ++k) {
    const double u = u0 + (u1 - u0) * k / legs;
    script.keyframes.push_back(frame_at(s, u, v, kPadDepth - kPress, 0.25 + 0.6 * k / legs));
  }
  auto release = frame_at(s, u1, v, kPadDepth + 1e-3, 0.95);
  release.event = argil::sculpt::ScriptEvent::release;
  script.keyframes.push_back(release);
  script.keyframes.push_back(frame_at(s, u1, v, kApproach, 1.05));
  if (auto st = argil::sculpt::write_script(script, out / "drag.json"); !st.ok()) {
    return fail(st.message);
  }
  std::printf("wrote %s, %s, %s\n", (out / "face.json").c_str(), (out / "thumb.json").c_str(),
              (out / "drag.json").c_str());
  return 0;
}
