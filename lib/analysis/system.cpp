#include "analysis/system.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace iga::analysis {

SceneSystem::SceneSystem(Scene& scene, RunContext& context, int requested_threads, const Communicator& comm)
    : scene_(scene), context_(context), comm_(comm)
{
    IGA_CHECK(scene.partition.size == comm.size(), "SceneSystem: the scene was partitioned for another rank count");
    auto elastic = std::make_unique<ElasticTerm>(scene, context, requested_threads);
    elastic_ = elastic.get();
    terms_.push_back(std::move(elastic));
    terms_.push_back(std::make_unique<DeadLoadTerm>(scene));
    for (const FollowerPressure& follower : scene.followers)
        terms_.push_back(std::make_unique<FollowerPressureTerm>(follower));
    for (std::size_t p = 0; p < scene.pairs.size(); ++p) {
        auto pair = std::make_unique<ContactTerm>(scene, static_cast<int>(p));
        contact_.push_back(pair.get());
        terms_.push_back(std::move(pair));
    }
}

void SceneSystem::set_weak_springs(std::vector<NodeSpring> springs)
{
    IGA_CHECK(springs_ == nullptr, "SceneSystem: weak springs are set once");
    auto term = std::make_unique<WeakSpringTerm>(scene_, std::move(springs));
    springs_ = term.get();
    terms_.insert(terms_.begin() + 1, std::move(term));  // right after the elastic bodies
}

solver::NonlinearSystem SceneSystem::nonlinear_system()
{
    solver::NonlinearSystem system;
    system.evaluate = [this](const Vector& u, double lambda, bool need_tangent, solver::Evaluation& out) {
        evaluate(u, lambda, need_tangent, out);
    };
    const bool follower = !scene_.followers.empty();
    system.linear = scene_.kinematics == mechanics::Kinematics::small && !scene_.has_contact();
    // Symmetric unless a follower load or a two-half-pass pair of two deformable sides
    // (each half pass assembles only its slave rows) makes it otherwise: elastic
    // tangents, rigid-obstacle and single-pass contact are Hessians of an energy.
    // Coulomb friction's slip tangent is not symmetric either (contact/friction.hpp).
    bool half_passes = false, friction = false;
    for (const PairModel& pair : scene_.pairs) {
        half_passes = half_passes || (pair.obstacle < 0 && pair.formulation == contact::Formulation::two_half_pass);
        friction = friction || pair.pair.settings().friction.active();
    }
    system.symmetric = !half_passes && !follower && !friction;
    if (comm_.parallel())
        system.sum_over_ranks = [this](Vector& v) { comm_.sum(v); };
    system.prescribed_motion_between = [this](double t0, double t1) {
        const Vector none = Vector::Zero(scene_.dofs->n_free());
        double motion = (scene_.dofs->expand(none, t1) - scene_.dofs->expand(none, t0)).lpNorm<Eigen::Infinity>();
        for (const PairModel& pair : scene_.pairs)
            if (pair.obstacle >= 0) {
                const auto& obstacle = std::get<contact::RigidObstacle>(pair.pair.surface(pair.obstacle));
                motion = std::max(motion, (obstacle.shift(t1) - obstacle.shift(t0)).lpNorm<Eigen::Infinity>());
            }
        return motion;
    };
    if (scene_.has_contact()) {
        system.hold_open = [this](const std::vector<int>& points) { return hold_open(points); };
        system.release_deep_holds = [this] { return release_deep_holds(); };
        system.release_holds = [this] {
            for (ContactTerm* pair : contact_)
                pair->release_holds();
        };
    }
    // A trust radius only where a singular first touch can send a step far away.
    system.max_step = scene_.has_contact() ? 0.05 * scene_.model_size : 0.0;
    const assembly::DofMap& dofs = *scene_.dofs;
    for (int k = 0; k < dofs.n_full() && !system.prescribed_motion; ++k)
        system.prescribed_motion = dofs.is_constrained(k) && dofs.prescribed(k) != 0.0;
    // A moving rigid obstacle drives the bodies like a prescribed displacement does.
    for (const PairModel& pair : scene_.pairs)
        if (pair.obstacle >= 0) {
            const auto& obstacle = std::get<contact::RigidObstacle>(pair.pair.surface(pair.obstacle));
            system.prescribed_motion = system.prescribed_motion || (obstacle.motion.size() > 0 && obstacle.motion.norm() > 0.0);
        }
    return system;
}

