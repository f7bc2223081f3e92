#pragma once
// Isotropic hyperelastic materials: pointwise stress, tangent and energy.
//
// Models (Bonet & Wood, "Nonlinear Continuum Mechanics for Finite Element
// Analysis", 2nd ed., ch. 6), with the 3D Lame parameters
// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)):
//  - linear_elastic:          sigma = lambda tr(eps) I + 2 mu eps.
//  - saint_venant_kirchhoff:  W = lambda/2 (tr E)^2 + mu E:E,
//                             S = lambda tr(E) I + 2 mu E.
//  - neo_hookean (compressible neo-Hookean of Bonet & Wood, ch. 6):
//                             W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,
//                             I1 = tr C, J = sqrt(det C),
//                             S = mu (I - C^-1) + lambda ln J C^-1,
//                             C_ijkl = lambda C^-1_ij C^-1_kl
//                                    + (mu - lambda ln J)(C^-1_ik C^-1_jl + C^-1_il C^-1_jk).
// E = (C - I)/2 is the Green-Lagrange strain, S the second Piola-Kirchhoff stress.
//
// Kinematics: `small` uses the linearization at zero strain, which is Hooke's law
// (above) for all three models with the same E and nu; `finite` evaluates S(E),
// and linear_elastic under finite kinematics is evaluated as Saint Venant-Kirchhoff
// (its geometrically nonlinear extension).
//
// Plane modes (d = 2): `strain` is the 3D law with E33 = E13 = E23 = 0 (so C33 = 1
// in I1 and J); `stress` imposes S33 = 0 by solving E33 with a local Newton and
// condensing the tangent, D2_ab = D_ab - D_a3 D_3b / D_33 (exact in one step for
// the two laws linear in E, where it equals the lambda* = 2 lambda mu/(lambda + 2 mu)
// reduction; iterated for neo-Hookean). `none` means 3D.
//
// Shapes: strains and stresses are d x d tensors; tangents are n_voigt x n_voigt
// in the Voigt order of voigt.hpp (engineering shear strains), symmetric.
// Energies are per unit reference volume (area in 2D, per unit thickness).
//
// A failed evaluation (det C <= 0 for neo-Hookean, local plane-stress Newton not
// converged) is a numerical failure, not an error: it is reported in `status`,
// the values are then NaN, and the load stepper should cut the step back.

#include "core/types.hpp"
#include "core/model_options.hpp"
#include "mechanics/voigt.hpp"

namespace iga::mechanics {

using iga::Kinematics;     // core/model_options.hpp
using iga::MaterialModel;
using iga::PlaneMode;

/// Spatial dimension implied by the plane mode: 2 for strain/stress, 3 for none.
constexpr int spatial_dim(PlaneMode plane) { return plane == PlaneMode::none ? 3 : 2; }

/// A material of a body. Preconditions (checked by IGA_CHECK in lame_parameters;
/// the deck reader reports them to the user first): E > 0, -1 < nu < 0.5.
struct Material {
    MaterialModel model = MaterialModel::linear_elastic;
    double E = 0.0;
    double nu = 0.0;
    PlaneMode plane = PlaneMode::strain;
};

/// 3D Lame parameters (the plane-stress reduction happens in the response).
struct Lame {
    double lambda;
    double mu;
};
Lame lame_parameters(const Material& material);

enum class ResponseStatus {
    ok,
    inverted,                    ///< det C <= 0 (or det F <= 0 at element level): the strain is not admissible
    plane_stress_not_converged,  ///< the local Newton for S33 = 0 did not converge
};

/// Pointwise response of a material.
struct StressResponse {
    MatN stress;           ///< d x d: sigma (small) or S (finite)
    VoigtMatrix tangent;   ///< n_voigt x n_voigt: d stress_voigt / d strain_voigt
    double energy = 0.0;   ///< strain energy density W (per unit reference volume)
    /// d = 2: the out-of-plane normal strain (eps33 or E33): 0 in plane strain,
    /// the solved value in plane stress. d = 3: 0 (unused).
    double strain33 = 0.0;
    ResponseStatus status = ResponseStatus::ok;
};

/// Linearized response (Hooke's law) at the small strain eps (d x d, symmetric).
StressResponse small_strain_response(const Material& material, const MatN& strain);

/// Finite-strain response: S and dS/dE at the Green-Lagrange strain E (d x d, symmetric).
StressResponse finite_strain_response(const Material& material, const MatN& green_lagrange);

/// Dispatch on the kinematics: small -> small_strain_response, finite -> finite_strain_response.
StressResponse stress_response(const Material& material, Kinematics kinematics, const MatN& strain);

}  // namespace iga::mechanics
