#include "argil/io/model/model.hpp"

namespace argil::io {

Box3 model_box(const Model& model) {
  Box3 box{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  bool first = true;
  for (const FaceRecord& face : model.faces) {
    if (face.surface.control_points.rows() == 0) continue;
    const Box3 face_box = control_point_box(face.surface);
    box.min = first ? face_box.min : box.min.cwiseMin(face_box.min);
    box.max = first ? face_box.max : box.max.cwiseMax(face_box.max);
    first = false;
  }
  return box;
}

}  // namespace argil::io
