// Cost of evaluating the rational basis per parameter point, degrees 1-5, for
// a curve and a surface patch (8 non-uniform spans per direction, random
// weights), with values only, first, and second derivatives.
// Run: bin/basis_benchmark [--benchmark_filter=Surface]

#include "nurbs/patch.hpp"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using iga::RowMatrix;
using iga::VecN;
using iga::Vector;
using iga::nurbs::KnotVector;
using iga::nurbs::Patch;

KnotVector make_knots(int p, int n_spans)
{
    std::vector<double> knots(p + 1, 0.0);
    for (int k = 1; k < n_spans; ++k)
        knots.push_back((k + 0.3 * (k % 2)) / (n_spans + 0.3));  // non-uniform
    knots.insert(knots.end(), p + 1, 1.0);
    return KnotVector(p, std::move(knots));
}

Patch make_patch(int p, int n_par)
{
    std::vector<KnotVector> knots(n_par, make_knots(p, 8));
    int n_cp = 1;
    for (const auto& k : knots)
        n_cp *= k.n_basis();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> weight(0.5, 2.0);
    Vector w(n_cp);
    for (int a = 0; a < n_cp; ++a)
        w(a) = weight(rng);
    return Patch(std::move(knots), RowMatrix::Random(n_cp, 2), std::move(w));
}

std::vector<VecN> make_points(int n_par, int n)
{
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<VecN> points;
    for (int i = 0; i < n; ++i) {
        VecN xi(n_par);
        for (int d = 0; d < n_par; ++d)
            xi(d) = unit(rng);
        points.push_back(xi);
    }
    return points;
}

void run(benchmark::State& state, int n_par)
{
    const int degree = static_cast<int>(state.range(0));
    const int n_derivs = static_cast<int>(state.range(1));
    const Patch patch = make_patch(degree, n_par);
    const std::vector<VecN> points = make_points(n_par, 256);
    std::size_t i = 0;
    for (auto _ : state) {
        const iga::nurbs::BasisValues b = iga::nurbs::rational_basis(patch, points[i++ % points.size()], n_derivs);
        benchmark::DoNotOptimize(b.R.data());
    }
    state.SetItemsProcessed(state.iterations());
}

void curve_basis(benchmark::State& state) { run(state, 1); }
void surface_basis(benchmark::State& state) { run(state, 2); }

void univariate_basis(benchmark::State& state)
{
    const int degree = static_cast<int>(state.range(0));
    const KnotVector knots = make_knots(degree, 8);
    const std::vector<VecN> points = make_points(1, 256);
    Eigen::MatrixXd ders;
    std::size_t i = 0;
    for (auto _ : state) {
        const double u = points[i++ % points.size()](0);
        iga::nurbs::basis_derivatives_into(knots, knots.find_span(u), u, 2, ders);
        benchmark::DoNotOptimize(ders.data());
    }
    state.SetItemsProcessed(state.iterations());
}

}  // namespace

// Args: {degree, n_derivs}.
BENCHMARK(univariate_basis)->DenseRange(1, 5);
BENCHMARK(curve_basis)->ArgsProduct({{1, 2, 3, 4, 5}, {0, 1, 2}});
BENCHMARK(surface_basis)->ArgsProduct({{1, 2, 3, 4, 5}, {0, 1, 2}});
