#include "contact/projection.hpp"

#include "contact/gap.hpp"
#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace iga::contact {
namespace {

/// A run of spans [first_span, last_span] (span numbers) joined by C1 knots.
struct Piece {
    int first_span;
    int last_span;
    double lower;
    double upper;
};

std::vector<Piece> smooth_pieces(const nurbs::KnotVector& knots)
{
    const std::vector<double> breaks = knots.breakpoints();
    const int n_spans = knots.n_spans();
    std::vector<Piece> pieces;
    int first = 0;
    for (int k = 1; k <= n_spans; ++k) {
        const bool end = k == n_spans || knots.multiplicity(breaks[k]) >= knots.degree();
        if (end) {
            pieces.push_back({first, k - 1, breaks[first], breaks[k]});
            first = k;
        }
    }
    return pieces;
}

/// Knot index of the span of `piece` used to evaluate at xi: the span holding
/// xi, except that a piece's right end is evaluated from inside the piece.
int span_in_piece(const nurbs::KnotVector& knots, const Piece& piece, double xi)
{
    const int k = std::clamp(knots.span_number(knots.find_span(xi)), piece.first_span, piece.last_span);
    return knots.span_start(k);
}

struct CurveSample {
    nurbs::BasisValues basis;
    nurbs::PointDerivatives point;
};

CurveSample evaluate_on_span(const nurbs::Patch& curve, int knot_span, double xi, int n_derivs)
{
    VecN param(1);
    param(0) = xi;
    CurveSample s;
    s.basis = nurbs::rational_basis(curve, {knot_span, 0, 0}, param, n_derivs);
    s.point = nurbs::combine(s.basis, curve.control_points());
    return s;
}

bool all_finite(const CurveSample& s)
{
    return s.point.x.allFinite() && s.point.dx.allFinite() && s.point.d2x.allFinite();
}

struct PieceResult {
    bool finite = false;     ///< false: non-finite values or a zero tangent met
    bool converged = false;  ///< orthogonality residual below tolerance
    bool clamped = false;    ///< stopped at a piece end with the step pointing outward
    double xi = 0.0;
    int span = 0;
    double distance = std::numeric_limits<double>::infinity();
    int iterations = 0;
    CurveSample sample;
};

PieceResult newton_on_piece(const nurbs::Patch& curve, const VecN& x, const Piece& piece, double xi0,
                            const ProjectionOptions& options, double curve_size)
{
    // Below this fraction of the tolerance the offset is at round-off level: no
    // polishing step is worth taking.
    constexpr double negligible_fraction = 1e-3;
    const nurbs::KnotVector& knots = curve.knots(0);
    const std::vector<double>& kv = knots.knot_values();
    PieceResult r;
    double xi = std::clamp(xi0, piece.lower, piece.upper);
    bool polished = false;  // the last step was below tolerance: this evaluation is the answer
    for (int it = 0;; ++it) {
        const int span = span_in_piece(knots, piece, xi);
        CurveSample s = evaluate_on_span(curve, span, xi, 2);
        r.xi = xi;
        r.span = span;
        r.iterations = it;
        if (!all_finite(s))
            return r;
        const VecN d = s.point.x - x;  // x_m - x
        const VecN t = s.point.dx.col(0);
        const VecN tt = s.point.d2x.col(0);
        const double m = t.squaredNorm();
        if (!(m > 0.0) || !std::isfinite(m))
            return r;
        r.finite = true;
        r.distance = d.norm();
        const double f = t.dot(d);
        const double offset = std::abs(f) / std::sqrt(m);  // tangential offset of x from the foot point
        const double tol = options.tolerance * (curve_size + r.distance);
        if (polished || offset <= negligible_fraction * tol) {
            r.converged = true;
            r.sample = std::move(s);
            return r;
        }
        if (it >= options.max_iterations) {
            r.converged = offset <= tol;
            r.sample = std::move(s);
            return r;
        }
        double fp = m + tt.dot(d);
        if (!(fp > 0.0))
            fp = m;  // Gauss-Newton: the full f' would step towards a distance maximum
        const double newton_step = -f / fp;
        const double max_step = options.max_step_fraction * (kv[span + 1] - kv[span]);
        const double xi_new = std::clamp(xi + std::clamp(newton_step, -max_step, max_step), piece.lower, piece.upper);
        if (xi_new == xi) {
            // Pushed against a piece end, or a step below the resolution of xi
            // (in the interior that is as converged as it gets).
            const bool at_end = xi == piece.lower || xi == piece.upper;
            r.converged = !at_end || offset <= tol;
            r.clamped = !r.converged;
            r.sample = std::move(s);
            return r;
        }
        // A full Newton step below tolerance: take it (quadratic convergence puts
        // the result near round-off) and stop after evaluating there.
        polished = std::abs(newton_step) * std::sqrt(m) <= tol;
        xi = xi_new;
    }
}

/// Start of Newton on a piece: the nearest of a few samples on its candidate spans.
double nearest_sample(const nurbs::Patch& curve, const VecN& x, const Piece& piece,
                      const std::vector<char>& span_is_candidate)
{
    const nurbs::KnotVector& knots = curve.knots(0);
    const std::vector<double>& kv = knots.knot_values();
    const int n_samples = knots.degree() + 2;  // enough to separate the local minima of one span
    double best_xi = 0.5 * (piece.lower + piece.upper);
    double best_dist = std::numeric_limits<double>::infinity();
    for (int k = piece.first_span; k <= piece.last_span; ++k) {
        if (!span_is_candidate[k])
            continue;
        const int span = knots.span_start(k);
        for (int j = 0; j < n_samples; ++j) {
            const double xi = kv[span] + (kv[span + 1] - kv[span]) * j / (n_samples - 1.0);
            const CurveSample s = evaluate_on_span(curve, span, xi, 0);
            const double dist = (s.point.x - x).norm();
            if (dist < best_dist) {
                best_dist = dist;
                best_xi = xi;
            }
        }
    }
    return best_xi;
}

/// Nearer wins; at (numerically) equal distance an orthogonal foot beats a
/// clamped one, so a geometrically smooth C0 knot is not called a kink.
bool is_better(const PieceResult& a, const PieceResult& b, double curve_size)
{
    constexpr double relative_tie = 1e-14;  // a few ulps of the coordinates
    const double tie = relative_tie * (curve_size + b.distance);
    if (a.distance < b.distance - tie)
        return true;
    return std::abs(a.distance - b.distance) <= tie && a.converged && !b.converged;
}

Projection failed_projection(int iterations)
{
    Projection p;
    p.status = Projection::Status::failed;
    p.point = p.tangent = p.second = p.normal = VecN::Zero(2);
    p.iterations = iterations;
    return p;
}

}  // namespace

