#include "contact/projection.hpp"

#include "contact/gap.hpp"
#include "core/error.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace iga::contact {
namespace {

constexpr double machine_eps = std::numeric_limits<double>::epsilon();
// Eigenvalues of a computed symmetric matrix (scaled to a unit diagonal, see
// direction_scaling) carry an error of a few eps times its norm: below this
// fraction of the largest one a direction is round-off and is dropped.
constexpr double round_off_eigenvalue = 64.0 * machine_eps;

/// A run of spans [first_span, last_span] (span numbers) of one direction joined by C1 knots.
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

/// Per-direction layout of the surface: its pieces and which piece holds each span.
struct Layout {
    int n_par = 0;
    std::array<const nurbs::KnotVector*, 2> knots{nullptr, nullptr};
    std::array<std::vector<Piece>, 2> pieces;
    std::array<std::vector<int>, 2> piece_of_span;
    std::array<int, 2> n_spans{1, 1};
    std::array<int, 2> n_pieces{1, 1};
    /// collapsed[k][end]: the patch edge xi_k = front (end 0) / back (end 1) is a
    /// single point (a pole), within sqrt(eps) of the surface size. Surfaces only.
    std::array<std::array<bool, 2>, 2> collapsed{};

    Layout(const nurbs::Patch& surface, double surface_size) : n_par(surface.n_par())
    {
        if (n_par == 2) {
            const RowMatrix& cps = surface.control_points();
            const int n_u = surface.n_basis(0), n_v = surface.n_basis(1);
            for (int k = 0; k < 2; ++k)
                for (int end = 0; end < 2; ++end) {
                    const int fixed = end == 0 ? 0 : (k == 0 ? n_u : n_v) - 1;
                    const int n_along = k == 0 ? n_v : n_u;
                    VecN lower = cps.row(k == 0 ? fixed : n_u * fixed).transpose(), upper = lower;
                    for (int t = 1; t < n_along; ++t) {
                        const Index a = k == 0 ? fixed + n_u * t : t + n_u * fixed;
                        lower = lower.cwiseMin(cps.row(a).transpose());
                        upper = upper.cwiseMax(cps.row(a).transpose());
                    }
                    collapsed[k][end] = (upper - lower).norm() <= std::sqrt(machine_eps) * surface_size;
                }
        }
        for (int k = 0; k < n_par; ++k) {
            knots[k] = &surface.knots(k);
            pieces[k] = smooth_pieces(*knots[k]);
            n_spans[k] = knots[k]->n_spans();
            n_pieces[k] = static_cast<int>(pieces[k].size());
            piece_of_span[k].resize(n_spans[k]);
            for (int p = 0; p < n_pieces[k]; ++p)
                for (int s = pieces[k][p].first_span; s <= pieces[k][p].last_span; ++s)
                    piece_of_span[k][s] = p;
        }
    }

