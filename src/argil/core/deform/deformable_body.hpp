#pragma once
// A deformable surface (docs/deformation.md): the control net is the state
// (dynamic NURBS). Mass, membrane, bending, joint and foundation terms are
// integrated once over the rest surface (shell_matrices.hpp); loads enter
// through the basis values at the contact; an implicit Euler step moves the
// control points, plasticity moves their rest positions, and the hierarchy
// sees the new control points. Nothing is fitted or inverted on the tick path.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "argil/core/deform/contact_response.hpp"
#include "argil/core/deform/join_rows.hpp"
#include "argil/core/deform/material.hpp"
#include "argil/core/deform/pole_stencil_matrix.hpp"
#include "argil/core/deform/pole_window.hpp"
#include "argil/core/deform/shell_matrices.hpp"
#include "argil/core/geometry/bspline_surface.hpp"
#include "argil/core/hierarchy/surface_hierarchy.hpp"
#include "argil/core/linalg/banded_cholesky.hpp"

namespace argil {

/// Largest time step a body accepts [s].
inline constexpr double kMaxTimeStep = 0.1;
/// The haptic step [s]: create() checks a material's conditioning at it.
inline constexpr double kHapticStep = 1e-3;

/// What a step would do before a load whose size depends on it is known: the
/// motion of the loaded point without that load, and its compliance.
struct LoadPreview {
  /// g . (P_next - P) over the step without the pattern load [mm], g the pattern.
  Eigen::Vector3d free_motion = Eigen::Vector3d::Zero();
  /// h^2 g^T A^-1 g [mm/N]: how far the loaded point moves this step per newton
  /// applied through the pattern (the same in every direction).
  double compliance = 0.0;
};

/// Multiply-adds of factorisation a step spends on a window being prepared
/// (about 0.1 ms): a new window is factorised over several steps, never in one.
inline constexpr double kWindowFactorWorkPerStep = 2e5;
/// The same while the active window still holds the loads (it moves ahead of
/// them): a quarter, so a growing window's steps stay near the median step.
inline constexpr double kWindowGrowthWorkPerStep = 5e4;

/// A window with no load left is dropped (the whole net solved again) once
/// none of its poles moved this far [mm] over a step.
inline constexpr double kWindowRestMotion = 1e-3;

/// Multiply-adds up to which create() factorises the whole net (about 50 ms);
/// larger nets are solved in local windows only.
inline constexpr double kCreateFactorWork = 1e8;

/// Plastic flow keeps every control point's stretch |P - P_rest| within this
/// many yields (the surface's own stretch is held at the yield).
inline constexpr double kPlasticStretchCap = 3.0;

/// How a body's poles move over one step under extra control-point forces
/// (DeformableBody::step_response): one row per pole in `poles`.
struct StepResponse {
  std::vector<Eigen::Index> poles;
  RowMajorMatrix motion;  // [mm] per unit of each force column
};

/// State P (control points), V (their velocities), P_rest (rest control
/// points) and a material. One step, with h = dt, K the elastic stiffness
/// (shell matrices times the material's stiffnesses), C = beta K and M' =
/// 1e-3 M the lumped mass:
///   (M' + h C + h^2 K) V+ = M' V + h (f - K (P - P_rest)),  P+ = P + h V+
/// (implicit Euler, unconditionally stable for M' > 0, K, C >= 0; without
/// external force the energy 0.5 V^T M' V + 0.5 U^T K U never increases).
/// Held control points keep P = P_rest and V = 0; the pole on a G1 join moves
/// with its row's neighbours (join_rows.hpp), so the join stays G1. After the step, plasticity
/// moves P_rest where the surface's stretch over a control point's cell
/// around its Greville point exceeds the yield (that point's rest follows it
/// by the excess fraction) and where a control point is farther than kPlasticStretchCap
/// yields from its rest; the rows across a C0 join flow together, and the
/// flow is cut short where it would raise the stored energy.
/// The weights of a rational face do not change.
class DeformableBody {
 public:
  /// Validates the surface and the material and integrates the shell
  /// matrices. Every valid material is accepted on every valid face: where the
  /// material is too stiff for its mass at kHapticStep, the elastic terms are
  /// capped (elastic_scale()); nothing checks an absolute mass.
  static Result<DeformableBody> create(const BSplineSurface& surface, const Material& material,
                                       const BoundaryConditions& conditions, OperatorCache& cache);

