#pragma once
// Closest-point projection of a point x onto a NURBS contact side in its
// CURRENT configuration: a patch with n_par = d - 1 parameters in d = 2 or 3
// (a curve in 2D, a surface in 3D). Finds xibar with
//   (x - x_m(xibar)) . a_alpha(xibar) = 0,   a_alpha = dx_m/dxi^alpha
// (Kopacka et al. eq. 9; Piegl & Tiller, The NURBS Book, section 6.1), i.e. a
// local minimum of f(xi) = 1/2 |x - x_m(xi)|^2, the nearest over the candidates.
//
// Algorithm (docs/theory.md, "Closest-point projection" and "Contact formulation"):
//  - Regions. Each parameter direction is split at its C0 knots (multiplicity
//    >= degree) into pieces on which the parametrization is C1; a region is a
//    product of pieces (a run of spans in 2D, a block of Bezier elements in 3D).
//    Newton crosses C1 element boundaries inside a region freely; a region's
//    bounds (patch ends, C0 creases) are box constraints. Evaluation always uses
//    an explicitly chosen span per direction, so a C0 knot is evaluated from the
//    side being worked on.
//  - Local phase, per region holding a candidate element: start from the warm
//    start (when it lies in the region) or from the nearest of (p+2)^(d-1)
//    samples per candidate element, then a safeguarded projected Newton on f:
//    gradient g = A^T (x_m - x), Hessian H = m_ab + (x_m - x) . x_m,ab with
//    m_ab = a_a . a_b (Gauss-Newton H = m when H is not positive definite),
//    a trust region of max_step_fraction of the current span per direction
//    (the step is scaled, keeping its direction), and clamping to the region box;
//    from the 11th iteration on (plain Newton has converged long before, unless
//    it cycles), a step that increases the distance is taken back and retried
//    with half the trust region.
//    A direction whose bound is active with the gradient pointing out is fixed:
//    Newton continues on the edge (1D), or stops at the corner. A warm start that
//    fails or stops on a bound is followed by a start from the samples.
//  - Collapsed edges (a pole, where one tangent vanishes): surfaces are evaluated
//    relative to a control point, so the coincident control points cancel exactly
//    and a short tangent keeps its relative accuracy; the linear solves scale each
//    direction by 1/|a_alpha| and drop a direction shorter than 1e4 eps of the
//    other (a pseudo-inverse), so Newton works on the remaining direction and
//    never divides by zero. Samples on a collapsed edge are taken a quarter
//    spacing inside (on the pole itself the azimuth is undefined), and on the
//    edge orthogonality is measured in space against the limit normal, which uses
//    the mixed derivative x_m,12 in place of the vanishing tangent.
//  - The nearest region result wins (at equal distance an orthogonal foot beats a
//    clamped one). A result clamped at a patch end, gap vector not along the
//    normal, is off_end; one clamped at an interior C0 crease is at_kink (x lies
//    in the fan between the one-sided normals). Both are inactive for the kernels.
// Convergence: a full Newton step moves the foot point by at most tolerance *
// (surface size + distance), surface size = diagonal of the control-point
// bounding box; that last step is still taken, so the foot point is accurate to
// about round-off. On a bound the test is the tangential offset
// |g|_{m^-1} = sqrt(g^T m^+ g) against the same bound.
// Method choice, measured (benchmarks/projection_benchmark.cpp, 256 points within
// +-0.05 of the surface, mean evaluations per projection to the same tolerance):
// Newton 4.1-4.3 on a rational sphere octant and 4.6-5.0 on a rational wavy
// free-form surface (degrees 2 and 4), against 4.0-4.2 and 6.6-6.9 for the
// second-order geometric iteration of Hu & Wallner (CAGD 22, 2005; our own code
// in the benchmark); an iteration costs the same (one evaluation with second
// derivatives), so Newton is as fast on the sphere and ~1.4x faster on the
// free-form surface. Newton stays the method; the torus-patch variant of
// Liu et al. (2009) needs the same derivatives and was not tried.
// Shapes: points and normals d; tangents d x (d-1); second d x (d-1)d/2 packed as
// BasisValues::d2R (uu; or uu, uv, vv); metric and curvature (d-1) x (d-1).
// A failed projection is reported by status, with finite fields, never by NaN.

