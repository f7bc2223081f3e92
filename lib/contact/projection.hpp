#pragma once
// Closest-point projection of a point onto a 2D NURBS curve (a contact side in
// its current configuration): find xibar with (x - x_m(xibar)) . x_m,xi(xibar) = 0
// (Kopacka et al. eq. 9; Piegl & Tiller, The NURBS Book, section 6.1).
//
// Algorithm (physics.md section 4.5):
//  - The curve is split at its C0 knots (multiplicity >= degree) into pieces on
//    which the parametrization is C1; Newton may cross knots inside a piece but
//    treats a piece's ends like patch ends. Evaluation always uses an explicitly
//    chosen span, so a C0 knot is evaluated from the side being worked on.
//  - Each piece that holds a candidate span starts either from the warm start
//    (when it lies in that piece) or from the nearest of a few samples per
//    candidate span, then runs Newton on f(xi) = x_xi . (x_m - x) with the full
//    f' = |x_xi|^2 + x_xixi . (x_m - x) (Gauss-Newton f' = |x_xi|^2 when the full
//    one is not positive), a trust region of max_step_fraction of the current
//    span, and clamping to the piece. A warm start that fails falls back to
//    sampling.
//  - The nearest piece result wins. A result clamped at a patch end whose gap
//    vector is not along the normal is off_end; one clamped at an interior C0
//    knot where the tangent jumps is at_kink (the point lies in the fan between
//    the one-sided normals). Both are inactive for the penalty kernels.
// Convergence: a full Newton step moves the foot point by at most tolerance *
// (curve size + distance), curve size = diagonal of the control-point bounding
// box; that last step is still taken, so the foot point is accurate to about
// round-off (which keeps finite-difference checks of the kernels clean). At a
// piece end the test is the tangential offset |f| / |x_xi| against the same bound.
// Shapes: points and vectors have d = 2 entries. 3D (surface sides) is not
// supported: project_to_curve throws iga::Error for n_par != 1 or d != 2.
// A failed projection is reported by status, with finite fields, never by NaN.

#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <optional>
#include <span>

namespace iga::contact {

struct ProjectionOptions {
    std::optional<double> start;      ///< warm start xi (e.g. last converged value); clamped to the domain
    double tolerance = 1e-12;         ///< relative to the curve size (see above)
    int max_iterations = 30;          ///< Newton iterations per piece
    double max_step_fraction = 0.5;   ///< trust region: at most this fraction of the current span per step
    /// Span numbers k in [0, n_spans) that the search found near the point; empty
    /// means all spans. Only pieces holding one of them are searched. The viewed
    /// storage must outlive the call.
    std::span<const int> candidate_spans;
};

struct Projection {
    enum class Status {
        ok,       ///< orthogonal projection found (the kernels may use it)
        off_end,  ///< nearest point at a patch end, gap vector not along the normal: inactive
        at_kink,  ///< nearest point at a C0 knot where the tangent jumps, x in the normal fan: inactive
        failed,   ///< no convergence or non-finite data: a numerical failure of the step
    };
    Status status = Status::failed;
    double xi = 0.0;       ///< parameter of the foot point
    int span = 0;          ///< knot index of the span used to evaluate at xi
    VecN point;            ///< x_m(xi), d
    VecN tangent;          ///< x_m,xi, d
    VecN second;           ///< x_m,xixi, d
    VecN normal;           ///< unit outward normal s (t_y, -t_x) / |t|, d
    double metric = 0.0;   ///< m = tangent . tangent
    double gap = 0.0;      ///< g_N = -(x - point) . normal, positive = penetration (gap.hpp)
    double curvature = 0.0;///< b = normal . second
    double distance = 0.0; ///< |x - point|
    int iterations = 0;    ///< Newton iterations over all pieces tried
    nurbs::BasisValues basis;  ///< R, dR (and d2R) on `span` at xi; indices are curve control points
};

/// Projects x onto `curve` (n_par = 1, d = 2, CURRENT control points) whose
/// outward normal has orientation sign `outward_sign` (+1/-1, orientation.hpp).
Projection project_to_curve(const nurbs::Patch& curve, int outward_sign, const VecN& x,
                            const ProjectionOptions& options = {});

}  // namespace iga::contact