  /// Current surface.
  const BSplineSurface& surface() const { return hierarchy_.surface(); }
  const SurfaceHierarchy& hierarchy() const { return hierarchy_; }
  /// Largest node count of the lazy hierarchy (SurfaceHierarchy::set_node_budget).
  void set_node_budget(std::size_t nodes) { hierarchy_.set_node_budget(nodes); }
  const SurfaceOperators& operators() const { return hierarchy_.operators(); }
  const Material& material() const { return material_; }
  /// Control points [mm], row i * n_v + j (the state).
  const ControlNet& control_points() const { return surface().control_points; }
  /// Rest control points [mm]; they move only by plastic flow.
  const ControlNet& rest_control_points() const { return rest_; }
  const ControlNet& velocities() const { return velocities_; }  // [mm/s]
  /// Lumped masses [kg]: rho h integral R_i dA, at least 1e-3 of the mean
  /// (a control point on a collapsed edge has no area of its own).
  const Eigen::VectorXd& masses() const { return masses_; }
  /// One flag per control point: held by the boundary conditions.
  const std::vector<char>& fixed() const { return fixed_; }
  const ShellMatrices& shell() const { return shell_; }
  /// K [N/mm], the same for x, y and z.
  const PoleStencilMatrix& stiffness() const { return stiffness_; }
  /// The factor (<= 1) the membrane, bending and joint terms were scaled by so
  /// the step stays resolved at kHapticStep (MaterialRange::min_inertia_ratio);
  /// 1 for every face stiff enough to matter at 1 kHz.
  double elastic_scale() const { return elastic_scale_; }
  /// 0.5 sum m' |v|^2 [mJ = N mm].
  double kinetic_energy() const;
  /// 0.5 sum_c U_c^T K U_c with U = P - P_rest [mJ].
  double potential_energy() const;

  /// One step of dt [s] (0 < dt <= kMaxTimeStep) with explicit control-point
  /// forces (n x 3 [N]; empty for none). Fails only on an invalid dt or a
  /// matrix that is not positive definite to working precision.
  Status step(double dt, const ControlNet& forces = {});

  /// The first half of a step with a load F spread by `pattern` (one weight
  /// per control point, e.g. contact_load_pattern(); empty for none) whose size
  /// is decided after seeing the preview. Must be followed by finish_step.
  Result<LoadPreview> begin_step(double dt, const ControlNet& forces,
                                 const Eigen::VectorXd& pattern);
  /// The same with the pattern's non-zero entries (contact_pole_weights,
  /// footprint_pole_weights): no pass over the whole net.
  Result<LoadPreview> begin_step(double dt, const ControlNet& forces, const PoleWeights& pattern);
  /// Completes the step with pattern force F [N] (control-point force g_i F).
  void finish_step(const Eigen::Vector3d& pattern_force);

