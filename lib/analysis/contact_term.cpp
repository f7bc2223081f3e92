#include "analysis/contact_term.hpp"

#include "analysis/output.hpp"
#include "analysis/warnings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace iga::analysis {

namespace {

/// The round-off of a pair's contact forces that |r_c| does not show (see the header).
/// `penalty`: the normal and the tangential penalty summed (a sticking point's
/// traction is eps_T times a difference of points of size |x|).
double contact_gap_round_off(const contact::PairEvaluation& c, double penalty)
{
    double sum2 = 0.0;
    for (const contact::CarrierResult& carrier : c.carriers)
        for (Index g = 0; g < carrier.pressure.size(); ++g) {
            if (!(carrier.pressure(g) > 0.0))
                continue;
            const double lambda = carrier.multiplier.size() > g ? std::abs(carrier.multiplier(g)) : 0.0;
            const double error = carrier.weight(g) * (lambda + penalty * carrier.coordinates.row(g).norm());
            sum2 += error * error;
        }
    return std::numeric_limits<double>::epsilon() * std::sqrt(sum2);
}

}  // namespace

RowMatrix side_displacement(const Scene& scene, const PairModel& pair, const Vector& u_full, int k)
{
    const int b = pair.body[static_cast<std::size_t>(k)];
    if (b < 0)
        return RowMatrix(0, scene.dim);
    const assembly::DofMap& dofs = *scene.dofs;
    const int d = scene.dim;
    const auto& parent = pair.parent_index[static_cast<std::size_t>(k)];
    RowMatrix u(static_cast<Index>(parent.size()), d);
    for (std::size_t a = 0; a < parent.size(); ++a)
        for (int i = 0; i < d; ++i)
            u(static_cast<Index>(a), i) = u_full(dofs.dof(dofs.node_offset(b) + parent[a], i));
    return u;
}

ContactTerm::ContactTerm(Scene& scene, int pair)
    : scene_(scene), index_(pair), model_(scene.pairs[static_cast<std::size_t>(pair)])
{
}

void ContactTerm::prepare(ModelAssembly& a)
{
    ScopedTimer timer(a.context, "contact");
    a.stop.check();
    evaluation_ = model_.pair.evaluate(side_displacement(scene_, model_, a.u_full, 0),
                                       side_displacement(scene_, model_, a.u_full, 1), a.need_tangent, a.context, a.t);
    model_.pair.adopt(std::move(evaluation_.trial));  // the state in use: warm starts, trial history
    if (a.need_tangent)
        register_couplings(a.context);
}

void ContactTerm::add_to(ModelAssembly& a)
{
    ScopedTimer timer(a.context, "contact");
    const contact::PairEvaluation& c = evaluation_;
    if (!c.ok) {
        a.fail(fmt::format("contact pair '{}': {}", model_.name, c.message));
        return;
    }
    a.active += c.n_active;
    if (a.root)
        for (std::size_t k = 0; k < model_.local_to_full.size(); ++k) {
            a.r_full(model_.local_to_full[k]) += c.residual(static_cast<Index>(k));
            a.magnitude(model_.local_to_full[k]) += std::abs(c.residual(static_cast<Index>(k)));
        }
    a.contact_norm += c.residual.norm();
    const contact::PairSettings& settings = model_.pair.settings();
    a.gap_round_off += contact_gap_round_off(
        c, settings.law.stiffness() + (settings.friction.active() ? settings.friction.tangential_penalty : 0.0));
    if (a.tangent)
        for (const contact::LocalBlock& block : c.tangent)
            a.add_block(model_.blocks.at(block.element), block.K);
}

void ContactTerm::commit()
{
    model_.pair.commit();
}

void ContactTerm::rollback()
{
    model_.pair.rollback();
}

void ContactTerm::report(const ModelAssembly& a, int samples_per_span, io::StepData& step) const
{
    step.contact.push_back(pair_result(scene_, index_, evaluation_, a.u_full, a.t, samples_per_span));
}

