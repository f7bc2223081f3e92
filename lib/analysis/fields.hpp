#pragma once
// Stress fields at the tessellation points (output.fields): for each point of a
// body's tessellation (analysis/tessellation.hpp), the reference position, the
// displacement and the Cauchy stress (mechanics::cauchy_stress) with its von
// Mises value, as io::BodyFields (results.md: /steps/<kkkk>/fields/<body>/).
//
// Stress rows: xx, yy, zz, xy, yz, xz. In 2D yz = xz = 0 and zz is the
// out-of-plane stress (plane strain: the reaction that keeps eps_zz = 0; plane
// stress: 0). von Mises from the full 3 x 3 tensor:
//   sqrt(((s_xx - s_yy)^2 + (s_yy - s_zz)^2 + (s_zz - s_xx)^2) / 2 + 3 (s_xy^2 + s_yz^2 + s_xz^2)).
//
// Points where the geometry map is singular (a collapsed edge or corner, as in
// the quarter and half discs: det(dX/dxi) below 1e-6 of its scale, which there is
// round-off of either sign) are not evaluated where they are: J^-1 would turn the
// round-off into O(1) stress errors, and the round-off still grows like
// 1/distance^2 close to the edge. Their stress is extrapolated linearly from two
// points inside, moved towards the centre of the knot span by 0.05 and 0.1 of the
// span: 2 s(0.05) - s(0.1), exact for a linear stress field. A point whose stress
// cannot be evaluated (det F <= 0 there in finite kinematics) gets zeros and is
// counted in n_unevaluated.

#include "analysis/scene.hpp"
#include "analysis/tessellation.hpp"
#include "io/results_data.hpp"

namespace iga::analysis {

struct FieldsResult {
    io::BodyFields fields;
    int n_unevaluated = 0;  ///< points left at zero (see above)
};

/// Fields of `body` at the points of `tessellation` for the body-node
/// displacements `u` (n_nodes x d).
FieldsResult body_fields(const BodyModel& body, const TessellatedBody& tessellation, mechanics::Kinematics kinematics,
                         const RowMatrix& u);

/// von Mises stress of a row xx, yy, zz, xy, yz, xz.
double von_mises(const Eigen::Ref<const Eigen::Matrix<double, 1, 6>>& s);

}  // namespace iga::analysis