  /// Largest distance a control point moved over the last step [mm] (0 before
  /// the first): the surface moved no farther (convex hull, fixed weights).
  double last_step_motion() const;
  /// How far any point of the surface can have moved since the last step
  /// began [mm]: the step's largest pole move plus the largest sum of one
  /// pole's joint corrections since (a seam weld puts a pair at its mean,
  /// which stays within that). last_step_motion() takes the larger of the two
  /// instead: a measure of activity for settling, not a bound.
  double last_step_travel() const;
  /// Whether the body is at rest to within `distance` [mm]: every control
  /// point within `distance` of its rest position (the unloaded equilibrium:
  /// K is positive definite on the free points whenever the foundation or a
  /// held point anchors the face) and moved less than `distance` over the last
  /// step.
  bool settled(double distance) const;
  /// Sets every velocity to zero: a body put to sleep wakes from a state that
  /// does not depend on how long it slept.
  /// It also marks the body resting (until the next load it does not step: it
  /// stays where it is, within the settling distance of its rest) and, if it
  /// was loaded since it last rested, drops its local window.
  void halt();

  /// Prepares the window a load at `uv` (a parameter point, e.g. the closest
  /// point to a tool coming near) would need: factorised a few rows per step
  /// from the next step on, so the first loaded step does not factorise it at
  /// once. Does nothing with a window active or being prepared, or without
  /// local solves. The solution does not depend on it beyond which poles the
  /// window holds.
  void anticipate(const Eigen::Vector2d& uv, double dt);
  /// Spends one step's share of work on the window being prepared, without
  /// stepping (a sleeping body near the tool: it prepares as an awake one would).
  Status prepare_window(double dt);
  /// At rest since create() or halt(), with no load since.
  bool resting() const { return resting_; }
  /// A window is active or being factorised.
  bool window_planned() const { return local_.has_value() || pending_.has_value(); }
  /// Whether a step under the load anticipate() last prepared for can move
  /// any of `poles`: the window being factorised (else the active one) holds
  /// one, or that load needs the whole net, or the body moves with no window
  /// (it steps its whole net), or local solves are off. False for a body at
  /// rest with nothing anticipated.
  bool step_may_move_any(const std::vector<Eigen::Index>& poles) const;

  /// Adds a joint's correction (edge_joint.hpp) to some poles: P += dp, V +=
  /// dv, held poles left alone. The body is no longer resting, and the next
  /// step solves for those poles as for loaded ones; last_step_motion()
  /// counts the move.
  void displace(const std::vector<Eigen::Index>& poles, const ControlNet& dp, const ControlNet& dv);
  /// Makes each pair of poles equal to the bit, points and velocities, at
  /// their mean (at the held one's place when one is held): a closed face's
  /// seam rows kept exactly together. Like displace() it marks them loaded for
  /// the next step, but last_step_motion() does not count the move. Returns
  /// whether anything moved.
  bool weld(const std::vector<std::pair<Eigen::Index, Eigen::Index>>& pairs);

  /// How much further the poles move over one step of dt [s] when control-point
  /// forces F are added to the step's load, the rest unchanged: h^2 S^-1 F,
  /// S = M' + (h beta + h^2) K the step's matrix, over the window of the
  /// poles in `poles` grown by the influence margin (poles outside it held,
  /// as a local step holds them). `forces` has a row per entry of `poles` and
  /// any number of columns (K acts alike on x, y and z: each column is one
  /// coordinate of one force field). Held poles do not move. Factorises the
  /// window once: a joint calls it when it is built, not every step.
  Result<StepResponse> step_response(const std::vector<Eigen::Index>& poles,
                                     const RowMajorMatrix& forces, double dt) const;

  /// Local solves (on by default; docs/deformation.md, Local solves): a step
  /// whose loads all lie inside the active window solves only the window's
  /// poles and holds the rest where they are (V = 0). Off: every step solves
  /// the whole net.
  void set_local_solves(bool on);
  bool local_solves() const { return local_solves_; }
  /// The poles the last step solved for: the whole net, the active window, or
  /// none (empty) when the body was exactly at rest with no load and no window.
  const PoleWindow& solved_window() const { return stepped_window_; }
  /// Box of the control points the last step solved for (empty when none):
  /// the rest did not move.
  Box3 solved_box() const;
  /// Whether a larger window is being factorised (a few rows per step).
  bool window_growing() const { return pending_.has_value(); }
  /// The window a load's poles need around them (the influence margin) and
  /// the one a new window gets (that plus room for the tool to move), in poles
  /// along u and v.
  int window_margin(int direction) const { return margin_[static_cast<std::size_t>(direction)]; }
  int window_slack(int direction) const { return slack_[static_cast<std::size_t>(direction)]; }
  /// How far a load's dent spreads [mm]: the larger of the bending length
  /// (D / k_a)^(1/4) and the membrane's sqrt(A / k_a) (+inf without a
  /// foundation: the whole face carries the load). A window reaches three.
  double influence_length() const { return influence_length_; }

