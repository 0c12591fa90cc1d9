#pragma once
// Bit-for-bit comparison of surfaces, trim curves and models for the round-trip
// tests: the first difference, printed with 17 digits to paste into a regression
// test, or an empty string when every bit agrees.

#include <bit>
#include <catch2/catch.hpp>
#include <cstdint>
#include <sstream>
#include <string>

#include "argil/io/model/model.hpp"

namespace argil::test {

// First entry whose bits differ, with 17 digits to paste into a regression test;
// empty when all bits agree.
inline std::string bit_difference(const char* what, const Eigen::Ref<const Eigen::ArrayXd>& a,
                                  const Eigen::Ref<const Eigen::ArrayXd>& b) {
  std::ostringstream out;
  out.precision(17);
  if (a.size() != b.size()) {
    out << what << ": sizes " << a.size() << " and " << b.size();
    return out.str();
  }
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (std::bit_cast<std::uint64_t>(a[k]) != std::bit_cast<std::uint64_t>(b[k])) {
      out << what << "[" << k << "]: " << a[k] << " became " << b[k];
      return out.str();
    }
  }
  return "";
}

inline std::string surface_difference(const BSplineSurface& a, const BSplineSurface& b) {
  if (a.degree != b.degree) return "degrees differ";
  for (const std::string& d :
       {bit_difference("knots_u", a.knots[0], b.knots[0]),
        bit_difference("knots_v", a.knots[1], b.knots[1]),
        bit_difference("control_points", a.control_points.reshaped(), b.control_points.reshaped()),
        bit_difference("weights", a.weights, b.weights)}) {
    if (!d.empty()) return d;
  }
  return "";
}

inline std::string curve_difference(const io::TrimCurve& a, const io::TrimCurve& b) {
  if (a.degree != b.degree) return "trim degrees differ";
  for (const std::string& d :
       {bit_difference("trim knots", a.knots, b.knots),
        bit_difference("trim poles", a.points.reshaped(), b.points.reshaped()),
        bit_difference("trim weights", a.weights, b.weights)}) {
    if (!d.empty()) return d;
  }
  return "";
}

inline void require_same_surfaces(const io::Model& written, const io::Model& read) {
  REQUIRE(read.faces.size() == written.faces.size());
  for (std::size_t f = 0; f < written.faces.size(); ++f) {
    INFO("face " << f);
    CHECK(surface_difference(written.faces[f].surface, read.faces[f].surface) == "");
  }
}

}  // namespace argil::test