    /// Span numbers of element e (u fastest, as Patch::elements()).
    std::array<int, 2> span_numbers(int e) const { return {e % n_spans[0], n_par > 1 ? e / n_spans[0] : 0}; }
    int element_index(const std::array<int, 2>& k) const { return k[0] + n_spans[0] * k[1]; }
    /// Region (a product of pieces, numbered u fastest) holding element e.
    int region_of(int e) const
    {
        const std::array<int, 2> k = span_numbers(e);
        return piece_of_span[0][k[0]] + n_pieces[0] * (n_par > 1 ? piece_of_span[1][k[1]] : 0);
    }
    const Piece& piece(int region, int dir) const
    {
        return pieces[dir][dir == 0 ? region % n_pieces[0] : region / n_pieces[0]];
    }
    bool region_contains(int region, const VecN& xi) const
    {
        for (int k = 0; k < n_par; ++k)
            if (xi(k) < piece(region, k).lower || xi(k) > piece(region, k).upper)
                return false;
        return true;
    }
};

/// Knot index of the span used to evaluate at u in direction `dir` of a region:
/// the span holding u, except that a piece's right end is evaluated from inside it.
int span_in_piece(const nurbs::KnotVector& knots, const Piece& piece, double u)
{
    const int k = std::clamp(knots.span_number(knots.find_span(u)), piece.first_span, piece.last_span);
    return knots.span_start(k);
}

struct Sample {
    nurbs::BasisValues basis;
    nurbs::PointDerivatives point;
    std::array<int, 3> span{0, 0, 0};  ///< knot index per direction
};

/// x = P_ref + sum_A R_A (P_A - P_ref), and the derivatives from the same
/// differences (sum_A dR_A = 0), with P_ref the control point of the largest R_A.
/// Next to a collapsed edge its coincident control points then cancel exactly,
/// so the vanishing tangent keeps its relative accuracy instead of drowning in
/// round-off of the coordinates (which would stall Newton near a pole).
nurbs::PointDerivatives combine_relative(const nurbs::BasisValues& basis, const RowMatrix& points)
{
    const int d = static_cast<int>(points.cols());
    const int n_local = static_cast<int>(basis.indices.size());
    Index dominant = 0;
    basis.R.maxCoeff(&dominant);
    const VecN reference = points.row(basis.indices[static_cast<std::size_t>(dominant)]).transpose();
    nurbs::PointDerivatives out;
    out.x = VecN::Zero(d);
    if (basis.dR.size() > 0)
        out.dx = Matrix::Zero(d, basis.dR.cols());
    if (basis.d2R.size() > 0)
        out.d2x = Matrix::Zero(d, basis.d2R.cols());
    for (int a = 0; a < n_local; ++a) {
        const VecN P = points.row(basis.indices[static_cast<std::size_t>(a)]).transpose() - reference;
        out.x += basis.R(a) * P;
        if (basis.dR.size() > 0)
            out.dx += P * basis.dR.row(a);
        if (basis.d2R.size() > 0)
            out.d2x += P * basis.d2R.row(a);
    }
    out.x += reference;
    return out;
}

/// Point and derivatives on given spans. Curves use nurbs::combine (the 2D
/// results are those of the first release, bit for bit); surfaces combine
/// relative to a control point (combine_relative).
Sample evaluate_on_spans(const nurbs::Patch& surface, const std::array<int, 3>& span, const VecN& xi, int n_derivs)
{
    Sample s;
    s.span = span;
    s.basis = nurbs::rational_basis(surface, span, xi, n_derivs);
    s.point = surface.n_par() == 1 ? nurbs::combine(s.basis, surface.control_points())
                                   : combine_relative(s.basis, surface.control_points());
    return s;
}

bool all_finite(const Sample& s)
{
    return s.point.x.allFinite() && s.point.dx.allFinite() && s.point.d2x.allFinite();
}


// A parameter direction whose tangent is shorter than this fraction of the
// longest is collapsed (a pole): its computed tangent is a difference of equal
// control points, pure round-off (a few eps of the longest). Above it the
// tangent has at least 1e-4 relative accuracy, enough for Newton to converge.
constexpr double collapse_floor = 1e4 * machine_eps;

/// Scaling of the parameter directions (n = 2): 1/|a_alpha| from the metric's
/// diagonal, so that the scaled metric has a unit diagonal and a direction that
/// is merely short near a pole is solved as accurately as the others; 0 for a
/// collapsed direction, which the solves then drop.
Eigen::Vector2d direction_scaling(const MatN& metric)
{
    const double longest = std::sqrt(std::max(metric(0, 0), metric(1, 1)));
    Eigen::Vector2d scaling;
    for (int k = 0; k < 2; ++k) {
        const double length = std::sqrt(std::max(metric(k, k), 0.0));
        scaling(k) = length > collapse_floor * longest ? 1.0 / length : 0.0;
    }
    return scaling;
}

/// A^+ b for a symmetric n x n matrix (n = 1, 2). 1D: b / A when A > 0, else 0.
/// 2D: on the scaled matrix S A S (S = direction_scaling(metric)), eigen-directions
/// with an eigenvalue that is not positive, or at round-off of the largest, are
/// dropped; collapsed directions get no step. Never divides by zero.
VecN pseudo_solve(const MatN& A, const VecN& b, const MatN& metric)
{
    if (A.rows() == 1) {
        VecN x(1);
        x(0) = A(0, 0) > 0.0 ? b(0) / A(0, 0) : 0.0;
        return x;
    }
    const Eigen::Vector2d S = direction_scaling(metric);
    Eigen::Matrix2d scaled;
    scaled << S(0) * A(0, 0) * S(0), S(0) * A(0, 1) * S(1), S(1) * A(1, 0) * S(0), S(1) * A(1, 1) * S(1);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
    es.computeDirect(scaled);
    const double largest = es.eigenvalues().cwiseAbs().maxCoeff();
    const Eigen::Vector2d scaled_b(S(0) * b(0), S(1) * b(1));
    Eigen::Vector2d y = Eigen::Vector2d::Zero();
    for (int k = 0; k < 2; ++k) {
        const double lambda = es.eigenvalues()(k);
        if (lambda > round_off_eigenvalue * largest) {
            const Eigen::Vector2d v = es.eigenvectors().col(k);
            y += (v.dot(scaled_b) / lambda) * v;
        }
    }
    VecN x(2);
    x << S(0) * y(0), S(1) * y(1);
    return x;
}

/// A positive definite on the directions that are not collapsed (scaled as in pseudo_solve).
bool positive_definite(const MatN& A, const MatN& metric)
{
    if (A.rows() == 1)
        return A(0, 0) > 0.0;
    const Eigen::Vector2d S = direction_scaling(metric);
    if (S(0) == 0.0 || S(1) == 0.0) {
        const int k = S(0) == 0.0 ? 1 : 0;  // the remaining direction
        return A(k, k) > 0.0;
    }
    Eigen::Matrix2d scaled;
    scaled << S(0) * A(0, 0) * S(0), S(0) * A(0, 1) * S(1), S(1) * A(1, 0) * S(0), S(1) * A(1, 1) * S(1);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es;
    es.computeDirect(scaled);
    return es.eigenvalues()(0) > round_off_eigenvalue * es.eigenvalues().cwiseAbs().maxCoeff();
}

/// |g|_{m^-1}: how far x is, tangentially, from being over the foot point.
double tangential_offset(const MatN& metric, const VecN& g)
{
    return std::sqrt(std::max(0.0, g.dot(pseudo_solve(metric, g, metric))));
}

MatN sub_matrix(const MatN& A, const std::vector<int>& idx)
{
    const Index n = static_cast<Index>(idx.size());
    MatN out(n, n);
    for (Index i = 0; i < n; ++i)
        for (Index j = 0; j < n; ++j)
            out(i, j) = A(idx[i], idx[j]);
    return out;
}

struct RegionResult {
    bool finite = false;        ///< false: non-finite values or zero tangents met
    bool converged = false;     ///< orthogonality residual below tolerance
    bool clamped = false;       ///< stopped on the region's boundary, not orthogonal
    bool at_patch_end = false;  ///< (clamped) held by a bound that is a patch end
    VecN xi;
    double distance = std::numeric_limits<double>::infinity();
    int iterations = 0;
    Sample sample;
};

/// True when a bound of direction k holds xi (the gradient pushes out of it).
bool pushed_out(double xi, double g, const Piece& piece)
{
    return (xi == piece.lower && g > 0.0) || (xi == piece.upper && g < 0.0);
}

RegionResult newton_in_region(const nurbs::Patch& surface, const Layout& layout, int region, const VecN& x,
                              VecN xi, const ProjectionOptions& options, double surface_size)
{
    // Below this fraction of the tolerance the offset is at round-off level: no
    // polishing step is worth taking.
    constexpr double negligible_fraction = 1e-3;
    const int n = layout.n_par;
    std::array<const Piece*, 2> piece{&layout.piece(region, 0), n > 1 ? &layout.piece(region, 1) : nullptr};
    for (int k = 0; k < n; ++k)
        xi(k) = std::clamp(xi(k), piece[k]->lower, piece[k]->upper);

    RegionResult r;
    // Decides clamped vs converged for a stop on the region's boundary.
    auto stop_on_bound = [&](Sample&& s, const VecN& g, double offset, double tol) {
        r.converged = offset <= tol;
        r.clamped = !r.converged;
        if (r.clamped) {
            bool held = false, at_end = false, at_end_any = false;
            for (int k = 0; k < n; ++k) {
                const nurbs::KnotVector& kv = *layout.knots[k];
                const bool patch_end = xi(k) == kv.front() || xi(k) == kv.back();
                at_end_any = at_end_any || patch_end;
                if (pushed_out(xi(k), g(k), *piece[k])) {
                    held = true;
                    at_end = at_end || patch_end;
                }
            }
            r.at_patch_end = held ? at_end : at_end_any;
        }
        r.sample = std::move(s);
        return r;
    };

    enum class Polish { none, interior, on_bound };
    Polish polished = Polish::none;  // the last step was below tolerance: this evaluation is the answer
    // Safeguard: the last point that did not increase the distance, and the
    // trust region's size relative to max_step_fraction.
    std::optional<VecN> accepted_xi;
    double accepted_distance = std::numeric_limits<double>::infinity();
    double radius = 1.0;
    for (int it = 0;; ++it) {
        std::array<int, 3> span{0, 0, 0};
        for (int k = 0; k < n; ++k)
            span[k] = span_in_piece(*layout.knots[k], *piece[k], xi(k));
        Sample s = evaluate_on_spans(surface, span, xi, 2);
        r.xi = xi;
        r.iterations = it;
        if (!all_finite(s))
            return r;
        const VecN d = s.point.x - x;  // x_m - x
        const Matrix& A = s.point.dx;
        MatN M(n, n);
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                M(a, b) = A.col(a).dot(A.col(b));
        if (!(M.trace() > 0.0) || !std::isfinite(M.trace()))
            return r;  // zero tangents: no foot point here
        r.finite = true;
        r.distance = d.norm();
        const VecN g = A.transpose() * d;
        double offset = tangential_offset(M, g);
        if (n == 2) {
            const Eigen::Vector2d S = direction_scaling(M);
            if (S(0) == 0.0 || S(1) == 0.0) {
                // On a collapsed edge the parameter gradient misses the offset
                // along the vanishing tangent: measure it in space, against the
                // tangent plane of the limit normal.
                std::array<bool, 2> near_lower{true, true};
                for (int k = 0; k < 2; ++k) {
                    const std::vector<double>& kv = layout.knots[k]->knot_values();
                    near_lower[k] = xi(k) - kv[span[k]] <= kv[span[k] + 1] - xi(k);
                }
                const VecN normal = side_normal(A, s.point.d2x, 1, near_lower);
                if (normal.norm() > 0.0)
                    offset = std::max(offset, (d - d.dot(normal) * normal).norm());
            }
        }
        const double tol = options.tolerance * (surface_size + r.distance);
        if (polished == Polish::interior || (polished == Polish::none && offset <= negligible_fraction * tol)) {
            r.converged = true;
            r.sample = std::move(s);
            return r;
        }
        if (polished == Polish::on_bound)
            return stop_on_bound(std::move(s), g, offset, tol);
        if (it >= options.max_iterations) {
            r.converged = offset <= tol;
            r.sample = std::move(s);
            return r;
        }
        // Newton alone can cycle between two points where f is far from quadratic.
        // After safeguard_after iterations (plain Newton converges well before:
        // its paths, and the 2D results of the first release, stay the same), a
        // step that increased the distance beyond round-off is taken back and
        // tried again with half the trust region; accepted steps let it grow back.
        constexpr int safeguard_after = 10;
        constexpr double uphill_tie = 1e-14;  // a few ulps of the coordinates
        if (it > safeguard_after && accepted_xi &&
            r.distance > accepted_distance + uphill_tie * (surface_size + accepted_distance)) {
            xi = *accepted_xi;
            radius *= 0.5;
            continue;
        }
        if (accepted_xi && r.distance < accepted_distance)
            radius = std::min(1.0, 2.0 * radius);
        accepted_xi = xi;
        accepted_distance = r.distance;

        // Directions held by an active bound are fixed; Newton goes on in the others.
        std::vector<int> free;
        for (int k = 0; k < n; ++k)
            if (!pushed_out(xi(k), g(k), *piece[k]))
                free.push_back(k);
        if (free.empty())
            return stop_on_bound(std::move(s), g, offset, tol);  // a corner (or a 1D end)
        const bool on_edge = static_cast<int>(free.size()) < n;

        MatN H = M;
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                H(a, b) += d.dot(s.point.d2x.col(nurbs::second_column(n, a, b)));
        const MatN M_free = sub_matrix(M, free);
        MatN H_free = sub_matrix(H, free);
        VecN g_free(static_cast<Index>(free.size()));
        for (std::size_t i = 0; i < free.size(); ++i)
            g_free(static_cast<Index>(i)) = g(free[i]);
        if (on_edge && tangential_offset(M_free, g_free) <= negligible_fraction * tol)
            return stop_on_bound(std::move(s), g, offset, tol);  // converged along the edge
        if (!positive_definite(H_free, M_free))
            H_free = M_free;  // Gauss-Newton: the full Hessian would step towards a distance maximum
        const VecN newton_step = -pseudo_solve(H_free, g_free, M_free);

        // Trust region: scale the step so that no direction moves more than
        // max_step_fraction of its current span (the limiting one exactly that).
        double scale = 1.0;
        int limiting = -1;
        VecN max_step(static_cast<Index>(free.size()));
        for (std::size_t i = 0; i < free.size(); ++i) {
            const int k = free[i];
            const std::vector<double>& kv = layout.knots[k]->knot_values();
            max_step(static_cast<Index>(i)) = radius * options.max_step_fraction * (kv[span[k] + 1] - kv[span[k]]);
            const double step = std::abs(newton_step(static_cast<Index>(i)));
            if (step > max_step(static_cast<Index>(i)) && max_step(static_cast<Index>(i)) / step < scale) {
                scale = max_step(static_cast<Index>(i)) / step;
                limiting = static_cast<int>(i);
            }
        }
        VecN xi_new = xi;
        for (std::size_t i = 0; i < free.size(); ++i) {
            const int k = free[i];
            const double full = newton_step(static_cast<Index>(i));
            const double step = static_cast<int>(i) == limiting ? std::copysign(max_step(static_cast<Index>(i)), full)
                                                                : scale * full;
            xi_new(k) = std::clamp(xi(k) + step, piece[k]->lower, piece[k]->upper);
        }
        if (xi_new == xi) {
            // Pushed against a bound, or a step below the resolution of xi (in the
            // interior that is as converged as it gets).
            bool at_bound = on_edge;
            for (int k = 0; k < n; ++k)
                at_bound = at_bound || xi(k) == piece[k]->lower || xi(k) == piece[k]->upper;
            if (!at_bound) {
                r.converged = true;
                r.sample = std::move(s);
                return r;
            }
            return stop_on_bound(std::move(s), g, offset, tol);
        }
        // A full Newton step below tolerance: take it (quadratic convergence puts
        // the result near round-off) and stop after evaluating there.
        if (std::sqrt(std::max(0.0, newton_step.dot(M_free * newton_step))) <= tol)
            polished = on_edge ? Polish::on_bound : Polish::interior;
        xi = xi_new;
    }
}

/// Lower bound of the distance from x to element e: the distance to the box of
/// the control points whose basis functions are non-zero on it (the element lies
/// in their convex hull), less a round-off margin.
double element_distance_bound(const nurbs::Patch& surface, const Layout& layout, int e, const VecN& x)
{
    const std::array<int, 2> number = layout.span_numbers(e);
    const RowMatrix& cps = surface.control_points();
    const int d = surface.dim();
    VecN lower = VecN::Constant(d, std::numeric_limits<double>::infinity());
    VecN upper = -lower;
    const int n = layout.n_par;
    const int span_u = layout.knots[0]->span_start(number[0]), p_u = layout.knots[0]->degree();
    const int span_v = n > 1 ? layout.knots[1]->span_start(number[1]) : 0, p_v = n > 1 ? layout.knots[1]->degree() : 0;
    for (int j = span_v - p_v; j <= span_v; ++j)
        for (int i = span_u - p_u; i <= span_u; ++i) {
            const int a = surface.control_point_index({i, j, 0});
            lower = lower.cwiseMin(cps.row(a).transpose());
            upper = upper.cwiseMax(cps.row(a).transpose());
        }
    const VecN outside = (lower - x).cwiseMax(x - upper).cwiseMax(0.0);
    // Evaluated points may leave the hull by a few ulps of the coordinates.
    const double round_off = 64.0 * machine_eps * (x.cwiseAbs().maxCoeff() + upper.cwiseAbs().maxCoeff());
    return outside.norm() - round_off;
}

/// Start of Newton in a region: the nearest of (p+2) samples per direction on
/// each of its candidate elements, the region's centre if none. Ties go to the
/// first sample in (element, v sample, u sample) order. Elements are visited
/// nearest box first, and those whose box is farther than the best sample are
/// skipped: the same answer as sampling them all, at a fraction of the cost
/// when there are many candidates.
VecN nearest_sample(const nurbs::Patch& surface, const Layout& layout, int region, const VecN& x,
                    const std::vector<int>& region_elements)
{
    const int n = layout.n_par;
    VecN best_xi(n);
    for (int k = 0; k < n; ++k)
        best_xi(k) = 0.5 * (layout.piece(region, k).lower + layout.piece(region, k).upper);
    double best_dist = std::numeric_limits<double>::infinity();
    long long best_key = -1;
    std::array<int, 2> n_samples{1, 1};
    for (int k = 0; k < n; ++k)
        n_samples[k] = layout.knots[k]->degree() + 2;  // enough to separate the local minima of one span
    const int per_element = n_samples[0] * n_samples[1];
    constexpr double pole_shift = 0.25;  // in sample spacings

    std::vector<std::pair<double, int>> order;  // (distance bound, element)
    order.reserve(region_elements.size());
    for (const int e : region_elements)
        order.emplace_back(region_elements.size() > 1 ? element_distance_bound(surface, layout, e, x) : 0.0, e);
    std::sort(order.begin(), order.end());

    VecN xi(n);
    for (const auto& [bound, e] : order) {
        if (bound > best_dist)
            break;  // no sample of this element (or of a later one) is nearer
        const std::array<int, 2> number = layout.span_numbers(e);
        std::array<int, 3> span{0, 0, 0};
        for (int k = 0; k < n; ++k)
            span[k] = layout.knots[k]->span_start(number[k]);
        for (int jv = 0; jv < n_samples[1]; ++jv)
            for (int ju = 0; ju < n_samples[0]; ++ju) {
                const std::array<int, 2> j{ju, jv};
                for (int k = 0; k < n; ++k) {
                    const std::vector<double>& kv = layout.knots[k]->knot_values();
                    const double length = kv[span[k] + 1] - kv[span[k]];
                    double t = static_cast<double>(j[k]);
                    // A sample on a collapsed edge (a pole) has no direction along
                    // the edge to start from: take it a quarter spacing inside.
                    if (n == 2 && j[k] == 0 && layout.collapsed[k][0] && kv[span[k]] == layout.knots[k]->front())
                        t = pole_shift;
                    if (n == 2 && j[k] == n_samples[k] - 1 && layout.collapsed[k][1] &&
                        kv[span[k] + 1] == layout.knots[k]->back())
                        t = j[k] - pole_shift;
                    xi(k) = kv[span[k]] + length * t / (n_samples[k] - 1.0);
                }
                const Sample s = evaluate_on_spans(surface, span, xi, 0);
                const double dist = (s.point.x - x).norm();
                const long long key = static_cast<long long>(e) * per_element + jv * n_samples[0] + ju;
                if (dist < best_dist || (dist == best_dist && key < best_key)) {
                    best_dist = dist;
                    best_key = key;
                    best_xi = xi;
                }
            }
    }
    return best_xi;
}

bool is_better(const RegionResult& a, const RegionResult& b, double surface_size)
{
    return nearer_foot(a.distance, a.converged, b.distance, b.converged, surface_size);
}

Projection failed_projection(int d, int iterations, int candidates)
{
    const int n = d - 1;
    Projection p;
    p.status = Projection::Status::failed;
    p.xi = VecN::Zero(n);
    p.point = p.normal = VecN::Zero(d);
    p.tangents = Matrix::Zero(d, n);
    p.second = Matrix::Zero(d, n * (n + 1) / 2);
    p.metric = p.curvature = Matrix::Zero(n, n);
    p.iterations = iterations;
    p.candidates = candidates;
    return p;
}

}  // namespace

