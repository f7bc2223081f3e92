#include "contact/normal_law.hpp"

#include "contact/gap.hpp"
#include "core/error.hpp"

#include <cmath>
#include <numbers>

namespace iga::contact {

namespace {

/// e - 1, as expm1 computes it (the exponential branch uses expm1, so p(0) = p0 to an ulp).
const double e_minus_1 = std::expm1(1.0);

/// The overloaded-lambda idiom for std::visit.
template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};

/// k0 = dp/dg_N at touch: p0 (2e - 1) / ((e - 1) c0).
double touch_slope(const NormalLaw::Exponential& law)
{
    return law.pressure * (2.0 * std::numbers::e - 1.0) / (e_minus_1 * law.clearance);
}

bool positive_finite(double a) { return std::isfinite(a) && a > 0.0; }

}  // namespace

const char* NormalLaw::name() const
{
    return as_penalty() ? "penalty" : "exponential";
}

bool NormalLaw::valid() const
{
    return std::visit(Overloaded{[](const Penalty& law) { return positive_finite(law.penalty); },
                                 [](const Exponential& law) {
                                     return positive_finite(law.clearance) && positive_finite(law.pressure);
                                 }},
                      law_);
}

NormalResponse NormalLaw::response(double gap, double multiplier) const
{
    return std::visit(
        Overloaded{[&](const Penalty& law) {
                       // p = <lambda + eps g_N>, dp/dg_N = eps H(lambda + eps g_N).
                       const double argument = multiplier + law.penalty * gap;
                       return NormalResponse{macaulay(argument), law.penalty * heaviside(argument)};
                   },
                   [&](const Exponential& law) {
                       if (!(gap > -law.clearance))
                           return NormalResponse{};
                       if (gap > 0.0) {  // the linear continuation with the slope at touch
                           const double k0 = touch_slope(law);
                           return NormalResponse{law.pressure + k0 * gap, k0};
                       }
                       // x = g_N / c0 + 1 in (0, 1]: p = p0/(e-1) x (e^x - 1).
                       const double x = gap / law.clearance + 1.0;
                       const double scale = law.pressure / e_minus_1;
                       const double em1 = std::expm1(x);
                       return NormalResponse{scale * x * em1, scale / law.clearance * (em1 + x * (em1 + 1.0))};
                   }},
        law_);
}

bool NormalLaw::active(double gap, double multiplier) const
{
    return std::visit(Overloaded{[&](const Penalty& law) { return multiplier + law.penalty * gap > 0.0; },
                                 [&](const Exponential& law) { return gap > -law.clearance; }},
                      law_);
}

double NormalLaw::updated_multiplier(double pressure) const
{
    return takes_multipliers() ? pressure : 0.0;
}

double NormalLaw::stiffness() const
{
    return std::visit(Overloaded{[](const Penalty& law) { return law.penalty; },
                                 [](const Exponential& law) { return touch_slope(law); }},
                      law_);
}

double NormalLaw::reach() const
{
    const Exponential* law = as_exponential();
    return law ? law->clearance : 0.0;
}

void NormalLaw::set_penalty(double eps)
{
    IGA_CHECK(std::isfinite(eps) && eps > 0.0, "contact: penalty must be > 0");
    Penalty* law = std::get_if<Penalty>(&law_);
    IGA_CHECK(law != nullptr, "contact: only the penalty law has a penalty to change");
    law->penalty = eps;
}

NormalLaw::Shifted NormalLaw::shifted(double multiplier, double unreleased, double overlap) const
{
    if (const Penalty* law = as_penalty())
        return Shifted{multiplier - law->penalty * unreleased * overlap, 0.0};
    return Shifted{multiplier, unreleased * overlap};
}

}  // namespace iga::contact
