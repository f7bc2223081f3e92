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
//   gap_tolerance (automatic) = auto_gap_fraction h.
//
// eps h / E' = c is the ratio of the contact stiffness of one element to its bulk
// stiffness: it sets both the penalty's own error (through kappa = eps a / E* =
// c a / h, a the contact half-width) and the extra conditioning of the tangent.

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
/// Automatic gap tolerance of the augmented Lagrangian, as a fraction of h: a
/// penetration of 1e-4 h changes the pressure by about 1e-4 E'/h * h / a of E',
/// far below any discretization error.
constexpr double auto_gap_fraction = 1e-4;

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
