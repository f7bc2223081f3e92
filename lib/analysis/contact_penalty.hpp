#pragma once
// The penalty of a contact pair written `penalty: auto` (docs/deck.md, docs/theory.md
// "Choosing the penalty"), and the automatic gap tolerance of the augmented
// Lagrangian, both from the pair's deformable sides in the reference configuration:
//
//   eps = min(kappa_side E* / l,  c_max E' / h),
//   E' = E / (1 - nu^2) (plane strain and 3D) or E (plane stress); E' of the SOFTER
//        deformable body in the cap, and the pair's Hertz modulus
//        E* = 1 / (1/E'_1 + 1/E'_2) (E* = E' against a rigid obstacle) in the first term,
//   l  = the size of the smallest deformable contact side: its reference length (2D)
//        or the square root of its reference area (3D),
//   h  = the smallest element of the pair's deformable sides: its reference length
//        (2D) or the square root of its reference area (3D);
//   gap_tolerance (automatic) = auto_gap_fraction h p_max / E', p_max the largest
//        Gauss-point pressure of the pair at the state checked.
//
// The penalty's own error is about 1/kappa, kappa = eps a / E* (a the contact
// half-width: the penalty layer in series with the bodies), and does not depend on
// the mesh; so the first term gives kappa = kappa_side a / l whatever h, and a mesh
// refined for accuracy keeps the eps, the conditioning and the Newton basin of the
// coarse one. The cap eps h / E' <= c_max bounds the ratio of one element's contact
// stiffness to its bulk stiffness (about log10 c_max digits of conditioning); it
// binds on coarse sides only (l/h < kappa_side E*/(c_max E'), 50 to 100 elements),
// and there gives the earlier rule eps = c_max E'/h.
// A penetration g changes the pressure by about E' g / L over a contact zone of
// size L >= h, so the automatic gap tolerance bounds that change by
// auto_gap_fraction h / L <= auto_gap_fraction of p_max, in any units and at any
// strain level (a tolerance proportional to h alone would not: at a strain of 1e-4
// a penetration of 1e-4 h is already a 1e-4 h / (1e-4 L) = h / L error).

#include "contact/contact_pair.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"

#include <string>
#include <vector>

namespace iga::analysis {

/// kappa_side in eps = kappa_side E*/l: kappa = 1e4 a/l, a penalty error of about
/// 1e-3 when the contact zone spans a tenth of the side. On both Hertz decks
/// (inputs/hertz.yaml, inputs/hertz_two_cylinders_2d.yaml: a/l = 0.07, kappa = 690)
/// the errors are then within 0.1 % (L2) of a penalty so stiff it no longer matters,
/// and Newton takes the two cylinders' load in one increment at refinement levels
/// 0-2; measured in docs/performance.md "penalty: auto".
constexpr double auto_penalty_kappa_side = 1.0e4;
/// c_max in the cap eps <= c_max E'/h: two digits of conditioning at most.
constexpr double auto_penalty_cap = 100.0;
/// kappa = eps a / E* per unit of the error allowed, that an accuracy run gives the
/// target pair's penalty once a level has measured the zone (analysis/accuracy.cpp): the
/// penalty's own error is about 1/kappa (above; on the finest 2D Hertz level of
/// inputs/hertz_accuracy_2d.yaml, L2 1.68 / 1.03 / 0.84 / 0.81 / 0.80 % at kappa = 100 /
/// 300 / 1 000 / 3 000 / 7 500), so kappa_target / error leaves it at a tenth of the target.
constexpr double kappa_target = 10.0;
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

/// The size l of a side patch: its reference length (2D), the square root of its
/// reference area (3D).
double side_size(const nurbs::Patch& side);

struct AutoPenalty {
    double penalty = 0.0;       ///< min(kappa_side E*/l, c_max E'/h)
    double modulus = 0.0;       ///< E' of the softer deformable body
    double hertz_modulus = 0.0; ///< E* of the pair
    double element_size = 0.0;  ///< h
    double side_size = 0.0;     ///< l
    bool capped = false;        ///< the cap c_max E'/h gave eps
};

/// The value and its origin in words, for the log: "3.5e+06 = 1e4 E*/l with ...".
std::string describe(const AutoPenalty& rule);

/// The rule above for the deformable sides `sides` (one or two, each with its body's
/// material; at least one).
AutoPenalty auto_penalty(const std::vector<const contact::DeformableSide*>& sides,
                         const std::vector<const mechanics::Material*>& materials);

}  // namespace iga::analysis
