#pragma once
// Free rigid-body modes of a scene (docs/theory.md, "Free rigid-body modes"):
// the rigid motions of a body that neither its Dirichlet constraints nor its
// frictionless contacts hold, so that the tangent is singular along them.
//
// A rigid motion of a body, u(X) = t + omega x (X - c), moves every control point
// by u(X_a) (NURBS are affine invariant): d translations and 1 (2D) or 3 (3D)
// rotations, the columns of R (n_body_dofs x n_rigid). A mode m = R q is held by
//  - a constraint when it moves a prescribed dof: (R q)_k != 0;
//  - a contact against a rigid obstacle when it moves a point of the contact side
//    along the obstacle's normal there: n(X_a) . u(X_a) != 0 (the normal of a
//    plane is constant, that of a sphere points from its centre: a plane holds
//    the translation along its normal (one-sided) and not the tangential ones, a
//    sphere does not hold rotations about its centre); a contact with friction
//    holds every direction (its points stick until the load overcomes mu p).
// Two bodies joined by a contact pair are taken to hold each other's relative
// motion (their contact is not examined): they form one group, whose rigid modes
// move all its bodies together. The free modes are the null space of the rows
// above, A q = 0, found by an SVD of A (n_rows x n_rigid).
//
// Named modes: the coordinate translations that are free ("can translate freely
// in x"), and for each rotation axis the rotation about the point c that makes it
// free, if one exists ("can rotate freely about (0, 1)"; a least-squares fit of
// the translation part). basis spans all free modes, named or not.
//
// What the run does with them (analysis/run_model.cpp): loads with a resultant along a
// free mode beyond round-off stop the run at once (driven_free_mode); otherwise
// weak springs at every node of the group, S_a = k sum_j m_j(X_a) m_j(X_a)^T, hold
// the modes: their resultant along each free mode balances the loads' (zero), so
// they fix the rigid position without carrying load, and their energy is reported
// against the strain energy.

#include "analysis/scene.hpp"
#include "core/types.hpp"

#include <optional>
#include <string>
#include <vector>

namespace iga::analysis {

/// A mode moves a prescribed dof or a contact point's normal by at most this much,
/// per unit amplitude (node motion <= 1), and counts as free: the geometry's
/// round-off is ~1e-15, a held mode moves them O(1).
constexpr double free_mode_tolerance = 1e-8;
/// A load's work along a unit free mode beyond this fraction of sum |f_i m_i| (the
/// round-off scale of that sum, ~n eps) drives the mode.
constexpr double driven_mode_tolerance = 1e-9;
/// Weak-spring stiffness: the springs of a group together hold a translation with
/// this fraction of E L^(d-2) (the stiffness of the body as a bar): six orders
/// below the body, so they change its deformation by ~1e-6 where they act at all.
constexpr double weak_spring_factor = 1e-6;
/// Spring energy above this fraction of the strain energy is not negligible: the
/// springs carry load (their share for a balanced load is ~weak_spring_factor).
constexpr double negligible_spring_energy = 1e-4;

/// A named free mode: a translation along a coordinate axis or a rotation about one.
struct FreeMode {
    enum class Kind { translation, rotation };
    Kind kind = Kind::translation;
    int axis = 0;         ///< 0, 1, 2 = x, y, z (a 2D rotation turns about z)
    VecN centre;          ///< rotation: the point it turns about
    Vector displacement;  ///< n_full: unit translation, or unit angle about centre (zero on prescribed dofs)
    std::string text;     ///< "translate freely in x", "rotate freely about (0, 1)"
};

/// The free modes of one group of deformable bodies joined by contact pairs.
struct FreeModeGroup {
    std::vector<int> bodies;       ///< deformable body indices
    std::string label;             ///< "body drum", "bodies a and b"
    std::vector<FreeMode> named;
    Matrix basis;                  ///< n_full x n_free_modes, node motion <= 1, zero on prescribed dofs
    double spring_stiffness = 0;   ///< k of the weak springs

    int n_modes() const { return static_cast<int>(basis.cols()); }
};

/// The groups that have free modes (none: every body held).
std::vector<FreeModeGroup> find_free_modes(const Scene& scene);

/// Whether the tangent is singular for sure while no contact point carries: some
/// body has rigid motions that its constraints leave free (under finite kinematics
/// translations only, the motions a stressed tangent is still singular along), more
/// of them than the weak springs of `free_modes` hold, so only contact holds the
/// rest (a first touch, docs/solver.md "The first touch"). Sufficient, not necessary:
/// false says nothing.
bool singular_without_contact(const Scene& scene, const std::vector<FreeModeGroup>& free_modes);

/// "body drum can translate freely in x", one line per group.
std::string free_mode_text(const FreeModeGroup& group);

/// The loads at pseudo-time t (dead loads, and follower pressures in the reference
/// configuration), n_full: what may drive a free mode. The loads are linear in t
/// between the path's breakpoints, so checking t = 0 and every breakpoint checks
/// the whole path.
Vector reference_loads(const Scene& scene, double t);

/// "loads drive a free mode: body block can translate freely in x and the loads
/// have a resultant 0.1 in x", or nothing when no load drives a free mode.
std::optional<std::string> driven_free_mode(const Scene& scene, const std::vector<FreeModeGroup>& groups,
                                            const Vector& loads);

/// The weak spring of one node: S (d x d) on its full dofs.
struct NodeSpring {
    std::vector<int> dofs;  ///< full dofs of the node, component order
    MatN stiffness;
};

/// The weak springs of a group (one per node that a free mode moves).
std::vector<NodeSpring> weak_springs(const Scene& scene, const FreeModeGroup& group);

}  // namespace iga::analysis
