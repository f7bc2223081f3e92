// One residual + tangent evaluation of analysis::SceneSystem (the work of one
// Newton iteration outside the linear solve), on Lame's thick cylinder
// (inputs/lame_cylinder_2d.yaml, degree 2 x 2) at 8 .. 128 spans per direction,
// for small and finite kinematics. Reported per free DOF ("per_dof", seconds).
//
// Small kinematics caches the element stiffness on the first evaluation (done
// before timing), so its number is the steady state of later increments:
// copying the assembled K and f_int = K_e u_e per element. Finite kinematics
// evaluates every element (F, S, material and geometric tangent) and the
// follower pressure on the inner arc each time, at a small non-zero state.
// Run: bin/element_assembly_benchmark (threads: automatic, assembly/threads.hpp;
// the figures below predate the ThreadTeam loop and were taken with OpenMP).
//
// Measured on the project machine (2 cores shared with other jobs, Release,
// GCC 12, OMP_NUM_THREADS=2), per evaluation:
//   spans   free dofs   small            finite
//     8        180      0.016 ms (91 ns/dof)   0.75 ms (4.2 us/dof)
//    32      2 244      0.25 ms (112 ns/dof)   6.6 ms (2.9 us/dof)
//   128     33 540      9.5 ms (282 ns/dof)    115 ms (3.4 us/dof)
// Finite kinematics costs ~3 us per dof (element kernels), flat in the size;
// small kinematics is a matrix copy plus K_e u_e, memory bound at large sizes.
//
// element_stiffness_3d: one degree-2 element of the 3D sphere octant (81 dofs, 27
// points), measured 2026-11-27 on the same machine (another build running):
//   B^T D B per Gauss point (element_response)   656 us
//   gradient moments (small_strain_stiffness)     68 us   (9.7x; the flop count says ~7x)
// The moments are what assembles K0 once per small-kinematics run.
//
// element_response_finite_3d: the same element under finite kinematics, with and
// without the tangent (a line-search probe forms no K_e; its round-off floor comes from
// the cancellation bound, mechanics/element.hpp). Measured 2026-11-28 on the same
// machine (an igacontact run on the other core), median of 3:
//   with the tangent (a Newton iterate)           407 us
//   force only (a line-search or predictor probe) 105 us   (3.9x less)

#include "analysis/scene.hpp"
#include "analysis/system.hpp"
#include "io/deck_reader.hpp"
#include "mechanics/element.hpp"
#include "mechanics/small_strain_stiffness.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

namespace {

using namespace iga;

void evaluate_lame(benchmark::State& state, const std::string& kinematics)
{
    const int spans = static_cast<int>(state.range(0));
    const io::Deck deck = io::read_deck(std::string(IGA_SOURCE_DIR) + "/inputs/lame_cylinder_2d.yaml",
                                        {"analysis.kinematics=" + kinematics,
                                         "bodies.tube.refine.spans=[" + std::to_string(spans) + "," +
                                             std::to_string(spans) + "]"});
    analysis::Scene scene = analysis::build_scene(deck);
    RunContext context(nullptr, Verbosity::quiet);
    analysis::SceneSystem system(scene, context);

    const Index n = scene.dofs->n_free();
    Vector u(n);
    for (Index k = 0; k < n; ++k)
        u(k) = 1e-4 * std::sin(0.37 * static_cast<double>(k));  // ~ the size of the Lame solution
    solver::Evaluation out;
    system.evaluate(u, 1.0, true, out);  // warm-up: pattern allocation, small-kinematics stiffness cache
    if (!out.ok) {
        state.SkipWithError(out.message.c_str());
        return;
    }
    for (auto _ : state) {
        system.evaluate(u, 1.0, true, out);
        benchmark::DoNotOptimize(out.residual.data());
        benchmark::ClobberMemory();
    }
    state.counters["dofs"] = static_cast<double>(n);
    state.counters["per_dof"] = benchmark::Counter(static_cast<double>(n),
                                                   benchmark::Counter::kIsIterationInvariantRate |
                                                       benchmark::Counter::kInvert);
}

BENCHMARK_CAPTURE(evaluate_lame, small, std::string("small"))
    ->RangeMultiplier(2)
    ->Range(8, 128)
    ->UseRealTime()  // elements run in OpenMP threads: CPU time of the main thread would mislead
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(evaluate_lame, finite, std::string("finite"))
    ->RangeMultiplier(2)
    ->Range(8, 128)
    ->UseRealTime()  // elements run in OpenMP threads: CPU time of the main thread would mislead
    ->Unit(benchmark::kMillisecond);

/// One small-strain element stiffness of the 3D sphere octant (degree 2: 27 functions,
/// 27 Gauss points): B^T D B point by point (element_response) against the gradient
/// moments (small_strain_stiffness).
void element_stiffness_3d(benchmark::State& state, bool moments)
{
    const io::Deck deck = io::read_deck(std::string(IGA_SOURCE_DIR) + "/inputs/hertz_sphere_plane_3d.yaml");
    const analysis::Scene scene = analysis::build_scene(deck);
    const analysis::BodyModel& body = scene.bodies.front();
    const mechanics::ElementGeometry& element = body.elements.front();
    const Matrix zero = Matrix::Zero(element.n_local(), element.dim);
    for (auto _ : state) {
        const Matrix K = moments ? mechanics::small_strain_stiffness(element, body.material)
                                 : mechanics::element_response(element, body.material, mechanics::Kinematics::small,
                                                               zero)
                                       .K;
        benchmark::DoNotOptimize(K.data());
    }
}
BENCHMARK_CAPTURE(element_stiffness_3d, b_transpose_d_b, false)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(element_stiffness_3d, gradient_moments, true)->Unit(benchmark::kMicrosecond);

/// One finite-strain response of the same element at a small non-zero displacement, with
/// the tangent (a Newton iterate) and without it (a line-search probe: f_int and the
/// round-off's cancellation bound, no K_e).
void element_response_finite_3d(benchmark::State& state, bool need_tangent)
{
    const io::Deck deck = io::read_deck(std::string(IGA_SOURCE_DIR) + "/inputs/hertz_sphere_plane_3d.yaml");
    const analysis::Scene scene = analysis::build_scene(deck);
    const analysis::BodyModel& body = scene.bodies.front();
    const mechanics::ElementGeometry& element = body.elements.front();
    Matrix u(element.n_local(), element.dim);
    for (Index a = 0; a < u.rows(); ++a)
        for (Index i = 0; i < u.cols(); ++i)
            u(a, i) = 1e-3 * std::sin(0.37 * static_cast<double>(a * u.cols() + i));
    for (auto _ : state) {
        const mechanics::ElementResponse r =
            mechanics::element_response(element, body.material, mechanics::Kinematics::finite, u, need_tangent);
        benchmark::DoNotOptimize(r.f_int.data());
    }
}
BENCHMARK_CAPTURE(element_response_finite_3d, with_tangent, true)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(element_response_finite_3d, force_only, false)->Unit(benchmark::kMicrosecond);

}  // namespace
