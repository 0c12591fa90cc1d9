#pragma once
// A scripted sphere press on one deformable face through the haptic tick
// (HapticWorld), and what the deformation tests check on it: finite state, how
// far the control points went, how deep the dent is and how far the normals
// turned, the force, and the energy after the tool lets go.

#include <Eigen/Core>
#include <string>

#include "argil/core/deform/material.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/haptic/haptic_tick.hpp"

namespace argil::test {

/// The device path: it starts `approach` above the point where the sphere
/// touches S(uv) from the side of S_u x S_v, moves down along the normal in
/// `approach_time` until its centre is `depth` below touching, holds there
/// until `press_time`, then disengages (the tool lets go) for `release_time`.
struct SpherePress {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  double radius = 0.5;          // [mm]
  double depth = 0.3;           // [mm], device below touching
  double approach = 0.1;        // [mm]
  double approach_time = 0.05;  // [s]
  double press_time = 0.6;      // [s], approach included
  double release_time = 0.3;    // [s]
  double dt = 1e-3;             // [s]
  Material material;
  BoundaryConditions conditions;
  double friction = 0.0;
  WorldOptions options;
  /// Normals and displacements are sampled on a grid of this many points per
  /// direction, and checked every `check_every` ticks while pressing.
  int samples = 33;
  int check_every = 100;
};

/// What happened. Angles in radians, lengths in mm, forces in N, energies in mJ.
struct PressOutcome {
  std::string error;   // empty when every tick ran (else the first failing status)
  bool finite = true;  // every control point finite at every tick
  ControlNet rest;     // control points before the press
  ControlNet pressed;  // at the end of the press (the last engaged tick)
  ControlNet final;    // after the release
  /// How deep the device's sphere, at its lowest, reaches into the face at
  /// rest: max(depth, the deepest r - |c - S| over a grid 4x finer than
  /// `samples`). More than depth where the face curves towards the tool.
  double device_penetration = 0.0;
  double max_control_move = 0.0;  // largest |P - P_before| over poles and ticks
  double peak_force = 0.0;        // largest |body force| over the press
  /// Dent at the contact point at the end of the press: how far S(uv) moved
  /// against the normal it was pressed along.
  double dent = 0.0;
  /// At the sample where the normal turned most relative to its bound:
  double normal_turn = 0.0;   // the largest normal turn over the grid
  double displacement = 0.0;  // the largest |S - S_before| over the grid then
  double turn_bound = 0.0;    // normal_turn_bound(displacement, radius)
  /// Largest energy rise of one release tick, relative to the energy at release.
  double energy_rise = 0.0;
  double energy_at_release = 0.0;
  double energy_final = 0.0;
  int contact_ticks = 0;  // ticks with the tool touching
};

/// The bound on how far a sphere of `radius` pressing a dent `displacement`
/// deep can turn the surface normal, a = sqrt(2 r delta - delta^2) the radius
/// of the sphere's footprint at that depth: the larger of atan(2 delta / a)
/// (a dent delta deep is at least a footprint wide, so its mean slope is at
/// most delta / a; a smooth bell's steepest slope is pi/2 of its mean, hence
/// 2) and atan(a / (r - delta)), the slope of the sphere's own imprint at its
/// rim, which a plastic dent that took the sphere's shape reaches (the two
/// agree, sqrt(2 delta / r), for shallow dents); pi/2 once delta reaches r.
double normal_turn_bound(double displacement, double radius);

/// Runs the press. The face is added with `press.conditions` and `press.friction`.
PressOutcome press_sphere(const BSplineSurface& face, const SpherePress& press);

/// Largest angle [rad] between the normals of `before` and `after` at the same
/// parameters over a samples x samples grid; points where either is nearly
/// degenerate (|S_u x S_v| below 1e-3 of the grid's median) are skipped.
/// `largest_move` receives max |S_after - S_before| over the grid [mm].
double largest_normal_turn(const BSplineSurface& before, const BSplineSurface& after, int samples,
                           double* largest_move = nullptr);

}  // namespace argil::test