bool nearer_foot(double distance_a, bool orthogonal_a, double distance_b, bool orthogonal_b, double surface_size)
{
    constexpr double relative_tie = 1e-14;  // a few ulps of the coordinates
    const double tie = relative_tie * (surface_size + distance_b);
    if (distance_a < distance_b - tie)
        return true;
    return std::abs(distance_a - distance_b) <= tie && orthogonal_a && !orthogonal_b;
}

VecN side_normal(const Matrix& tangents, const Matrix& second, int sign, const std::array<bool, 2>& near_lower)
{
    const Index d = tangents.rows();
    if (d == 2) {
        const VecN t = tangents.col(0);
        if (!(t.norm() > 0.0) || !t.allFinite())
            return VecN::Zero(2);
        return curve_normal_2d(t, sign);
    }
    IGA_CHECK(d == 3 && tangents.cols() == 2 && second.cols() == 3, "contact: side normal needs d x (d-1) tangents");
    // A tangent below sqrt(eps) of the other is dominated by round-off (it is a
    // difference of equal control points): its limit direction +-x_m,12 is more
    // accurate than its computed value, to within the same sqrt(eps).
    const double collapse_ratio = std::sqrt(machine_eps);
    Eigen::Vector3d a1 = tangents.col(0), a2 = tangents.col(1);
    const Eigen::Vector3d mixed = second.col(1);
    if (a1.norm() < collapse_ratio * a2.norm())
        a1 = (near_lower[1] ? 1.0 : -1.0) * mixed;  // a_1 ~ (xi_2 - edge) x_m,12 next to the edge
    else if (a2.norm() < collapse_ratio * a1.norm())
        a2 = (near_lower[0] ? 1.0 : -1.0) * mixed;
    const Eigen::Vector3d c = a1.cross(a2);
    const double length = c.norm();
    if (!(length > 0.0) || !std::isfinite(length))
        return VecN::Zero(3);
    return VecN((static_cast<double>(sign) / length) * c);
}

