// Set-up of a multi-patch body (analysis::build_body_patches: refinement, gluing,
// the thin-patch, overlap and connectivity checks), the part of a run before any
// element geometry, which must grow about linearly with the patches and elements:
//   disc/L   inputs/disc_on_plane_2d.yaml (five patches, graded knots) with every
//            span halved L times (--refine-levels L);
//   strip/N  N unit squares in a row, glued side by side.
// Run: bin/setup_benchmark
//
// Measured on the project machine (2 cores shared with other jobs, Release, GCC 12),
// CPU time per build, before (quadratic overlap check and interface search) and after
// (bounding-box tree of all elements, hash of side corners):
//   case         elements / patches   before     after
//   disc/0          8 474             63 ms      33 ms
//   disc/1         34 076            847 ms     130 ms
//   disc/2        136 664           13.2 s      543 ms
//   disc/3        547 376     ~200 s (extrap.)  2.5 s
//   strip/200         200            269 ms     2.7 ms
//   strip/2000       2000           26.8 s       29 ms
//   strip/20000     20000     ~45 min (extrap.) 0.30 s

#include "analysis/multipatch.hpp"
#include "io/deck_reader.hpp"

#include <benchmark/benchmark.h>

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {

using namespace iga;

void disc(benchmark::State& state)
{
    const io::Deck deck = io::read_deck(std::string(IGA_SOURCE_DIR) + "/inputs/disc_on_plane_2d.yaml");
    const io::Body& body = *deck.find_body("disc");
    std::size_t elements = 0;
    for (auto _ : state) {
        const analysis::BodyPatches built = analysis::build_body_patches(deck, body, static_cast<int>(state.range(0)));
        elements = 0;
        for (const nurbs::Patch& p : built.patches)
            elements += p.elements().size();
    }
    state.counters["elements"] = static_cast<double>(elements);
}

void strip(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    std::string text = "format: 1\nanalysis: {dimension: 2, plane: strain}\nmaterials: [{name: m, E: 1.0, nu: 0.3}]\n"
                       "bodies:\n  - name: strip\n    material: m\n    patches:\n";
    for (int k = 0; k < n; ++k)
        text += fmt::format("      - {{name: p{}, nurbs: {{degrees: [1, 1], knots: [[0, 0, 1, 1], [0, 0, 1, 1]], "
                            "control_points: [[{}, 0, 1], [{}, 0, 1], [{}, 1, 1], [{}, 1, 1]]}}}}\n",
                            k, k, k + 1, k, k + 1);
    const std::filesystem::path file = std::filesystem::temp_directory_path() / fmt::format("strip_{}.yaml", n);
    std::ofstream(file) << text;
    const io::Deck deck = io::read_deck(file.string());
    std::filesystem::remove(file);
    std::size_t interfaces = 0;
    for (auto _ : state)
        interfaces = analysis::build_body_patches(deck, deck.bodies.front()).topology.interfaces.size();
    state.counters["interfaces"] = static_cast<double>(interfaces);
}

}  // namespace

BENCHMARK(disc)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(strip)->Arg(200)->Arg(2000)->Arg(20000)->Unit(benchmark::kMillisecond);