std::vector<std::string> ContactTerm::warnings(const io::StepData& step) const
{
    const auto result = std::find_if(step.contact.begin(), step.contact.end(),
                                     [&](const io::ContactPairResult& r) { return r.name == model_.name; });
    std::vector<std::string> out = driven_through_warnings(scene_, model_, step);
    for (std::string& line : undeclared_contact_warnings(scene_, model_, step))
        out.push_back(std::move(line));
    if (result != step.contact.end()) {
        for (std::string& line : pair_warnings(scene_, model_, *result, step.load_factor))
            out.push_back(std::move(line));
        for (std::string& line : resolution_warnings(model_, *result))
            out.push_back(std::move(line));
    }
    return out;
}

void ContactTerm::append_activity(std::vector<std::uint8_t>& out) const
{
    for (const contact::CarrierResult& carrier : evaluation_.carriers)
        for (Index g = 0; g < carrier.pressure.size(); ++g)
            out.push_back(carrier.pressure(g) > 0.0 ? 1 : 0);
}

int ContactTerm::n_points() const
{
    int n = 0;
    for (int c = 0; c < model_.pair.n_carriers(); ++c)
        n += model_.pair.n_gauss_points(c);
    return n;
}

namespace {

/// The normal force point g of `carrier` would carry were it free: its law's pressure at
/// its gap, times its weight (0 where the law presses nothing).
double free_force(const contact::ContactPair& pair, const contact::CarrierResult& carrier, Index g)
{
    const double multiplier = carrier.multiplier.size() > g ? carrier.multiplier(g) : 0.0;
    return pair.settings().law.response(carrier.gap(g), multiplier).pressure * carrier.weight(g);
}

}  // namespace

double ContactTerm::withheld_share(int c) const
{
    const contact::CarrierResult& carrier = evaluation_.carriers[static_cast<std::size_t>(c)];
    double carried = 0.0, withheld = 0.0;
    for (Index g = 0; g < carrier.pressure.size(); ++g) {
        carried += carrier.pressure(g) * carrier.weight(g);
        if (model_.pair.is_held(c, static_cast<int>(g)))
            withheld += free_force(model_.pair, carrier, g);
    }
    return withheld > 0.0 ? withheld / std::max(carried + withheld, DBL_MIN) : 0.0;
}

bool ContactTerm::hold_open(int index)
{
    for (int c = 0; c < model_.pair.n_carriers(); ++c) {
        const int n = model_.pair.n_gauss_points(c);
        if (index >= n) {
            index -= n;
            continue;
        }
        if (static_cast<std::size_t>(c) >= evaluation_.carriers.size() || !model_.pair.hold_open(c, index))
            return false;
        if (withheld_share(c) <= max_held_force)
            return true;
        model_.pair.release_hold(c, index);  // it would leave too much of the side's force out
        return false;
    }
    return false;
}

int ContactTerm::release_deep_holds()
{
    int released = 0;
    for (int c = 0; c < static_cast<int>(evaluation_.carriers.size()); ++c) {
        if (withheld_share(c) <= max_held_force)
            continue;
        for (int g = 0; g < model_.pair.n_gauss_points(c); ++g)
            if (model_.pair.is_held(c, g)) {
                model_.pair.release_hold(c, g);
                ++released;
            }
    }
    return released;
}

void ContactTerm::register_couplings(RunContext* context)
{
    // Every rank registers the same couplings (the contact evaluation is the same on
    // all); a block another rank assembles keeps its index but no entries here.
    std::vector<std::vector<int>> new_blocks;
    std::vector<contact::Coupling> couplings;
    const int first_index = scene_.pattern->n_blocks();
    for (const contact::LocalBlock& block : evaluation_.tangent)
        if (!model_.blocks.contains(block.element)) {
            const bool mine = scene_.partition.owns(first_index + static_cast<int>(couplings.size()));
            couplings.push_back(block.element);
            new_blocks.push_back(mine ? coupling_full_dofs(model_, block.element) : std::vector<int>{});
        }
    if (new_blocks.empty())
        return;
    const Index nnz_before = scene_.pattern->n_nonzeros();
    const int first = scene_.pattern->extend(std::move(new_blocks), nullptr, coupling_blocks_searched(scene_.dim));
    for (std::size_t k = 0; k < couplings.size(); ++k)
        model_.blocks.emplace(couplings[k], first + static_cast<int>(k));
    if (context)
        context->log(Verbosity::verbose,
                     fmt::format("  contact pair '{}': {} new coupling(s) registered, {} new tangent entries",
                                 model_.name, couplings.size(), scene_.pattern->n_nonzeros() - nnz_before));
}

}  // namespace iga::analysis
