#pragma once
// The penalty of a contact pair written `penalty: auto` (docs/deck.md, docs/theory.md
// "Choosing the penalty"), and the automatic gap tolerance of the augmented
// Lagrangian, both from the pair's deformable sides in the reference configuration:
//
//   eps = c E' / h,   c = auto_penalty_factor,
//   E' = E / (1 - nu^2) (plane strain and 3D) or E (plane stress), the contact
//        modulus of the SOFTER deformable body of the pair,
//   h  = the smallest element of the pair's deformable sides: its reference length
//        (2D) or the square root of its reference area (3D);
//   gap_tolerance (automatic) = auto_gap_fraction h p_max / E', p_max the largest
//        Gauss-point pressure of the pair at the state checked.
//
// eps h / E' = c is the ratio of the contact stiffness of one element to its bulk
// stiffness: it sets both the penalty's own error (through kappa = eps a / E* =
// c a / h, a the contact half-width) and the extra conditioning of the tangent.
// A penetration g changes the pressure by about E' g / L over a contact zone of
// size L >= h, so the automatic gap tolerance bounds that change by
// auto_gap_fraction h / L <= auto_gap_fraction of p_max, in any units and at any
// strain level (a tolerance proportional to h alone would not: at a strain of 1e-4
// a penetration of 1e-4 h is already a 1e-4 h / (1e-4 L) = h / L error).

#include "contact/contact_pair.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"

#include <vector>

namespace iga::analysis {

/// c in eps = c E'/h. 100: on Hertz (inputs/hertz.yaml, a/h = 67) the penalty then
/// costs less than the mesh (kappa = 6700: peak and half-width within 0.1 % of the
/// exact-constraint values), while eps h/E' = 100 adds two digits to the condition
/// number, far from the round-off floor; measured in README "What accuracy costs".
constexpr double auto_penalty_factor = 100.0;
/// Automatic gap tolerance of the augmented Lagrangian (above): the pressure error
/// it leaves is at most 1e-3 relative, below the discretization error of any
/// mesh a contact run can afford (Hertz, inputs/hertz.yaml: L2 0.8 %).
constexpr double auto_gap_fraction = 1e-3;

/// The automatic gap tolerance auto_gap_fraction h p_max / E'.
inline double auto_gap_tolerance(double element_size, double modulus, double max_pressure)
{
    return auto_gap_fraction * element_size * max_pressure / modulus;
}

/// E' = E/(1 - nu^2) (plane strain, 3D) or E (plane stress).
double contact_modulus(const mechanics::Material& material);

/// The smallest element of a side patch (d - 1 parameters): reference length in
/// 2D, square root of the reference area in 3D.
double smallest_element_size(const nurbs::Patch& side);

struct AutoPenalty {
    double penalty = 0.0;       ///< c E' / h
    double modulus = 0.0;       ///< E' of the softer deformable body
    double element_size = 0.0;  ///< h
};

/// The rule above for the deformable sides `sides` (one or two, each with its body's
/// material; at least one).
AutoPenalty auto_penalty(const std::vector<const contact::DeformableSide*>& sides,
                         const std::vector<const mechanics::Material*>& materials);

}  // namespace iga::analysis
