#pragma once
// Sauer's post-processing of the Gauss-point contact pressure (Sauer, Comput Mech
// 52 (2013) 301; Kopacka et al. eqs. 10-11; docs/theory.md "Sauer's pressure post-processing"):
//
//   p_A = sum_g R_A(eta_g) p_g W_g / sum_g R_A(eta_g) W_g,     p^h = sum_A R_A p_A,
//
// sums over ALL Gauss points of the side (W = w_g |dX/deta|, reference). p_A is a
// weighted average, not the pressure at control point A; p_A = 0 where the
// denominator is 0. Properties: p_A >= 0; sum_A p_A sum_g R_A W_g = sum_g p_g W_g
// exactly (partition of unity); a uniform p_g = p gives p_A = p.
//
// Shapes: the side (a curve in 2D, a surface in 3D, q = d - 1 parameters) has
// n_cp control points and d coordinates. Samples: in each direction every span is
// divided into samples_per_span equal parameter intervals and every interval end
// is taken once (shared span ends too): n_spans * samples_per_span + 1 values; a
// curve has that many samples, a surface the tensor grid of both directions
// (u fastest).

#include "contact/contact_pair.hpp"
#include "core/types.hpp"
#include "nurbs/patch.hpp"

#include <array>
#include <vector>

namespace iga::contact {

struct RecoveredPressure {
    Vector control_point_pressure;   ///< n_cp, p_A
    RowMatrix parameter;             ///< n_s x q, sample parameters (u fastest)
    std::array<Index, 2> grid{0, 0}; ///< surfaces: (n_u, n_v) samples per direction; curves: (n_s, 1)
    /// Multi-piece surfaces: the grid of each piece, samples piece after piece
    /// (then `grid` is (n_s, 1)); empty for one piece.
    std::vector<std::array<Index, 2>> grids;
    RowMatrix coordinates;           ///< n_s x d, current configuration
    RowMatrix reference_coordinates; ///< n_s x d
    Vector pressure;                 ///< n_s, p^h at the samples
    double normal_force = 0.0;       ///< sum_g p_g W_g, the resultant of the contact pressure on the side
};

/// p_A from Gauss-point parameters (n_g x q), pressures p (n_g) and weights W (n_g)
/// on `side` (n_par = q = 1 or 2).
Vector control_point_pressure(const nurbs::Patch& side, const RowMatrix& parameter, const Vector& pressure,
                              const Vector& weight);
/// The same on a curve side, with the parameters as a list.
Vector control_point_pressure(const nurbs::Patch& side, const std::vector<double>& eta, const Vector& pressure,
                              const Vector& weight);

/// Everything results.md asks for one carrying side: `side_reference` is the
/// side in the reference configuration, `side_displacement` its n_cp x d
/// control-point displacements, `carrier` its Gauss-point data from
/// ContactPair::evaluate. samples_per_span >= 1.
RecoveredPressure recover_pressure(const nurbs::Patch& side_reference, const RowMatrix& side_displacement,
                                   const CarrierResult& carrier, int samples_per_span);

/// The same on a (possibly multi-piece) surface: p_A over the surface's control
/// points (an interface control point averages the Gauss points of every piece
/// around it, once), samples of every piece in piece order. surface_displacement:
/// n_cp x d in the surface numbering. One piece: exactly the single-side result.
RecoveredPressure recover_pressure(const DeformableSide& surface, const RowMatrix& surface_displacement,
                                   const CarrierResult& carrier, int samples_per_span);

}  // namespace iga::contact
