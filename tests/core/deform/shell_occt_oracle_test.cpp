// The shell matrices against OpenCASCADE (docs/deformation.md, Testing): the
// face's area from BRepGProp, and degree elevation (Geom_BSplineSurface::
// IncreaseDegree) of the face and of a displacement field, whose shell
// energies must not change.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "argil/core.hpp"
#include "support/occt_surface.hpp"
#include "support/random_surface.hpp"
#include "support/test_plates.hpp"

namespace {

using argil::BSplineSurface;

/// `s` raised by one degree in both directions by OpenCASCADE (the same surface).
BSplineSurface elevated(const BSplineSurface& s) {
  Handle(Geom_BSplineSurface) g = argil::test::to_occt(s);
  g->IncreaseDegree(s.degree[0] + 1, s.degree[1] + 1);
  return argil::test::from_occt(g);
}

/// The flat plate with an affine parametrisation: exact Gauss quadrature.
BSplineSurface affine_plate() {
  BSplineSurface plate;
  plate.degree = {3, 2};
  plate.knots = {argil::test::piece_knots(3, 3, 1), argil::test::piece_knots(2, 4, 1)};
  const Eigen::VectorXd gu = argil::greville_abscissae(3, plate.knots[0]);
  const Eigen::VectorXd gv = argil::greville_abscissae(2, plate.knots[1]);
  plate.control_points.resize(gu.size() * gv.size(), 3);
  for (Eigen::Index i = 0; i < gu.size(); ++i)
    for (Eigen::Index j = 0; j < gv.size(); ++j)
      plate.control_points.row(plate.pole_index(static_cast<int>(i), static_cast<int>(j)))
          << 30.0 * gu[i] + 5.0 * gv[j],
          12.0 * gv[j], 0.0;
  return plate;
}

/// Energies of a random field and of the same field degree-elevated agree to `tolerance`.
void check_elevation(const BSplineSurface& s, double tolerance) {
  const BSplineSurface e = elevated(s);
  const argil::ShellMatrices a = argil::shell_matrices(s);
  const argil::ShellMatrices b = argil::shell_matrices(e);
  CAPTURE(a.total_area, b.total_area);
  CHECK(std::abs(b.total_area - a.total_area) <= tolerance * a.total_area);
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    BSplineSurface field = s;  // same weights and knots, the displacement as control points
    for (Eigen::Index i = 0; i < field.control_points.size(); ++i)
      field.control_points.data()[i] = normal(rng);
    const Eigen::MatrixXd dp = field.control_points;
    const Eigen::MatrixXd dq = elevated(field).control_points;
    REQUIRE(dq.rows() == b.area.size());
    const double bend_a = a.bending.quadratic_form(dp), bend_b = b.bending.quadratic_form(dq);
    const double mem_a = a.membrane.quadratic_form(dp), mem_b = b.membrane.quadratic_form(dq);
    CAPTURE(trial, bend_a, bend_b, mem_a, mem_b);
    CHECK(std::abs(bend_b - bend_a) <= tolerance * bend_a);
    CHECK(std::abs(mem_b - mem_a) <= tolerance * mem_a);
  }
}

}  // namespace

TEST_CASE("shell areas agree with OpenCASCADE's BRepGProp", "[deformation][shell][occt]") {
  for (const auto& [name, s] :
       {std::pair{"affine flat plate", affine_plate()},
        std::pair{"asymmetric rational", argil::test::asymmetric_surface()},
        std::pair{"asymmetric polynomial", argil::test::asymmetric_surface(false)}}) {
    CAPTURE(name);
    const TopoDS_Face face =
        BRepBuilderAPI_MakeFace(argil::test::to_occt(s), Precision::Confusion());
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face, props, 1e-12);
    const argil::ShellMatrices m = argil::shell_matrices(s);
    CAPTURE(props.Mass(), m.total_area);
    // As against dense sampling (shell_matrices_test.cpp): the quadrature of a
    // curved face's area element within 1e-5.
    CHECK(std::abs(m.total_area - props.Mass()) <= 1e-5 * props.Mass());
  }
}

TEST_CASE("degree elevation leaves the shell energies of a field alone: affine flat plate",
          "[deformation][shell][occt]") {
  check_elevation(affine_plate(), 1e-9);
}

TEST_CASE(
    "degree elevation leaves the shell energies of a field alone: curved rational "
    "asymmetric surface",
    "[deformation][shell][occt]") {
  // Quadrature error on a rational face (quotient integrands, 2p + 2 Gauss
  // points): measured up to 6e-4 relative for bending.
  check_elevation(argil::test::asymmetric_surface(), 1e-3);
}
