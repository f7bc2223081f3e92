#pragma once
// XDMF (version 2) index of a results file, for ParaView (output.paraview).
//
// The XDMF file holds no data: it points into the HDF5 results file (by file
// name, so the two must sit in the same folder) and describes a temporal
// collection with one spatial collection per stored increment:
//   - each body: its tessellation (/paraview/<body>/points, n_t x 3; cells,
//     quadrilaterals in 2D, hexahedra in 3D) with the node attribute
//     "displacement" (/steps/<kkkk>/paraview/<body>/displacement, n_t x 3):
//     apply ParaView's "Warp By Vector" to see the deformed shape; with
//     output.fields also the node attributes "stress_xx", "stress_yy",
//     "stress_zz", "stress_xy", "stress_yz", "stress_xz" (each a HyperSlab,
//     one column of /steps/<kkkk>/fields/<body>/stress, n_t x 6 in the order
//     xx, yy, zz, xy, yz, xz) and "von_mises" (fields/<body>/von_mises, n_t).
//     Six scalars rather than one "Tensor6": XDMF's Tensor6 order is xx, xy,
//     xz, yy, yz, zz, not the file's, and ParaView colours by scalars directly;
//   - each contact side carrying Gauss points: the Gauss points (a
//     polyvertex at gauss_points/coordinates, current configuration) with
//     "pressure" and "gap", and the post-processed curve (a polyline at
//     postprocessed/coordinates) or face sample grid (a 2DSMesh) with "pressure".
//     A surface of several patch sides (results.md: samples stored patch side
//     after patch side, postprocessed/patch_grid_shape) gets one post-processed
//     grid per patch side, named after it, each a HyperSlab of the rows of its
//     samples in postprocessed/coordinates and postprocessed/pressure.
//     With friction the Gauss points also carry "status" (0 open, 1 stick, 2 slip),
//     "slip", "slip_increment" and the components "tangential_traction_x", "_y"
//     (, "_z") of gauss_points/tangential_traction_vector, and a one-patch-side
//     post-processed grid the components of postprocessed/tangential_traction_vector
//     (scalars, each a HyperSlab column: ParaView colours by them directly).

#include <array>
#include <string>
#include <vector>

namespace iga::io {

struct XdmfMesh {
    std::string body;
    long long n_points = 0;
    long long n_cells = 0;
    int nodes_per_cell = 4;  ///< 4: quadrilaterals (2D), 8: hexahedra (3D)
    bool fields = false;     ///< the steps hold fields/<body>/{stress, von_mises} (output.fields)
};

struct XdmfContactSide {
    std::string group;  ///< e.g. "/steps/0001/contact/cyl_floor/cylinder.v0"
    std::string label;  ///< e.g. "cyl_floor cylinder.v0"
    long long n_gauss = 0;
    long long n_samples = 0;
    int dim = 2;        ///< columns of the coordinate datasets
    long long n_u = 0;  ///< surface sides: samples form an n_v x n_u grid (0: a curve)
    long long n_v = 0;
    /// Surfaces of several patch sides: [n_v, n_u] samples of each (a curve: [1, n]),
    /// in storage order, and their names ("left.v0"); empty for one side.
    std::vector<std::array<long long, 2>> patch_grids;
    std::vector<std::string> patch_sides;
    bool friction = false;  ///< the side holds the friction datasets (a pair with friction)
};

struct XdmfStep {
    int index = 0;  ///< 1-based increment number (group /steps/<kkkk>)
    double load_factor = 0.0;
    std::vector<XdmfContactSide> sides;
};

/// The XDMF text; `h5_name` is the results file's name as seen from the XDMF file's folder.
std::string xdmf_text(const std::string& h5_name, const std::vector<XdmfMesh>& meshes,
                      const std::vector<XdmfStep>& steps);

/// Writes the text to `path` through a temporary file and rename (never half a file).
/// Throws iga::Error when it cannot.
void write_xdmf(const std::string& path, const std::string& text);

}  // namespace iga::io
