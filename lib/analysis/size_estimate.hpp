#pragma once
// The size of the model a deck asks for, estimated from the deck alone, BEFORE
// anything is built: a deck with spans: [1e8, 1e8] must be refused in a
// millisecond with a located message, not die minutes later of std::bad_alloc.
//
// Per deformable body and parametric direction i, from the deck's degree p_i and
// knots (or the built-in shape's: half_disc cubic x linear, quarter_disc quadratic x
// linear, rectangle bilinear, one span each) and the refinement in its order:
//   elevate t:  p_i += t, every distinct interior knot gains multiplicity t;
//   spans n:    at most n - 1 new knots and spans (refine_uniform);
//   insert k:   k more knots and at most k more spans.
// n_cp,i = p_i + 1 + (interior knots); dofs = d prod n_cp,i; elements = prod spans_i.
// A multi-patch body: the same per patch, after the body's refine and then the
// patch's own (analysis/multipatch.hpp), summed over the patches. Two things are
// left out: the knots and degrees that gluing propagates across interfaces
// (they need the geometry), and the sharing of interface control points (counted
// once per patch); the first can make a patch bigger than estimated, the second
// makes the sum bigger than the body, so neither is a bound in general.
// A contact surface of several patch sides counts each side's spans and control points.
// Memory (bytes, what the run holds at once; all counts in double precision, so no
// estimate overflows; closed forms in the deck's numbers, nothing proportional to
// the model is built, so a deck with spans: [1e8, 1e8] is judged in microseconds):
//   element geometry   elements * prod(p_i+1) Gauss points * (prod(p_i+1) (d+1) + 1) * 8
//   assembly positions elements * 4 (d prod(p_i+1))^2
//   element matrix     8 (d prod(p_i+1))^2 of the largest element, held while it is
//                      assembled (once: a lower bound for several threads); 6 GB at
//                      degree 20 in 3D
//   tangent + factor   2 * 12 * nonzeros, nonzeros of a patch = d^2 prod_i (n_i (2 p_i + 1)
//                      - p_i (p_i + 1)) (basis pairs sharing a span, simple knots: exact
//                      over all dofs, so above the free-dof pattern by the constrained rows)
//   contact            Gauss points (quadrature per span x spans of the side) * 64 d,
//                      plus the couplings' pattern blocks (sparse coupling), each taking
//                      4 (block dofs)^2 bytes of positions: against a rigid obstacle one
//                      per side element (no new tangent entries); between two deformable
//                      sides, assumed to face each other, each slave element meets
//                      w = 2 + 0.2 n master elements per side direction (n master spans
//                      per direction; the automatic search margin is a tenth of the
//                      larger side), so spans_s w^(d-1) blocks and 2 d^2 n_cp,s
//                      (w + p_m + p_s)^(d-1) new tangent entries (the larger of the two
//                      half passes; they find the same blocks). Measured on the inputs/
//                      decks: couplings within 4x, all nonzeros within 8 %
//   samples            samples_per_span x spans of each contact side * (2d+1) * 8 * 4
// Hard limits, whatever the memory (docs/deck.md): a degree above 20 after elevation,
// contact quadrature above 64 points per span, samples_per_span above 1000.
//
// check_size throws DeckError located at the key that makes the model too big
// (bodies.<name>.refine.spans, ...elevate, ...insert, bodies.<name>.nurbs.degrees,
// bodies.<name>.patches.<patch>.refine.spans, ..., bodies.<name>.patches.<patch>.nurbs.degrees,
// contact.<pair>.quadrature, output.samples_per_span), with the estimated memory and
// the machine's. The culprit among several keys is the one whose removal shrinks the
// estimate most. Nothing here allocates per planned increment (steps.count).

#include "io/deck.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

struct SizeLimits {
    double memory_bytes = 0.0;  ///< the memory this process may use; 0 = unknown (no memory check)
    std::string memory_name = "this machine's";  ///< whose limit memory_bytes is, for messages
    int max_degree = 20;
    int max_quadrature = 64;
    int max_samples_per_span = 1000;
};

/// Physical memory of this machine in bytes (sysconf: MemTotal), or 0 if unknown.
double machine_memory_bytes();

/// The limits for this process: the least of the machine's memory, its address-space
/// limit (ulimit -v) and its container's memory limit (cgroup v2 memory.max), and the
/// hard limits above.
SizeLimits machine_limits();

/// One patch after the body's and its own refinement.
struct PatchSize {
    std::string name;                    ///< "" for a single-patch body
    std::vector<double> degrees;         ///< after elevation
    std::vector<double> spans;           ///< per direction (upper bound)
    std::vector<double> control_points;  ///< per direction
    double dofs = 0.0;
    double elements = 0.0;
};

struct BodySize {
    std::string name;
    std::vector<PatchSize> patches;      ///< one per patch (one for a single-patch body)
    std::vector<double> degrees;         ///< per direction, the largest over the patches
    std::vector<double> spans;           ///< per direction, the largest over the patches
    std::vector<double> control_points;  ///< per direction, the largest over the patches
    double dofs = 0.0;                   ///< sum over the patches
    double elements = 0.0;               ///< sum over the patches
    double nonzeros = 0.0;
};

struct SizeEstimate {
    std::vector<BodySize> bodies;  ///< deformable bodies, deck order
    double dofs = 0.0;
    double nonzeros = 0.0;  ///< tangent entries: the bodies' (all dofs) plus the contact couplings'
    double element_gauss_points = 0.0;
    double contact_gauss_points = 0.0;
    double contact_couplings = 0.0;  ///< pattern blocks of the contact pairs (sparse coupling)
    double samples = 0.0;
    double bytes = 0.0;  ///< estimated memory
};

SizeEstimate estimate_size(const io::Deck& deck);

/// Throws DeckError (located, see above) if the deck's model breaks a hard limit or
/// its estimated memory exceeds limits.memory_bytes.
void check_size(const io::Deck& deck, const SizeLimits& limits = machine_limits());

}  // namespace iga::analysis
