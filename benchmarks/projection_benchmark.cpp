// Closest-point projection onto NURBS surfaces in 3D: the local iteration of
// lib/contact/projection (Newton on f = 1/2 |x - x_m(xi)|^2 with the full
// Hessian) against the second-order geometric iteration of Hu & Wallner
// ("A second order algorithm for orthogonal projection onto curves and
// surfaces", CAGD 22, 2005: first-order tangent-plane step, then its length
// corrected on the osculating circle of the normal section in that direction),
// and the full project_to_surface (samples + Newton, or a warm start).
// Surfaces: a rational sphere octant (4 x 4 spans) and a rational wavy
// free-form surface (6 x 6 spans), each in degree 2 and degree 4. Points lie
// within +-0.05 of the surface along its normal over the interior of the domain.
// Starts: "warm" = the foot parameters moved by up to 0.03 (a previous foot
// point), "cold" = the nearest point of a 13 x 13 parameter grid.
// Both local iterations evaluate the same rational basis (value, first and second
// derivatives) once per iteration and stop at the same tolerance; the counter
// `iterations` is the mean number of evaluations per projection, `failures` the
// fraction not converged in 50 iterations. Time is per projection.
// Search: ElementSearch on the degree 2 sphere octant with n x n elements, its
// construction (`search_build`) and one query at a point within 0.01 of the
// surface (`search_query`, counter `candidates`): O(n^2 log n) and O(log n + k).
// Run: bin/projection_benchmark [--benchmark_filter=HuWallner]

#include "contact/projection.hpp"
#include "contact/search.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/refine.hpp"

#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using iga::Matrix;
using iga::RowMatrix;
using iga::VecN;
using iga::Vector;
using iga::nurbs::KnotVector;
using iga::nurbs::Patch;

constexpr double tolerance = 1e-12;  // as ProjectionOptions::tolerance (relative to size + distance)
constexpr int max_iterations = 50;

Patch sphere_octant(int degree)
{
    const double s = std::sqrt(0.5);
    const double pts[3][2] = {{1, 0}, {1, 1}, {0, 1}};
    const double w[3] = {1, s, 1};
    RowMatrix P(9, 3);
    Vector weights(9);
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            P.row(i + 3 * j) << pts[j][0] * pts[i][0], pts[j][0] * pts[i][1], pts[j][1];
            weights(i + 3 * j) = w[i] * w[j];
        }
    const KnotVector q(2, {0, 0, 0, 1, 1, 1});
    Patch patch({q, q}, P, weights);
    for (int dir = 0; dir < 2; ++dir) {
        patch = iga::nurbs::elevate_degree(patch, dir, degree - 2);
        patch = iga::nurbs::refine_uniform(patch, dir, 4);
    }
    return patch;
}

Patch wavy_surface(int degree)
{
    const int n_spans = 6;
    std::vector<double> knots(degree + 1, 0.0);
    for (int k = 1; k < n_spans; ++k)
        knots.push_back(static_cast<double>(k) / n_spans);
    knots.insert(knots.end(), degree + 1, 1.0);
    const KnotVector kv(degree, knots);
    const int n = kv.n_basis();
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    RowMatrix P(n * n, 3);
    Vector w(n * n);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = 2.0 * i / (n - 1.0), y = 2.0 * j / (n - 1.0);
            P.row(i + n * j) << x, y, 0.3 * std::sin(3.0 * x) * std::cos(2.0 * y) + 0.02 * unit(rng);
            w(i + n * j) = 1.0 + 0.3 * unit(rng);
        }
    return Patch({kv, kv}, P, w);
}

struct Case {
    Patch surface;
    std::vector<VecN> points;
    std::vector<VecN> warm_starts;
    std::vector<VecN> cold_starts;
    double size = 0.0;
};

Case make_case(Patch surface)
{
    Case c{std::move(surface), {}, {}, {}, 0.0};
    const RowMatrix& cps = c.surface.control_points();
    c.size = (cps.colwise().maxCoeff() - cps.colwise().minCoeff()).norm();
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> param(0.1, 0.9), offset(-0.05, 0.05), shift(-0.03, 0.03);
    constexpr int n_grid = 13;
    std::vector<std::pair<VecN, VecN>> grid;  // (xi, x)
    for (int j = 0; j < n_grid; ++j)
        for (int i = 0; i < n_grid; ++i) {
            VecN xi(2);
            xi << i / (n_grid - 1.0), j / (n_grid - 1.0);
            grid.emplace_back(xi, iga::nurbs::evaluate(c.surface, xi, 0).x);
        }
    for (int k = 0; k < 256; ++k) {
        VecN xi(2);
        xi << param(rng), param(rng);
        const iga::nurbs::PointDerivatives e = iga::nurbs::evaluate(c.surface, xi, 1);
        const Eigen::Vector3d n = Eigen::Vector3d(e.dx.col(0)).cross(Eigen::Vector3d(e.dx.col(1))).normalized();
        const VecN x = e.x + offset(rng) * VecN(n);
        c.points.push_back(x);
        VecN warm = xi;
        warm(0) = std::clamp(warm(0) + shift(rng), 0.0, 1.0);
        warm(1) = std::clamp(warm(1) + shift(rng), 0.0, 1.0);
        c.warm_starts.push_back(warm);
        double best = 1e300;
        VecN cold = xi;
        for (const auto& [gxi, gx] : grid)
            if ((gx - x).norm() < best) {
                best = (gx - x).norm();
                cold = gxi;
            }
        c.cold_starts.push_back(cold);
    }
    return c;
}

