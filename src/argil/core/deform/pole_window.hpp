#pragma once
// A rectangle of control-point indices: the poles a local solve frees
// (docs/deformation.md, Local solves). Rectangular in index space so its
// row-major solve order keeps the band as narrow as the window.

#include <algorithm>

namespace argil {

/// Poles (i, j) with i0 <= i < i1 (along u) and j0 <= j < j1 (along v).
struct PoleWindow {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;

  bool empty() const { return i0 >= i1 || j0 >= j1; }
  int count_u() const { return std::max(0, i1 - i0); }
  int count_v() const { return std::max(0, j1 - j0); }
  bool contains(int i, int j) const { return i >= i0 && i < i1 && j >= j0 && j < j1; }
  /// Whether every pole of `w` lies in this window (an empty `w` always does).
  bool contains(const PoleWindow& w) const {
    return w.empty() || (w.i0 >= i0 && w.i1 <= i1 && w.j0 >= j0 && w.j1 <= j1);
  }
  /// The window grown by mu poles each way along u and mv along v, clipped to
  /// a nu x nv net.
  PoleWindow grown(int mu, int mv, int nu, int nv) const {
    return {std::max(0, i0 - mu), std::min(nu, i1 + mu), std::max(0, j0 - mv),
            std::min(nv, j1 + mv)};
  }
  /// The smallest window holding both.
  PoleWindow united(const PoleWindow& w) const {
    if (w.empty()) return *this;
    if (empty()) return w;
    return {std::min(i0, w.i0), std::max(i1, w.i1), std::min(j0, w.j0), std::max(j1, w.j1)};
  }
  bool operator==(const PoleWindow&) const = default;
};

}  // namespace argil