RowMatrix SceneSystem::body_displacement(const Vector& u_full, int b) const
{
    const assembly::DofMap& dofs = *scene_.dofs;
    const int d = scene_.dim;
    const int n = dofs.n_nodes(b);
    RowMatrix u(n, d);
    for (int a = 0; a < n; ++a)
        for (int i = 0; i < d; ++i)
            u(a, i) = u_full(dofs.dof(dofs.node_offset(b) + a, i));
    return u;
}

RowMatrix SceneSystem::side_displacement(const Vector& u_full, int p, int k) const
{
    return analysis::side_displacement(scene_, scene_.pairs[static_cast<std::size_t>(p)], u_full, k);
}

int SceneSystem::hold_open(const std::vector<int>& points)
{
    int held = 0;
    int first = 0;  // the pair's first point in Evaluation::contact_active
    for (ContactTerm* pair : contact_) {
        const int n = pair->n_points();
        for (int index : points)
            if (index >= first && index < first + n && pair->hold_open(index - first))
                ++held;
        first += n;
    }
    if (held > 0)
        context_.add_count("contact_points_held_open", held);
    return held;
}

int SceneSystem::release_deep_holds()
{
    int released = 0;
    for (ContactTerm* pair : contact_)
        released += pair->release_deep_holds();
    return released;
}

void SceneSystem::commit()
{
    for (const auto& term : terms_)
        term->commit();
}

void SceneSystem::rollback()
{
    for (const auto& term : terms_)
        term->rollback();
}

void SceneSystem::evaluate(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out)
{
    evaluate_into(u_free, load_factor, need_tangent, out, &context_, nullptr);
    // last_active_ counts every pair's Gauss points on every rank: the same verdict on all.
    out.singular_tangent = need_tangent && singular_without_contact_ && last_active_ == 0;
}

Vector SceneSystem::full_residual(const Vector& u_free, double load_factor)
{
    solver::Evaluation scratch;
    Vector r_full;
    evaluate_into(u_free, load_factor, false, scratch, nullptr, &r_full);
    return r_full;
}

void SceneSystem::report(const Vector& u_free, double load_factor, int samples_per_span, io::StepData& step) const
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    const ModelAssembly a(scene_, u_full, load_factor);
    for (const auto& term : terms_)
        term->report(a, samples_per_span, step);
}

std::vector<std::string> SceneSystem::warnings(const io::StepData& step) const
{
    std::vector<std::string> out;
    for (const auto& term : terms_)
        for (std::string& line : term->warnings(step))
            out.push_back(std::move(line));
    return out;
}

void SceneSystem::evaluate_into(const Vector& u_free, double t, bool need_tangent, solver::Evaluation& out,
                                RunContext* context, Vector* r_full_out)
{
    const assembly::DofMap& dofs = *scene_.dofs;
    const Vector u_full = dofs.expand(u_free, t);
    // One rank alone must not leave on a stop request (see the header): polled in the sum.
    const StopRequest stop = context && !comm_.parallel() ? context->stop() : StopRequest{};
    ModelAssembly a(scene_, u_full, t, need_tangent, context, stop, comm_.root());
    // Contact first: a coupling that the pattern lacks extends it before the
    // tangent is shaped, so K has one pattern throughout the evaluation.
    for (const auto& term : terms_)
        term->prepare(a);
    shape_tangent(need_tangent, out.tangent);
    a.tangent = need_tangent ? &out.tangent : nullptr;
    a.r_full = Vector::Zero(dofs.n_full());
    a.magnitude = Vector::Zero(dofs.n_full());
    a.f_int = Vector::Zero(dofs.n_full());
    for (const auto& term : terms_)
        term->add_to(a);
    last_active_ = a.active;
    out.contact_active.clear();
    if (a.ok)
        for (const ContactTerm* pair : contact_)
            pair->append_activity(out.contact_active);
    if (!a.ok) {
        out.ok = false;
        out.message = a.message;
    }
    sum_over_ranks(a, context);
    if (!a.ok) {
        out.ok = false;
        out.message = a.message;
    }
    finish(a, out);
    if (r_full_out)
        *r_full_out = a.r_full;
}