Projection project_to_curve(const nurbs::Patch& curve, int outward_sign, const VecN& x,
                            const ProjectionOptions& options)
{
    if (curve.n_par() != 1 || curve.dim() != 2)
        throw Error("contact: projection onto a side with n_par = " + std::to_string(curve.n_par()) +
                    " in d = " + std::to_string(curve.dim()) +
                    " is not supported (only 2D curves; 3D contact is not implemented yet)");
    IGA_CHECK(x.size() == 2, "contact: projected point must have 2 coordinates");
    IGA_CHECK(outward_sign == 1 || outward_sign == -1, "contact: outward sign must be +1 or -1");

    if (!x.allFinite() || !curve.control_points().allFinite())
        return failed_projection(0);

    const nurbs::KnotVector& knots = curve.knots(0);
    const int n_spans = knots.n_spans();
    const RowMatrix& cps = curve.control_points();
    const double curve_size = (cps.colwise().maxCoeff() - cps.colwise().minCoeff()).norm();

    std::vector<char> span_is_candidate(n_spans, options.candidate_spans.empty() ? 1 : 0);
    for (const int k : options.candidate_spans) {
        IGA_CHECK(k >= 0 && k < n_spans, "contact: candidate span number out of range");
        span_is_candidate[k] = 1;
    }

    const std::vector<Piece> pieces = smooth_pieces(knots);
    int total_iterations = 0;
    std::optional<PieceResult> best;
    for (const Piece& piece : pieces) {
        bool considered = false;
        for (int k = piece.first_span; k <= piece.last_span && !considered; ++k)
            considered = span_is_candidate[k] != 0;
        if (!considered)
            continue;

        std::optional<PieceResult> result;
        if (options.start && std::isfinite(*options.start)) {
            const double start = std::clamp(*options.start, knots.front(), knots.back());
            if (start >= piece.lower && start <= piece.upper) {
                PieceResult r = newton_on_piece(curve, x, piece, start, options, curve_size);
                total_iterations += r.iterations;
                if (r.finite && (r.converged || r.clamped))
                    result = std::move(r);
            }
        }
        // No warm start here, it failed, or it ran into a piece end: (also) start
        // from the nearest sample.
        if (!result || result->clamped) {
            const double start = nearest_sample(curve, x, piece, span_is_candidate);
            PieceResult r = newton_on_piece(curve, x, piece, start, options, curve_size);
            total_iterations += r.iterations;
            if (!r.finite || !(r.converged || r.clamped)) {
                if (!result)
                    return failed_projection(total_iterations);
            } else if (!result || is_better(r, *result, curve_size)) {
                result = std::move(r);
            }
        }
        if (!best || is_better(*result, *best, curve_size))
            best = std::move(result);
    }
    if (!best)
        return failed_projection(total_iterations);

    Projection p;
    p.xi = best->xi;
    p.span = best->span;
    p.point = best->sample.point.x;
    p.tangent = best->sample.point.dx.col(0);
    p.second = best->sample.point.d2x.col(0);
    p.metric = p.tangent.squaredNorm();
    p.normal = curve_normal_2d(p.tangent, outward_sign);
    p.gap = normal_gap(x, p.point, p.normal);
    p.curvature = p.normal.dot(p.second);
    p.distance = best->distance;
    p.iterations = total_iterations;
    p.basis = std::move(best->sample.basis);
    if (best->converged)
        p.status = Projection::Status::ok;
    else if (p.xi == knots.front() || p.xi == knots.back())
        p.status = Projection::Status::off_end;
    else
        p.status = Projection::Status::at_kink;
    return p;
}

}  // namespace iga::contact
