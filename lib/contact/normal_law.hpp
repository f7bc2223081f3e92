#pragma once
// The normal contact law of a pair: the contact pressure p >= 0 at a Gauss point as
// a function of its normal gap g_N (gap.hpp: positive = penetration, the
// "overclosure" h of Abaqus) and of its multiplier lambda >= 0, with the slope
// dp/dg_N the consistent tangent needs. It is written here once; the kernels
// (gpts_kernel.hpp, gpts_friction.hpp), the pair (contact_pair.hpp) and the driver's
// scales ask this object, never a penalty parameter directly. docs/theory.md
// "Contact formulation", "Augmented Lagrangian" and "Softened contact" derive them.
//
// Penalty, and the augmented Lagrangian (the same law, with multipliers): with the
// penalty parameter eps > 0 and the Macaulay bracket <a> = max(a, 0),
//
//   p = <lambda + eps g_N>,   dp/dg_N = eps H(lambda + eps g_N),
//
// H the Heaviside step (H(0) = 0: a point whose argument is exactly zero is open).
// lambda = 0 gives the plain penalty p = eps <g_N> (Kopacka et al. eq. 3). The Uzawa
// step of the augmented Lagrangian, at a converged state, is
// lambda <- <lambda + eps g_N>, i.e. lambda <- p. Its stiffness scale is eps.
//
// Exponential ("softened") pressure-overclosure, as Abaqus offers it: contact is
// felt from the clearance c0 > 0 on, the pressure rising smoothly to p0 > 0 at
// touch (g_N = 0). With x = g_N / c0 + 1,
//
//   p = 0                                        g_N <= -c0
//   p = p0 / (e - 1) x (e^x - 1)                 -c0 < g_N <= 0
//   p = p0 + k0 g_N                              g_N > 0,
//
//   dp/dg_N = p0 / ((e - 1) c0) (e^x - 1 + x e^x) on the middle branch,
//   k0 = dp/dg_N at g_N = 0 = p0 (2e - 1) / ((e - 1) c0).
//
// p and dp/dg_N are continuous everywhere: at g_N = -c0 both are 0 (x = 0), at
// g_N = 0 the pressure is p0 and the slope k0 on both sides. Beyond touch the law
// continues LINEARLY with the slope k0 (a maximum stiffness, as Abaqus allows): the
// exponential itself would stiffen without bound (its slope grows like x e^x) and
// with it the conditioning of Newton's matrix. The second derivative jumps at both
// ends (at -c0 from 0 to 2 p0 / ((e - 1) c0^2), at 0 to 0). The law carries no
// multiplier: lambda is ignored, its Uzawa step gives 0, and it has no penalty
// parameter to raise (set_penalty refuses it). Its stiffness scale is k0.
//
// Activity: a point is active where p > 0, i.e. lambda + eps g_N > 0 for the
// penalty law and g_N > -c0 for the exponential one: pressure at negative gaps,
// whence reach() (how far outside a surface a point can still be pressed), which a
// pair adds to its search margin.

#include "core/types.hpp"

#include <variant>

namespace iga::contact {

/// p and dp/dg_N of a law at one gap and multiplier.
struct NormalResponse {
    double pressure = 0.0;  ///< p >= 0
    double slope = 0.0;     ///< dp/dg_N >= 0
};

class NormalLaw {
public:
    /// p = <lambda + eps g_N> (see the header paragraph).
    struct Penalty {
        double penalty = 0.0;  ///< eps > 0, pressure per unit penetration
    };
    /// Abaqus' exponential pressure-overclosure, continued linearly beyond touch.
    struct Exponential {
        double clearance = 0.0;  ///< c0 > 0: no pressure at gaps g_N <= -c0
        double pressure = 0.0;   ///< p0 > 0: the pressure at touch, g_N = 0
    };

    /// The penalty law with eps = 0: a placeholder, refused by ContactPair until set.
    NormalLaw() = default;
    static NormalLaw penalty(double eps) { return NormalLaw(Penalty{eps}); }
    static NormalLaw exponential(double clearance, double pressure)
    {
        return NormalLaw(Exponential{clearance, pressure});
    }

    /// The penalty law's parameters, or nullptr.
    const Penalty* as_penalty() const { return std::get_if<Penalty>(&law_); }
    /// The exponential law's parameters, or nullptr.
    const Exponential* as_exponential() const { return std::get_if<Exponential>(&law_); }
    /// "penalty" or "exponential" (the deck's and the results' word).
    const char* name() const;
    /// The parameters are finite and > 0.
    bool valid() const;

    /// p and dp/dg_N at gap g_N with multiplier lambda.
    NormalResponse response(double gap, double multiplier) const;
    /// p > 0 (the point presses): lambda + eps g_N > 0, or g_N > -c0.
    bool active(double gap, double multiplier) const;
    /// The Uzawa step from the pressure p = p(g_N, lambda) of a converged evaluation:
    /// lambda <- <lambda + eps g_N> = p for the penalty law; 0 for a law without multipliers.
    double updated_multiplier(double pressure) const;
    /// Whether the law takes multipliers (the augmented Lagrangian can run on it).
    bool takes_multipliers() const { return as_penalty() != nullptr; }

    /// The law's stiffness scale dp/dg_N in contact: eps, or k0 (the slope at touch). It
    /// stands for "the penalty" in scales: gap round-off, conditioning, `auto` tangential penalty.
    double stiffness() const;
    /// How far outside the master a point can be pressed with lambda = 0: 0, or c0.
    double reach() const;
    /// Replaces eps (> 0, finite; the augmented Lagrangian's safeguard). Penalty law only.
    void set_penalty(double eps);

    /// The initial overclosure not yet released, s = u g0 (u the unreleased fraction,
    /// g0 >= 0 the overlap at rest; docs/theory.md "Initial overclosure"), enters the
    /// law as p(g_N - s, lambda). The penalty law is affine in g_N, so that is
    /// p(g_N, lambda - eps u g0): a shifted multiplier, gap untouched. Other laws shift
    /// the gap.
    struct Shifted {
        double multiplier = 0.0;  ///< the multiplier to evaluate the law with
        double gap_offset = 0.0;  ///< subtracted from g_N before the law is evaluated
    };
    Shifted shifted(double multiplier, double unreleased, double overlap) const;

private:
    explicit NormalLaw(std::variant<Penalty, Exponential> law) : law_(law) {}
    std::variant<Penalty, Exponential> law_{Penalty{}};
};

}  // namespace iga::contact