const Case& get_case(int surface, int degree)
{
    static const Case cases[2][2] = {{make_case(sphere_octant(2)), make_case(sphere_octant(4))},
                                     {make_case(wavy_surface(2)), make_case(wavy_surface(4))}};
    return cases[surface][degree == 2 ? 0 : 1];
}

struct LocalResult {
    int iterations = 0;
    bool converged = false;
};

void clamp_to_domain(VecN& xi)
{
    xi(0) = std::clamp(xi(0), 0.0, 1.0);
    xi(1) = std::clamp(xi(1), 0.0, 1.0);
}

/// Newton on grad f = 0 with the full Hessian (Gauss-Newton when indefinite), as
/// in lib/contact/projection.cpp without its bounds and trust region.
LocalResult newton(const Patch& s, const VecN& x, VecN xi, double size)
{
    for (int it = 1; it <= max_iterations; ++it) {
        const iga::nurbs::PointDerivatives e = iga::nurbs::evaluate(s, xi, 2);
        const VecN r = e.x - x;
        const Eigen::Matrix2d M = e.dx.transpose() * e.dx;
        Eigen::Matrix2d H = M;
        H(0, 0) += r.dot(e.d2x.col(0));
        H(0, 1) += r.dot(e.d2x.col(1));
        H(1, 0) += r.dot(e.d2x.col(1));
        H(1, 1) += r.dot(e.d2x.col(2));
        if (!(H.determinant() > 0.0 && H(0, 0) > 0.0))
            H = M;
        const Eigen::Vector2d g = e.dx.transpose() * r;
        const Eigen::Vector2d step = -H.ldlt().solve(g);
        xi += VecN(step);
        clamp_to_domain(xi);
        if ((e.dx * step).norm() <= tolerance * (size + r.norm()))
            return {it, true};
    }
    return {max_iterations, false};
}

/// Hu & Wallner's second-order geometric iteration.
LocalResult hu_wallner(const Patch& s, const VecN& x, VecN xi, double size)
{
    for (int it = 1; it <= max_iterations; ++it) {
        const iga::nurbs::PointDerivatives e = iga::nurbs::evaluate(s, xi, 2);
        const Eigen::Vector3d c = e.x, r = Eigen::Vector3d(x) - c;
        const Eigen::Vector3d a1 = e.dx.col(0), a2 = e.dx.col(1);
        const Eigen::Vector3d n = a1.cross(a2).normalized();
        const Eigen::Matrix2d M = e.dx.transpose() * e.dx;
        // First order: the foot of x in the tangent plane, in parameters.
        const Eigen::Vector2d d1 = M.ldlt().solve(Eigen::Vector2d(e.dx.transpose() * VecN(r)));
        const Eigen::Vector3d t = a1 * d1(0) + a2 * d1(1);
        const double length = t.norm();
        if (length <= tolerance * (size + r.norm()))
            return {it, true};
        // Normal curvature of the section in direction t, and its osculating circle.
        const double b = n.dot(Eigen::Vector3d(e.d2x.col(0))) * d1(0) * d1(0) +
                         2.0 * n.dot(Eigen::Vector3d(e.d2x.col(1))) * d1(0) * d1(1) +
                         n.dot(Eigen::Vector3d(e.d2x.col(2))) * d1(1) * d1(1);
        const double kappa = b / (length * length);
        Eigen::Vector2d step = d1;
        if (std::abs(kappa) * length > 1e-12) {
            const Eigen::Vector3d th = t / length;
            const Eigen::Vector3d m = c + n / kappa;
            const Eigen::Vector3d in_plane = c + r.dot(th) * th + r.dot(n) * n;  // x in the normal section plane
            const Eigen::Vector3d w = in_plane - m;
            if (w.norm() > 0.0) {
                const Eigen::Vector3d q = m + w.normalized() / std::abs(kappa);
                const Eigen::Vector3d u0 = c - m, u1 = q - m;
                const double angle = std::atan2(u0.cross(u1).norm(), u0.dot(u1));
                const double arc = angle / std::abs(kappa) * ((q - c).dot(th) >= 0.0 ? 1.0 : -1.0);
                step = d1 * (arc / length);
            }
        }
        xi += VecN(step);
        clamp_to_domain(xi);
    }
    return {max_iterations, false};
}