void SceneSystem::shape_tangent(bool need_tangent, SparseMatrix& tangent) const
{
    const assembly::SparsePattern& pattern = *scene_.pattern;
    if (need_tangent) {
        if (!pattern.matches(tangent))
            pattern.shape(tangent);
        else
            tangent.coeffs().setZero();
    } else if (tangent.nonZeros() > 0) {
        // A line search's trial states need no tangent: a stale one would keep a
        // tangent-sized block of memory per trial evaluation (docs/performance.md "Memory in 3D").
        release(tangent);
    }
}

void SceneSystem::finish(ModelAssembly& a, solver::Evaluation& out) const
{
    const assembly::DofMap& dofs = *scene_.dofs;
    double reaction_norm2 = 0.0;
    for (Index k = 0; k < a.f_int.size(); ++k)
        if (dofs.is_constrained(static_cast<int>(k)))
            reaction_norm2 += a.f_int(k) * a.f_int(k);
    const double f_int_norm = a.f_int.norm();
    out.residual = dofs.restrict(a.r_full);
    out.force_scale = std::max({a.external_norm, std::sqrt(reaction_norm2), a.contact_norm, f_int_norm});
    out.residual_floor = std::numeric_limits<double>::epsilon() * dofs.restrict(a.magnitude).norm() + a.gap_round_off;
    if (!out.residual.allFinite() && out.ok) {
        out.ok = false;
        out.message = "the residual is not finite";
    }
}

void SceneSystem::sum_over_ranks(ModelAssembly& a, RunContext* context) const
{
    if (!comm_.parallel())
        return;
    // A stop request on any rank stops every rank here, together.
    if (comm_.any(context != nullptr && collective_stop_.requested()))
        throw Interrupted();
    comm_.sum(a.r_full);
    comm_.sum(a.magnitude);
    comm_.sum(a.f_int);
    a.external_norm = comm_.sum(a.external_norm);
    const std::string failure = comm_.first_message(a.ok ? std::string() : a.message);
    if (!failure.empty())
        a.fail(failure);
}

namespace {
std::vector<double> per_rank(const Communicator& comm, double mine)
{
    Vector counts = Vector::Zero(comm.size());
    counts(comm.rank()) = mine;
    comm.sum(counts);
    return {counts.data(), counts.data() + counts.size()};
}
}  // namespace

std::vector<double> SceneSystem::elements_per_rank() const
{
    const Partition& p = scene_.partition;
    return per_rank(comm_, p.last_element - p.first_element);
}

std::vector<double> SceneSystem::couplings_per_rank() const
{
    double mine = 0;
    for (const PairModel& pair : scene_.pairs)
        for (const auto& [coupling, block] : pair.blocks)
            mine += scene_.partition.owns(block) ? 1 : 0;
    return per_rank(comm_, mine);
}

double SceneSystem::spring_energy(const Vector& u_free, double load_factor) const
{
    return springs_ ? springs_->energy(scene_.dofs->expand(u_free, load_factor)) : 0.0;
}

double SceneSystem::strain_energy(const Vector& u_free, double load_factor)
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    Vector f_int = elastic_->internal_forces(u_full);
    comm_.sum(f_int);
    return 0.5 * u_full.dot(f_int);
}

std::vector<contact::PairEvaluation> SceneSystem::contact_state(const Vector& u_free, double load_factor)
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    ModelAssembly a(scene_, u_full, load_factor);
    std::vector<contact::PairEvaluation> out;
    for (ContactTerm* pair : contact_) {
        pair->prepare(a);
        out.push_back(pair->evaluation());
    }
    return out;
}

}  // namespace iga::analysis
