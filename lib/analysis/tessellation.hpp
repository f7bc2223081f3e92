#pragma once
// Tessellation of a body for visualization (output.paraview): for each of its
// patches a grid of `per_span` cells per knot span in each direction
// (quadrilaterals in 2D, hexahedra in 3D, VTK node order), patch after patch in
// one mesh (points on an interface appear once per patch), with the basis at
// each grid point kept so that the displacement there is sum_A R_A u_A (A body
// nodes) for any state.

#include "analysis/scene.hpp"
#include "io/results_data.hpp"

#include <vector>

namespace iga::analysis {

struct TessellatedBody {
    io::Tessellation mesh;                 ///< points padded to 3 columns
    std::vector<std::vector<int>> indices; ///< per point: body nodes with non-zero basis
    std::vector<Vector> R;                 ///< per point: their basis values
    std::vector<VecN> parameters;          ///< per point: its parameter xi (n_par entries) on its patch
    std::vector<int> patch;                ///< per point: its patch
};

TessellatedBody tessellate(const BodyModel& body, int per_span);

/// n_t x 3 displacements at the tessellation points from the body's n_nodes x d displacements.
RowMatrix tessellation_displacement(const TessellatedBody& t, const RowMatrix& u);

}  // namespace iga::analysis
