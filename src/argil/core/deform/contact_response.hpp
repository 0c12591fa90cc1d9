#pragma once
// From collision contacts to forces (docs/deformation.md): how a tool force is
// shared among contacts, carried exactly onto the control points, and split by Coulomb
// friction into stick and slip.

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/geometry/bspline_surface.hpp"

namespace argil {

/// Share of a tool force each contact carries, summing to 1: proportional to
/// depth + eps (touching within eps counts, so every reported contact carries
/// some). Empty for no contacts.
std::vector<double> contact_shares(const std::vector<Contact>& contacts, double eps);

/// The non-zero entries of a load pattern: (pole index i * n_v + j, weight),
/// each pole once, in increasing pole order. A contact's pattern touches the
/// (p + 1) x (q + 1) poles around it, whatever the net's size.
using PoleWeights = std::vector<std::pair<Eigen::Index, double>>;

/// contact_load_pattern's non-zero entries, computed without touching the
/// rest of the net (the same sums, in the same order, bit for bit).
PoleWeights contact_pole_weights(const BSplineSurface& surface,
                                 const std::vector<Contact>& contacts,
                                 const std::vector<double>& shares);

/// The same for unit forces at points of the domain (each clamped to it)
/// with the given shares: contact_pole_weights reads only the contacts' uv_a.
PoleWeights pole_weights_at(const BSplineSurface& surface, const std::vector<Eigen::Vector2d>& uvs,
                            const std::vector<double>& shares);

/// `weights` scattered into a dense pattern of `count` entries.
Eigen::VectorXd dense_pattern(const PoleWeights& weights, Eigen::Index count);

/// Control-point weights g (n_u * n_v entries, row i * n_v + j) of a unit
/// force applied at the contacts' points S(uv_a) with the given shares:
/// g_ij = sum_k share_k R_ij(uv_k), R the rational basis. A force F through
/// the pattern gives control-point forces g_ij F that are non-negative
/// multiples of F, sum to F and have the moment sum_k share_k S(uv_k) x F,
/// exactly (virtual work: g . P is the shared contact point for any control
/// points P). Nothing is inverted, so nothing amplifies.
Eigen::VectorXd contact_load_pattern(const BSplineSurface& surface,
                                     const std::vector<Contact>& contacts,
                                     const std::vector<double>& shares);

/// Largest Coulomb coefficient mu [-] of a tool-body pair (rubber on rubber
/// is about 1; beyond 10 the stick cone is a wall).
inline constexpr double kMaxFriction = 10.0;

/// Coulomb friction for a proxy held by a spring (stiffness k [N/mm]) at its
/// stick point on a surface with outward unit normal n (from the surface
/// towards the proxy): the spring force F = k (device - stick point) [N]
/// presses with N = -F . n and pulls along the surface with F_t = F + N n.
struct FrictionOutcome {
  double normal_force = 0.0;                                   // N [N], > 0 when pressing
  Eigen::Vector3d tangential_force = Eigen::Vector3d::Zero();  // F_t [N]
  /// |F_t| <= mu N: the proxy stays at its stick point.
  bool stick = true;
  /// Slip: how far the proxy slides along the surface so that the remaining
  /// tangential pull is mu N, (|F_t| - mu N) / k along F_t [mm]. Zero on stick.
  Eigen::Vector3d slide = Eigen::Vector3d::Zero();
};
/// Not pressing (N <= 0) counts as slip with the whole tangential pull released
/// (the proxy is free to leave the surface).
FrictionOutcome coulomb_friction(const Eigen::Vector3d& spring_force,
                                 const Eigen::Vector3d& outward_normal, double mu,
                                 double stiffness);

}  // namespace argil
