#pragma once
// What one run writes to its results file (docs/results.md, version 1),
// as plain structs with no HDF5 types: analysis/ fills them, io::ResultsWriter
// stores them. Names follow the groups and datasets of results.md.
//
// Shapes (row-major, d = spatial dimension 2 or 3, all reals float64):
//   control_points n_cp x (d+1) (x, y[, z], w); displacement n_cp x d;
//   Gauss-point coordinates n_g x d, parameter n_g x (d-1) (written 1-D in 2D);
//   postprocessed coordinates n_s x d; convergence n x 4.
// Sign convention: gap > 0 means penetration (contact/gap.hpp).

#include "core/types.hpp"

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace iga::io {

/// One patch of a multi-patch body: /bodies/<body>/patches/<name>/.
struct PatchGeometry {
    std::string name;
    std::vector<int> degrees;
    std::vector<std::vector<double>> knots;
    RowMatrix control_points;  ///< n_cp x (d+1)
};

/// The analysed (refined) geometry of one deformable body: /bodies/<name>/.
/// A multi-patch body lists its patches (and leaves degrees, knots and
/// control_points empty).
struct BodyGeometry {
    std::string name;
    std::vector<PatchGeometry> patches;      ///< multi-patch bodies only
    std::vector<int> degrees;                ///< one per parametric direction
    std::vector<std::vector<double>> knots;  ///< knots[0] = u, knots[1] = v (, knots[2] = w)
    RowMatrix control_points;                ///< n_cp x (d+1): x, y[, z], w
    /// Optional, for built-in shapes: (name, side) pairs, written as an n x 2 string dataset "side_names".
    std::vector<std::pair<std::string, std::string>> side_names;
};

/// Per-Gauss-point contact data of one side: .../gauss_points/.
struct GaussPointData {
    RowMatrix coordinates;            ///< n_g x d, current configuration
    RowMatrix reference_coordinates;  ///< n_g x d, reference configuration
    RowMatrix parameter;              ///< n_g x (d-1); written as a 1-D dataset of length n_g when d-1 == 1
    Vector gap;                       ///< n_g, normal gap g_N (positive = penetration)
    Vector pressure;                  ///< n_g, contact pressure <lambda + eps_N g_N> (lambda = 0: penalty)
    Vector weight;                    ///< n_g, quadrature weight times Jacobian (extra; written when non-empty)
    Vector multiplier;                ///< n_g, augmented-Lagrangian multipliers lambda (written when non-empty)
    // Friction (written when the pair has friction): the tangential traction on this
    // side in the local tangent basis (n_g x (d-1)) and in space (n_g x d), the state
    // (0 open, 1 stick, 2 slip), the slip length of this increment and accumulated.
    RowMatrix tangential_traction;
    RowMatrix tangential_traction_vector;
    std::vector<int> status;
    Vector slip_increment;
    Vector slip;
    Vector elastic_slip;              ///< n_g, |t_T - lambda_T| / eps_T (augmented Lagrangian; written when non-empty)
    /// Surfaces of several patch sides: n_g, the index into ContactSideResult::patch_sides
    /// of each Gauss point's patch side (gauss_points/patch, int); empty otherwise.
    std::vector<int> patch;
};

/// Recovered pressure of one side (Sauer's weighted averages): .../postprocessed/.
struct PostProcessedData {
    Vector control_point_pressure;    ///< n_cp_side, p_A
    RowMatrix coordinates;            ///< n_s x d, sample points, current configuration
    RowMatrix reference_coordinates;  ///< n_s x d, the same points, reference configuration
    Vector pressure;                  ///< n_s, sum_A R_A p_A at the sample points
    /// Friction: the tangential traction recovered the same way, per component, in the
    /// local tangent basis (n_s x (d-1)) and in space (n_s x d); empty without friction.
    RowMatrix tangential_traction;
    RowMatrix tangential_traction_vector;
    /// Surface sides (3D): the samples form an n_v x n_u grid (u fastest), written as
    /// the attribute grid_shape = [n_v, n_u] of postprocessed/; {0, 0} on curves.
    std::array<long long, 2> grid{0, 0};
    /// Surfaces of several patch sides: the samples are stored patch side after patch
    /// side, each its own grid [n_v, n_u] (a curve: [1, n]), written as the int dataset
    /// patch_grid_shape (n_patches x 2) of postprocessed/ (and no grid_shape); empty otherwise.
    std::vector<std::array<long long, 2>> patch_grids;
};

/// One side of a contact pair that carries Gauss points: contact/<pair>/<body.side>/.
struct ContactSideResult {
    std::string side_name;  ///< "body.side", e.g. "cylinder.v0"
    /// Surfaces of several patch sides: their names in the surface's order ("left.v0",
    /// ...), written as the string dataset patch_sides; empty for one side.
    std::vector<std::string> patch_sides;
    GaussPointData gauss_points;
    PostProcessedData postprocessed;
    double normal_force = 0.0;                ///< resultant of the contact pressure on this side
    /// Friction: the resultant of the tangential traction on this side (the force the
    /// contact exerts on its body, d); empty without friction.
    std::vector<double> friction_force;
    std::map<std::string, double> attributes;  ///< extra numbers (n_active, max_penetration, ...)
};

/// One contact pair: contact/<pair>/.
struct ContactPairResult {
    std::string name;
    std::vector<ContactSideResult> sides;
    std::map<std::string, double> attributes;  ///< extra numbers (candidates, projections, penalty, ...)
    std::map<std::string, std::string> text_attributes;  ///< extra words (enforcement, penalty_rule)
    /// d-vector, pairs with a rigid obstacle: the force the body's contact pressure exerts
    /// ON the obstacle (attribute obstacle_force); empty for two deformable sides.
    std::vector<double> obstacle_force;
};

/// Stress fields of one body at its tessellation points (output.fields): steps/<kkkk>/fields/<body>/.
struct BodyFields {
    std::string body;
    RowMatrix reference_coordinates;  ///< n_t x d
    RowMatrix displacement;           ///< n_t x d
    RowMatrix stress;                 ///< n_t x 6: Cauchy xx, yy, zz, xy, yz, xz (2D: yz = xz = 0)
    Vector von_mises;                 ///< n_t
};

/// Total reaction of one constrained side (or named surface), of a body or of one
/// constraint item: steps/<kkkk>/reactions/<name>.
struct Reaction {
    std::string name;            ///< path under reactions/: "block.v0", "total/block" or "items/0"
    std::vector<double> force;   ///< d: force the constraint exerts on the body (sum over its constrained dofs)
};

/// A body tessellated for visualization (ParaView, output.paraview): /paraview/<body>/.
struct Tessellation {
    std::string body;
    RowMatrix points;        ///< n_t x d, reference configuration
    std::vector<int> cells;  ///< n_cells * nodes_per_cell point indices (quads in 2D, hexahedra in 3D)
    int nodes_per_cell = 4;
};

/// One converged increment: /steps/<kkkk>/.
struct StepData {
    int index = 0;  ///< 1-based; the group name is index with at least 4 digits
    double load_factor = 0.0;
    int newton_iterations = 0;
    double residual_norm = 0.0;
    int cutbacks = 0;
    double wall_s = 0.0;
    int uzawa_updates = -1;  ///< augmented-Lagrangian updates of the increment; written when >= 0 (contact)
    std::vector<std::pair<std::string, RowMatrix>> displacement;  ///< (body, n_cp x d) per single-patch body
    /// Multi-patch bodies: (body, [(patch, n_cp of the patch x d)]) -> displacement/<body>/<patch>.
    std::vector<std::pair<std::string, std::vector<std::pair<std::string, RowMatrix>>>> patch_displacement;
    std::vector<ContactPairResult> contact;
    /// Displacements at the tessellation points (output.paraview): steps/<kkkk>/paraview/<body>/displacement.
    std::vector<std::pair<std::string, RowMatrix>> tessellation_displacement;
    std::vector<Reaction> reactions;  ///< constrained sides (deck order), then total/<body>, then items/<k>
    std::vector<BodyFields> fields;   ///< output.fields: one per deformable body
};

/// One row of /history, appended for EVERY converged increment (also when only the
/// last increment is stored under /steps).
struct HistoryRow {
    double load_factor = 0.0;
    int uzawa_updates = -1;  ///< history/uzawa_updates (n), written when the first row has it (>= 0)
    std::vector<Reaction> reactions;  ///< history/reactions/<name>: n x d
    struct ContactSide {
        std::string pair;               ///< history/contact/<pair>/<side>/...
        std::string side;               ///< "body.side"
        double normal_force = 0.0;
        double max_penetration = 0.0;
        std::vector<double> friction_force;  ///< d; zeros without friction
        double contact_area = 0.0;           ///< length (2D) or area (3D) in contact
    };
    std::vector<ContactSide> contact;
};

/// An analytic reference curve and this run's errors against it: /reference/<pair>/.
struct ReferenceData {
    std::string pair;
    std::string type;  ///< deck spelling, e.g. "hertz_cylinder_plane"
    double a = 0.0;    ///< contact half-width
    double p0 = 0.0;   ///< peak pressure
    std::map<std::string, double> inputs;  ///< radius, force, E_star, ...: one attribute each
    std::map<std::string, double> errors;  ///< peak, half_width, l2, ...: one attribute each
    RowMatrix coordinates;                 ///< n x d, points of the curve
    Vector x;                              ///< n, signed distance along the contact line (dataset "x")
    Vector pressure;                       ///< n
    std::vector<double> center;            ///< d, where x = 0 (attribute; written when non-empty)
    std::vector<double> tangent;           ///< d, direction of the contact line (attribute; when non-empty)
    std::vector<double> normal;            ///< 3D point contact: normal of the contact plane (attribute; when non-empty)
};

/// What finish() writes once the run is over.
struct RunSummary {
    std::string status;   ///< "completed" | "failed" | "running"
    std::string message;  ///< why, when failed
    std::string warnings; ///< root attribute "warnings": one line per warning, "" when none
    int ranks = 1;        ///< root attribute "ranks": the MPI ranks of the run
    std::string linear_solver;  ///< root attribute "linear_solver": backend and method, for the record
    /// /parallel/<name>: one value per rank (elements_per_rank, couplings_per_rank); empty on one process
    std::map<std::string, std::vector<double>> parallel;
    std::map<std::string, double> timings;      ///< seconds: total, assembly, contact_search, ... -> /timings
    std::map<std::string, long long> counters;  ///< -> attributes of /counters (int64)
    RowMatrix convergence;                      ///< n x 4: increment, iteration, residual_norm, load_factor
    std::vector<ReferenceData> references;
};

}  // namespace iga::io