 private:
  /// The largest distance a pole moved in the last step itself [mm].
  double step_pole_motion() const;
  /// Whether every free pole the last step solved outside `kept` is at rest:
  /// it moved less than kWindowRestMotion in the step, and its elastic force
  /// would move it less than that on its own (its row of K (P - P_rest) over
  /// its diagonal). Poles the step did not solve have no velocity.
  bool rests_outside(const PoleWindow& kept) const;
  /// The unknowns of one factorisation: a window's poles in solve order
  /// (row-major in the direction that gives the narrower band), its tied join
  /// rows, and its factor, computed a few rows at a time for a local window.
  struct SolveRegion {
    PoleWindow window;
    std::vector<Eigen::Index> order;  // the pole of each unknown
    std::vector<int> rank;            // the unknown of each pole; -1 outside the window
    std::vector<JoinRow> ties;        // the tied join rows inside the window
    int bandwidth = 0;
    double dt = 0.0;
    /// Factorised up to factored_rows; filled as far (whole with ties).
    SymmetricBandMatrix matrix;
    int factored_rows = 0;
    std::optional<BandedCholesky> solver;  // once every row is factorised
    /// Opened on a body at rest: the poles outside stay at rest, so the
    /// window is kept when its loads end (the body settles and sleeps in it).
    bool outside_at_rest = false;
  };

  DeformableBody(SurfaceHierarchy hierarchy, const Material& material);
  /// The window's unknowns, solve order and ties (no matrix yet). The window
  /// must hold every tied join row it touches (tie_closed).
  SolveRegion region(const PoleWindow& window) const;
  /// The window grown until every tied join row is wholly in or out of it.
  PoleWindow tie_closed(PoleWindow window) const;
  Status factorize(double dt);
  /// Picks the region this step solves (the whole net or the local window),
  /// grows the window ahead of the loads and spends this step's share of the
  /// pending window's factorisation.
  Status plan_region(double dt, const ControlNet& forces, const PoleWeights* pattern);
  /// This step's share of the pending window's factorisation (all of it when
  /// `loads` lie outside the active window and the step cannot wait).
  Status advance_pending(double dt, const PoleWindow& loads);
  /// Drops the active window, keeping it as kept_ when it is factorised.
  void keep_local();
  /// Makes kept_ the active window (keeping the one it replaces) for loads
  /// needing `needed` when it holds them at dt and is at most twice the size
  /// of `target`, the window they would get; true when it did.
  bool take_kept(const PoleWindow& needed, const PoleWindow& target, double dt);
  /// begin_step with a pattern or without one (null).
  Result<LoadPreview> start_step(double dt, const ControlNet& forces, const PoleWeights* pattern);
  /// Moves the rest control points so that no stretch exceeds the yield,
  /// looking only at the poles `window` moved and those their stretch reaches.
  void plastic_flow(const ControlNet& points, const PoleWindow& window);
  /// The implicit matrix M' + (h beta + h^2) K over a region's unknowns in
  /// band form; poles outside the region are held (V = 0).
  SymmetricBandMatrix step_matrix(const SolveRegion& region, double dt) const;
  /// Rows [begin, end) of that matrix, ties not applied: a pole's row holds
  /// only its own couplings, so rows fill one batch at a time.
  void fill_step_rows(const SolveRegion& region, double dt, int begin, int end,
                      SymmetricBandMatrix& a) const;