Projection project_to_surface(const nurbs::Patch& surface, int outward_sign, const VecN& x,
                              const ProjectionOptions& options)
{
    const int d = surface.dim();
    const int n = surface.n_par();
    if ((d != 2 && d != 3) || n != d - 1)
        throw Error("contact: projection onto a side with n_par = " + std::to_string(n) + " in d = " +
                    std::to_string(d) + " is not supported (a curve in 2D or a surface in 3D)");
    IGA_CHECK(x.size() == d, "contact: projected point must have d coordinates");
    IGA_CHECK(outward_sign == 1 || outward_sign == -1, "contact: outward sign must be +1 or -1");
    IGA_CHECK(!options.start || options.start->size() == n, "contact: warm start must have d-1 parameters");

    const RowMatrix& cps = surface.control_points();
    const double surface_size = (cps.colwise().maxCoeff() - cps.colwise().minCoeff()).norm();
    const Layout layout(surface, surface_size);
    const int n_elements = layout.n_spans[0] * (n > 1 ? layout.n_spans[1] : 1);

    // Candidate elements grouped by region, ascending within each.
    const int n_regions = layout.n_pieces[0] * (n > 1 ? layout.n_pieces[1] : 1);
    std::vector<std::vector<int>> region_elements(n_regions);
    int n_candidates = 0;
    if (options.candidate_elements.empty()) {
        for (int e = 0; e < n_elements; ++e)
            region_elements[layout.region_of(e)].push_back(e);
        n_candidates = n_elements;
    } else {
        std::vector<char> is_candidate(n_elements, 0);
        for (const int e : options.candidate_elements) {
            IGA_CHECK(e >= 0 && e < n_elements, "contact: candidate element index out of range");
            is_candidate[e] = 1;
        }
        for (int e = 0; e < n_elements; ++e)
            if (is_candidate[e]) {
                region_elements[layout.region_of(e)].push_back(e);
                ++n_candidates;
            }
    }

    if (!x.allFinite() || !surface.control_points().allFinite())
        return failed_projection(d, 0, n_candidates);


    std::optional<VecN> start;
    if (options.start && options.start->allFinite()) {
        start = *options.start;
        for (int k = 0; k < n; ++k)
            (*start)(k) = std::clamp((*start)(k), layout.knots[k]->front(), layout.knots[k]->back());
    }
    const int start_region = options.start_element >= 0 && options.start_element < n_elements
                                 ? layout.region_of(options.start_element)
                                 : -1;

    int total_iterations = 0;
    std::optional<RegionResult> best;
    std::optional<RegionResult> unsettled;  // the nearest finite point of a Newton that did not settle
    for (int region = 0; region < n_regions; ++region) {
        if (region_elements[region].empty())
            continue;
        std::optional<RegionResult> result;
        if (start && (start_region < 0 ? layout.region_contains(region, *start) : start_region == region)) {
            RegionResult r = newton_in_region(surface, layout, region, x, *start, options, surface_size);
            total_iterations += r.iterations;
            if (r.finite && (r.converged || r.clamped))
                result = std::move(r);
        }
        // No warm start here, it failed, or it ran into a bound: (also) start
        // from the nearest sample.
        if (!result || result->clamped) {
            const VecN sample_start = nearest_sample(surface, layout, region, x, region_elements[region]);
            RegionResult r = newton_in_region(surface, layout, region, x, sample_start, options, surface_size);
            total_iterations += r.iterations;
            if (!r.finite || !(r.converged || r.clamped)) {
                if (r.finite && (!unsettled || r.distance < unsettled->distance))
                    unsettled = std::move(r);
                if (!result)
                    continue;  // another region may hold the foot
            } else if (!result || is_better(r, *result, surface_size)) {
                result = std::move(r);
            }
        }
        if (!best || is_better(*result, *best, surface_size))
            best = std::move(result);
    }
    const bool settled = best.has_value();
    if (!settled)
        best = std::move(unsettled);
    if (!best)
        return failed_projection(d, total_iterations, n_candidates);

    const Sample& s = best->sample;
    std::array<bool, 2> near_lower{true, true};
    std::array<int, 2> number{0, 0};
    for (int k = 0; k < n; ++k) {
        const std::vector<double>& kv = layout.knots[k]->knot_values();
        near_lower[k] = best->xi(k) - kv[s.span[k]] <= kv[s.span[k] + 1] - best->xi(k);
        number[k] = layout.knots[k]->span_number(s.span[k]);
    }
    const VecN normal = side_normal(s.point.dx, s.point.d2x, outward_sign, near_lower);
    if (!(normal.norm() > 0.0))
        return failed_projection(d, total_iterations, n_candidates);

    Projection p;
    p.xi = best->xi;
    p.element = layout.element_index(number);
    p.point = s.point.x;
    p.tangents = s.point.dx;
    p.second = s.point.d2x;
    p.normal = normal;
    p.metric = p.tangents.transpose() * p.tangents;
    p.curvature.resize(n, n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            p.curvature(a, b) = p.normal.dot(p.second.col(nurbs::second_column(n, a, b)));
    p.gap = normal_gap(x, p.point, p.normal);
    p.distance = best->distance;
    p.iterations = total_iterations;
    p.candidates = n_candidates;
    p.basis = std::move(best->sample.basis);
    if (!settled)
        p.status = Projection::Status::unsettled;
    else if (best->converged)
        p.status = Projection::Status::ok;
    else if (best->at_patch_end)
        p.status = Projection::Status::off_end;
    else
        p.status = Projection::Status::at_kink;
    return p;
}

}  // namespace iga::contact
