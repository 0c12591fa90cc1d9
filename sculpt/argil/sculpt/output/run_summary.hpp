#pragma once
// A finished run in a few numbers: how far the sculpted faces moved in and out
// and over how much area, the peak force on the device, the faces refined, how
// many ticks overran the haptic budget, and warnings when the tool touched
// nothing or nothing changed. Printed by `argil sculpt` and written as
// summary.json (docs/formats.md). Pure functions of their arguments.
//
// Displacement sign: at each (u, v) of a face, d = (S_after - S_before) . n,
// with n the unit normal of the face before the run (S_u x S_v, negated for a
// reversed face: the outward normal of a solid's face). Inward (into the
// material, against n) is negative, outward positive.

#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/geometry/trim_region.hpp"
#include "argil/sculpt/output/tick_log.hpp"

namespace argil::sculpt {

/// One face as the run found it and left it.
struct SculptedFace {
  std::string model;  // the scene model's name
  int face = 0;       // face index in the model's file
  /// The surface before and after the run [mm], on the same parameter domain
  /// (the run changes control points only).
  BSplineSurface before{}, after{};
  TrimRegion trim{};      // the face's material region; empty: the whole domain
  bool reversed = false;  // the face's normal is -S_u x S_v
};

/// Where a face moved farthest one way.
struct DisplacementExtreme {
  /// Signed displacement d [mm]: <= 0 for the inward extreme, >= 0 for the
  /// outward one; 0 when no sample moved that way (then model is empty).
  double displacement = 0.0;
  std::string model{};                            // empty: none
  int face = -1;                                  // face index in the model's file
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();   // on the face
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // S_before(u, v) [mm]
};

struct DisplacementOptions {
  /// Cells per knot span in each direction. The move S_after - S_before of a
  /// face (the run keeps knots and weights) is a spline on the face's own
  /// knots, a polynomial of its degree on each span (rational with its
  /// weights): a fixed grid per span resolves it whatever the span's size in mm.
  int cells_per_span = 16;
  /// Rounds of the local search that refines each extreme: each samples a
  /// 9 x 9 grid over a window about the best point so far (at first the
  /// cells about the best corner), then halves the window.
  int refine_rounds = 12;
};

/// How the faces moved.
struct DisplacementSummary {
  DisplacementExtreme inward, outward;
  /// Area [mm^2] of the faces where |d| > eps: sum of the areas |S_u x S_v|
  /// du dv of the grid cells whose centre moved more than eps (midpoint rule,
  /// on the surfaces before the run, material cells only).
  double affected_area = 0.0;
  double area = 0.0;      // [mm^2] of all the faces' material cells
  long long samples = 0;  // cell centres and corners evaluated (the local search excluded)
  /// max(|inward|, |outward|) [mm].
  double max_abs() const { return std::max(-inward.displacement, outward.displacement); }
};

/// Samples each face on a grid of cells (options.cells_per_span per knot
/// span in u and in v): the areas at the cells' centres inside its trims, the
/// displacement there and at the cells' corners (the domain's edges and the
/// knot lines included); then refines the largest inward and outward
/// displacement by local search from the best corner. `eps` [mm] > 0 is the
/// scene's tolerance. Faces whose control points and weights did not change
/// are not evaluated after the run (their displacement is zero; their area is
/// still counted). Precondition: each face's before and after surfaces are
/// valid and share their domain.
DisplacementSummary summarize_displacement(const std::vector<SculptedFace>& faces, double eps,
                                           const DisplacementOptions& options = {});

/// The largest force on the device in a log.
struct PeakForce {
  double force = 0.0;   // |f| [N], after the coupling's clamp
  long long tick = -1;  // -1: an empty log
  double time = 0.0;    // [s]
};

/// The first tick of the log with the largest |f|.
PeakForce peak_force(const TickLog& log);

/// Ticks with at least one contact.
long long contact_ticks(const TickLog& log);

/// Durations [s] strictly longer than `budget` [s] (as TimingSummary::over_budget).
long long count_over_budget(const std::vector<double>& durations, double budget);

struct RunSummaryOptions {
  double tolerance = 0.0;    // eps [mm], > 0
  double haptic_rate = 0.0;  // [Hz], > 0; the budget of a tick is 1 / rate
  DisplacementOptions sampling{};
};

/// A finished run in a few numbers.
struct RunSummary {
  double tolerance = 0.0;  // eps [mm]
  DisplacementSummary displacement;
  PeakForce peak_force;
  long long ticks = 0;             // ticks of the log (replayed ones included)
  long long contact_ticks = 0;     // of them, ticks with a contact
  double budget = 0.0;             // 1 / haptic rate [s]
  long long ticks_timed = 0;       // ticks stepped live (replayed ones are not timed)
  long long over_budget_wall = 0;  // timed ticks whose wall time exceeded the budget
  long long over_budget_cpu = 0;   // timed ticks whose thread CPU time exceeded it
  /// Thread CPU time of the timed ticks with a contact: the ticks that query
  /// and load the bodies (free moves and released ticks cost microseconds and
  /// fill the whole run's median).
  TimingSummary contact_cpu{};
  std::vector<std::string> refinements{};  // the faces refined (refinement_text())
  /// "the tool never touched anything" when no tick had a contact; "nothing
  /// changed ..." when no sampled point moved more than eps.
  std::vector<std::string> warnings{};
};

/// The summary of a run: `faces` the sculpted faces (deformable models), `log`
/// every tick, `wall_s` and `cpu_s` the wall and thread CPU time [s] of each
/// live tick. `refinements` is left empty for the caller.
RunSummary summarize_run(const std::vector<SculptedFace>& faces, const TickLog& log,
                         const std::vector<double>& wall_s, const std::vector<double>& cpu_s,
                         const RunSummaryOptions& options);

/// A few readable lines, without line ends (warnings are not among them):
/// "largest inward displacement: -10.2 mm (hood face 0 at (u, v) = (0.5, 0.5))", ...
std::vector<std::string> summary_lines(const RunSummary& summary);

/// summary.json (format "argil.summary", version 1; docs/formats.md):
/// `scene_name` as given, and `scene_absolute` (when given) the same file's
/// absolute path, which reaches it from any working directory.
std::string summary_json(const RunSummary& summary, const std::string& scene_name,
                         const std::string& scene_absolute = "");

}  // namespace argil::sculpt