#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <array>
#include <optional>
#include <span>

namespace iga::contact {

struct ProjectionOptions {
    std::optional<VecN> start;      ///< warm start (d-1 parameters), e.g. the last foot point; clamped to the domain
    int start_element = -1;         ///< its element (index into surface.elements()), if known: its region only
    double tolerance = 1e-12;       ///< relative to surface size + distance (see above)
    int max_iterations = 30;        ///< Newton iterations per start
    double max_step_fraction = 0.5; ///< trust region: at most this fraction of the current span per direction
    /// Indices into surface.elements() that the search found near the point; empty
    /// means all. Only regions holding one of them are searched, from samples on
    /// them. The viewed storage must outlive the call.
    std::span<const int> candidate_elements;
};

struct Projection {
    enum class Status {
        ok,       ///< orthogonal projection found (the kernels may use it)
        off_end,  ///< nearest point on the patch boundary, gap vector not along the normal: inactive
        at_kink,  ///< nearest point on an interior C0 crease, x in the normal fan: inactive
        failed,   ///< no convergence or non-finite/degenerate data: a numerical failure of the step
        /// Newton did not settle in any region (near a collapsed edge the parametrization
        /// is singular and its steps can swing between two azimuths), but found finite
        /// points: the nearest of them is reported, not necessarily the surface's nearest.
        /// The caller may take the point as open where its gap is clearly open (with a
        /// margin for that); elsewhere it is a failure.
        unsettled,
    };
    Status status = Status::failed;
    VecN xi;            ///< d-1 parameters of the foot point
    int element = -1;   ///< index into surface.elements() whose spans evaluated xi
    VecN point;         ///< x_m(xi), d
    Matrix tangents;    ///< d x (d-1): a_alpha = dx_m/dxi^alpha
    Matrix second;      ///< d x (d-1)d/2: x_m,alpha beta, packed like BasisValues::d2R
    VecN normal;        ///< unit outward normal, d: 2D s (t_y, -t_x)/|t|, 3D s (a_1 x a_2)/|a_1 x a_2|
    Matrix metric;      ///< (d-1) x (d-1): m_ab = a_a . a_b (singular on a collapsed edge)
    Matrix curvature;   ///< (d-1) x (d-1): b_ab = normal . x_m,ab
    double gap = 0.0;   ///< g_N = -(x - point) . normal, positive = penetration (gap.hpp)
    double distance = 0.0;  ///< |x - point|
    int iterations = 0;     ///< Newton iterations over all starts and regions tried
    int candidates = 0;     ///< candidate elements considered
    nurbs::BasisValues basis;  ///< R, dR, d2R on `element` at xi; indices are surface control points
};

/// Projects x (d entries) onto `surface` (n_par = d - 1, d = 2 or 3, CURRENT
/// control points) whose outward normal has orientation sign `outward_sign`
/// (+1/-1). Throws iga::Error for other shapes and out-of-range candidates
/// (programming errors); non-finite data gives status failed.
Projection project_to_surface(const nurbs::Patch& surface, int outward_sign, const VecN& x,
                              const ProjectionOptions& options = {});

/// The choice between two candidate feet of one point: the nearer wins; at
/// (numerically) equal distance an orthogonal foot beats a clamped one, so a
/// geometrically smooth C0 knot or patch interface is not called a kink. Used
/// between the regions of a patch and between the patches of a surface.
bool nearer_foot(double distance_a, bool orthogonal_a, double distance_b, bool orthogonal_b, double surface_size);

/// Unit outward normal of a side at a point with tangents `tangents` (d x (d-1))
/// and second derivatives `second` (packed), orientation sign s. In 3D a tangent
/// that vanishes (below sqrt(eps) of the other: a collapsed edge) is replaced by
/// +-x_m,12, its limit direction; `near_lower` says, per direction, whether xi is
/// nearer the lower end of its span (which fixes that sign). Returns a zero vector
/// when no normal exists (zero tangents).
VecN side_normal(const Matrix& tangents, const Matrix& second, int sign, const std::array<bool, 2>& near_lower);

}  // namespace iga::contact
