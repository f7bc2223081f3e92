#pragma once
// Regularized Coulomb friction at one contact Gauss point: a tangential penalty
// (elastic stick) with a return map to the Coulomb cone |t_T| <= mu p
// (docs/theory.md "Coulomb friction"; Wriggers, Computational Contact Mechanics, ch. 5).
//
// Slip is measured in space, in the frame of the master: y is the slave point in
// that frame (for a rigid obstacle its position minus the obstacle's translation),
// and `anchor` the point of that frame the slave sticks to. Nothing refers to a
// patch's parameters, so a point that slides from one patch onto the next keeps
// its history. With the current tangent projector P = I - n n:
//
//   trial traction    s = -eps_T P (y - anchor)
//   stick  |s| <= mu p:  t_T = s
//   slip   |s| >  mu p:  t_T = mu p s / |s|,   slip increment (|s| - mu p) / eps_T
//
// and the history of a converged state (FrictionHistory): open points re-anchor
// where they are, slipping points where the traction is reproduced (anchor = y +
// t_T / eps_T), sticking points keep their anchor. The force on the slave is
// +W N_a t_T, so the slave residual gains r_a = -W N_a t_T.
//
// Augmented Lagrangian (docs/theory.md "Frictional augmented Lagrangian"): a tangential
// multiplier lambda_T (a traction, in the anchor's frame; zero: the penalty law), held
// fixed while Newton solves, adds to the trial, s = P lambda_T - eps_T P (y - anchor):
// the anchor shifted by lambda_T / eps_T, so everything below holds with w = y - anchor
// - lambda_T / eps_T. The elastic slip |t_T - P lambda_T| / eps_T is the slide the
// penalty still turns into traction; an Uzawa update adopts the returned traction,
// lambda_T <- t_T (frame_traction), and a slipping point's anchor then reproduces
// t_T with lambda_T kept: anchor = y + (t_T - lambda_T) / eps_T.
//
// Linearization in y (the slave point): with w = y - anchor (- lambda_T / eps_T), rho the distance over
// which the normal turns (dn/dy = P / rho; infinite for a plane),
//   G = d(P w)/dy = P - ((n . w) P + n (P w)^T) / rho,
//   stick: dt_T/dy = -eps_T G,
//   slip:  dt_T/dy = -eps_T mu p / |s| (I - s^ s^T) G + mu s^ (dp/dy)^T.
// The slip tangent is not symmetric: friction makes every tangent non-symmetric.

#include "core/types.hpp"

#include <limits>

namespace iga::contact {

struct FrictionLaw {
    double coefficient = 0.0;         ///< mu >= 0; 0: frictionless
    double tangential_penalty = 0.0;  ///< eps_T > 0 (used when mu > 0)
    bool active() const { return coefficient > 0.0; }
};

enum class StickSlip : int { open = 0, stick = 1, slip = 2 };

/// A Gauss point's friction history, committed once per converged increment.
struct FrictionHistory {
    VecN anchor;           ///< the master-frame point the slave sticks to, d
    double slip = 0.0;     ///< accumulated slip length
    bool anchored = true;  ///< false: no anchor yet (open against a deformable master; gpts_friction.hpp, "First touch")
    /// It slipped in the increment that made this history, so its trial traction starts
    /// on the Coulomb cone: there (to round-off) it is read as slipping on, not sticking.
    bool slipping = false;
    /// Not anchored, open, with a foot on a deformable master: its gap g_N < 0 (a
    /// separation; g_N > 0 is penetration) at the converged state. The increment in
    /// which it first presses takes from it when the gap closed (gpts_friction.hpp).
    /// 0: none known.
    double open_gap = 0.0;
};

/// The tangential response at one Gauss point.
struct TangentialResponse {
    StickSlip status = StickSlip::open;
    VecN traction;               ///< t_T on the slave (tangential), d
    Matrix d_traction;           ///< dt_T/dz, d x m: z = y (m = d) against a rigid obstacle, the kernel's dofs otherwise
    FrictionHistory next;        ///< the history if this state is committed
    double slip_increment = 0.0; ///< slip length since the committed state
    VecN frame_traction;         ///< t_T in the anchor's frame, d: the tangential multiplier an Uzawa update adopts
    double elastic_slip = 0.0;   ///< |t_T - lambda_T| / eps_T (lambda_T in space): 0 where no friction acts
};

/// The return map alone: the trial traction s (tangential, d) with ds/dz (d x m),
/// the pressure p and dp/dz (m). Fills status, traction, d_traction and the slip
/// increment; the history is the caller's (it knows the frame of the anchor).
/// `was_slipping`: the committed state slipped. Its anchor reproduces a traction on the
/// cone, so at the converged state |s| = mu p up to round-off; read as stick there, the
/// tangent the next increment's predictor solves with would hold the point fast and drag
/// the surface along (the ironing die started every increment with half its points stuck).
/// Within `cone_band` of the cone such a point slips: the traction is the same, the
/// tangent is the sliding one. `round_off` (absolute, a traction) widens the band
/// to what the trial's round-off can be: eps_T times the round-off of the positions it
/// is the difference of (trial_round_off below). At a small pressure that is more than
/// cone_band of mu p: a point of the dragged block (verification/scenes/block_drag_2d.yaml)
/// at p = 0.29 with eps_T = 1.1e6 read 1 - 1.3e-9 of the cone under --threads 2 and on
/// the cone under --threads 1, and the two predictors' steps from the same converged
/// state parted by 9 %.
TangentialResponse coulomb_return_map(const FrictionLaw& law, const VecN& trial, const Matrix& d_trial,
                                      double pressure, const Vector& d_pressure, bool was_slipping = false,
                                      double round_off = 0.0);

/// Relative band around the Coulomb cone in which a point that slipped keeps slipping.
inline constexpr double cone_band = 1e-9;

/// Positions are known to this fraction of their magnitude (about 45 eps: the sums of
/// the basis times the control points and the pull-back to the anchor's frame).
inline constexpr double position_round_off = 1e-14;

/// The round-off of a trial traction eps_T (x - a) between positions of magnitude up to
/// `length`.
inline double trial_round_off(const FrictionLaw& law, double length)
{
    return law.tangential_penalty * position_round_off * length;
}

/// Coulomb's law at the slave point y (master frame) with outward normal n of
/// the master, contact pressure p >= 0 and its derivative dp/dy (d), and the
/// tangential multiplier lambda_T (d, in space: the obstacle's frame only translates;
/// zeros for the penalty law).
TangentialResponse coulomb_response(const FrictionLaw& law, const FrictionHistory& committed, const VecN& multiplier,
                                    const VecN& y, const VecN& normal, double pressure, const VecN& d_pressure,
                                    double normal_radius = std::numeric_limits<double>::infinity());

/// An orthonormal tangent basis (d x (d - 1)) of the plane normal to n: in 2D
/// t = e_z x n; in 3D the part of `along` (a tangent of the slave surface)
/// normal to n, then n x t1 (a fixed choice when `along` is parallel to n).
Matrix tangent_basis(const VecN& normal, const VecN& along);

}  // namespace iga::contact