  SurfaceHierarchy hierarchy_;
  Material material_;
  ShellMatrices shell_;
  PoleStencilMatrix stiffness_;
  double elastic_scale_ = 1.0;
  std::vector<char> fixed_;
  Eigen::VectorXd masses_;
  ControlNet rest_, velocities_;
  /// The control points (the hierarchy's copy is updated from it window by window).
  ControlNet points_;
  /// At rest with no load since create() or halt(): a step without load is skipped.
  bool resting_ = true;
  /// Where plastic flow measures the surface's stretch for one control point:
  /// a 3 x 3 grid over its cell (from halfway to the previous Greville point
  /// to halfway to the next, each way). The samples are tensor products, so
  /// each direction keeps, per pole, the basis at its three abscissae (first
  /// pole, degree + 1 values) and the poles non-zero at any of them.
  struct YieldBasis {
    int degree = 0;
    std::vector<int> first;      // 3 per pole
    std::vector<double> values;  // 3 (degree + 1) per pole
    std::vector<std::vector<int>> poles;
  };
  std::array<YieldBasis, 2> yield_basis_;
  /// The stretch of the surface at sample su (along u: 3 per pole) x sv.
  Eigen::RowVector3d sample_stretch(int su, int sv) const;
  /// The largest stretch of the surface over the 3 x 3 samples of pole
  /// (ci, cj)'s yield cell.
  double largest_cell_stretch(int ci, int cj);
  /// How many poles away along u and v a yield cell's poles reach.
  std::array<int, 2> yield_reach_{0, 0};
  /// The rows of poles across the face's C0 knot lines (join_rows.hpp): the
  /// step ties the G1 ones; plastic flow keeps every row's proportions.
  std::vector<JoinRow> join_rows_;
  /// The whole net, factorised at create() and at each new dt.
  SolveRegion full_;
  /// The active local window and a larger one being factorised.
  std::optional<SolveRegion> local_, pending_;
  /// The last factorised window dropped (its loads came to rest, or the body
  /// slept): a load that comes back inside it steps in it at once instead of
  /// stepping the whole net while a new window is factorised (take_kept).
  std::optional<SolveRegion> kept_;
  bool local_solves_ = true;
  /// The last anticipate() found the load's window to be the whole net.
  bool anticipated_whole_ = false;
  /// Influence margin and growth slack of a window, in poles along u and v.
  std::array<int, 2> margin_{0, 0}, slack_{0, 0};
  double influence_length_ = 0.0;  // see influence_length()
  PoleWindow stepped_window_;
  /// Poles a joint moved since the last step, and how far the farthest went [mm].
  PoleWindow displaced_;
  double displaced_motion_ = 0.0;
  /// Per pole, the sum of the joints' moves since the last step (nonzero
  /// only in displaced_), and the largest sum [mm].
  std::vector<double> displaced_sum_;
  double displaced_travel_ = 0.0;
  bool step_local_ = false;  // this step solves local_ (else full_)
  bool step_idle_ = false;   // this step changes nothing: exactly at rest, no load
  // Scratch over the whole net; a local step touches only rows near its window.
  Eigen::MatrixXd stretch_, force_, flow_;
  Eigen::VectorXd stretch_norm_;
  std::vector<Eigen::Index> flowing_poles_;  // plastic flow's non-zero rows
  /// largest_cell_stretch's partial sums: 3 per row of poles the cell reads.
  std::vector<Eigen::RowVector3d> cell_rows_;
  // Between begin_step and finish_step, in solve order.
  RowMajorMatrix work_;
  /// The last pattern scattered over the net (zero elsewhere).
  Eigen::VectorXd pattern_;
  PoleWeights pattern_weights_;
  double step_dt_ = 0.0;
  bool has_pattern_ = false;
};

}  // namespace argil