enum class Method { newton, hu_wallner };

void local(benchmark::State& state, int surface, Method method, bool warm)
{
    const int degree = static_cast<int>(state.range(0));
    const Case& c = get_case(surface, degree);
    const std::vector<VecN>& starts = warm ? c.warm_starts : c.cold_starts;
    long long iterations = 0, failures = 0, projections = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        const LocalResult r = method == Method::newton ? newton(c.surface, c.points[k], starts[k], c.size)
                                                       : hu_wallner(c.surface, c.points[k], starts[k], c.size);
        benchmark::DoNotOptimize(r);
        iterations += r.iterations;
        failures += r.converged ? 0 : 1;
        ++projections;
        k = (k + 1) % c.points.size();
    }
    state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(projections);
    state.counters["failures"] = static_cast<double>(failures) / static_cast<double>(projections);
}

void full(benchmark::State& state, int surface, bool warm)
{
    const int degree = static_cast<int>(state.range(0));
    const Case& c = get_case(surface, degree);
    long long iterations = 0, failures = 0, projections = 0, candidates = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        iga::contact::ProjectionOptions options;
        if (warm)
            options.start = c.warm_starts[k];
        const iga::contact::Projection p = iga::contact::project_to_surface(c.surface, +1, c.points[k], options);
        benchmark::DoNotOptimize(p);
        iterations += p.iterations;
        candidates += p.candidates;
        failures += p.status == iga::contact::Projection::Status::ok ? 0 : 1;
        ++projections;
        k = (k + 1) % c.points.size();
    }
    state.counters["iterations"] = static_cast<double>(iterations) / static_cast<double>(projections);
    state.counters["candidates"] = static_cast<double>(candidates) / static_cast<double>(projections);
    state.counters["failures"] = static_cast<double>(failures) / static_cast<double>(projections);
}

Patch sphere_elements(int n_spans)
{
    Patch patch = sphere_octant(2);  // 4 x 4 spans
    for (int dir = 0; dir < 2; ++dir)
        patch = iga::nurbs::refine_uniform(patch, dir, n_spans);
    return patch;
}

void search_build(benchmark::State& state)
{
    const Patch patch = sphere_elements(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const iga::contact::ElementSearch search(patch, iga::contact::SearchOptions{.distance = 0.01});
        benchmark::DoNotOptimize(search.bounds());
    }
    state.counters["elements"] = static_cast<double>(patch.elements().size());
}

void search_query(benchmark::State& state)
{
    const Patch patch = sphere_elements(static_cast<int>(state.range(0)));
    const iga::contact::ElementSearch search(patch, iga::contact::SearchOptions{.distance = 0.01});
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> angle(0.0, 1.57), radius(0.99, 1.01);
    std::vector<VecN> points;
    for (int k = 0; k < 256; ++k) {
        const double t = angle(rng), f = angle(rng), r = radius(rng);
        VecN x(3);
        x << r * std::sin(t) * std::cos(f), r * std::sin(t) * std::sin(f), r * std::cos(t);
        points.push_back(x);
    }
    std::vector<int> out;
    long long hits = 0, queries = 0;
    std::size_t k = 0;
    for (auto _ : state) {
        search.candidates(points[k], out);
        hits += static_cast<long long>(out.size());
        ++queries;
        k = (k + 1) % points.size();
    }
    state.counters["elements"] = static_cast<double>(search.n_elements());
    state.counters["candidates"] = static_cast<double>(hits) / static_cast<double>(queries);
}

BENCHMARK(search_build)->Arg(8)->Arg(32)->Arg(128);
BENCHMARK(search_query)->Arg(8)->Arg(32)->Arg(128);

constexpr int sphere = 0, wavy = 1;

BENCHMARK_CAPTURE(local, Sphere_Newton_warm, sphere, Method::newton, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Sphere_HuWallner_warm, sphere, Method::hu_wallner, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Sphere_Newton_cold, sphere, Method::newton, false)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Sphere_HuWallner_cold, sphere, Method::hu_wallner, false)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Wavy_Newton_warm, wavy, Method::newton, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Wavy_HuWallner_warm, wavy, Method::hu_wallner, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Wavy_Newton_cold, wavy, Method::newton, false)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(local, Wavy_HuWallner_cold, wavy, Method::hu_wallner, false)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(full, Sphere_project_to_surface_warm, sphere, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(full, Sphere_project_to_surface_all_elements, sphere, false)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(full, Wavy_project_to_surface_warm, wavy, true)->Arg(2)->Arg(4);
BENCHMARK_CAPTURE(full, Wavy_project_to_surface_all_elements, wavy, false)->Arg(2)->Arg(4);

}  // namespace
