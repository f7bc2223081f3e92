#include "analysis/system.hpp"

#include "assembly/threads.hpp"
#include "mechanics/element.hpp"
#include "mechanics/small_strain_stiffness.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <cstdint>
#include <mutex>

namespace iga::analysis {

namespace {

/// The round-off of a pair's contact forces that |r_c| does not show: the gap of an
/// active Gauss point is a difference of coordinates of size |x|, so its pressure
/// <lambda + eps g_N> carries an error of about eps_mach (|lambda| + eps |x|), and
/// W times that lands on the point's dofs. Independent errors add in quadrature.
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

Matrix local_displacement(const Vector& u_full, const std::vector<int>& dofs, int d)
{
    const int n = static_cast<int>(dofs.size()) / d;
    Matrix u(n, d);
    for (int a = 0; a < n; ++a)
        for (int i = 0; i < d; ++i)
            u(a, i) = u_full(dofs[static_cast<std::size_t>(a * d + i)]);
    return u;
}

std::string point_text(const VecN& p)
{
    std::string out = "(";
    for (Index i = 0; i < p.size(); ++i)
        out += fmt::format("{}{:.4g}", i > 0 ? ", " : "", p(i));
    return out + ")";
}

/// Names the body, the parameter point and the reference and current position
/// of the Gauss point where an element's evaluation failed.
std::string inadmissible_message(const std::string& body, const mechanics::ElementGeometry& element,
                                 const mechanics::ElementResponse& response, const Matrix& u_local)
{
    const std::string what =
        response.status == mechanics::ResponseStatus::inverted
            ? fmt::format("inadmissible deformation (det F = {:.3g})", response.det_F)
        : response.status == mechanics::ResponseStatus::ok
            ? std::string("non-finite internal force")
            : fmt::format("material evaluation failed (plane-stress iteration, det F = {:.3g})", response.det_F);
    if (response.failed_point < 0 || response.failed_point >= static_cast<int>(element.points.size()))
        return fmt::format("{} in body '{}'", what, body);
    const mechanics::QuadraturePoint& q = element.points[static_cast<std::size_t>(response.failed_point)];
    const VecN x = q.X + mechanics::point_displacement(q, u_local);
    return fmt::format("{} in body '{}' at parameter {}, X = {}, x = {}", what, body, point_text(q.xi), point_text(q.X),
                       point_text(x));
}

/// K += the free x free block of A (over all dofs), A symmetric and stored by its
/// upper triangle, K in a full pattern that holds it. Free indices grow with full
/// ones, so each column of A is one merge of sorted rows for its entries (i <= j),
/// and the mirrored entries (j, i) reach each column of K in increasing rows: one
/// cursor per column, O(nnz).
void add_free_block(const SparseMatrix& A_upper, const assembly::DofMap& map, SparseMatrix& K)
{
    const int* outer = K.outerIndexPtr();
    const int* inner = K.innerIndexPtr();
    double* values = K.valuePtr();
    std::vector<int> mirror(outer, outer + K.outerSize());  // next position to look at, per column
    auto find = [&](int& p, int column, int row) {
        while (p < outer[column + 1] && inner[p] < row)
            ++p;
        IGA_CHECK(p < outer[column + 1] && inner[p] == row,
                  "SceneSystem: the elastic stiffness lies outside the sparsity pattern");
        return p;
    };
    for (Index j = 0; j < A_upper.outerSize(); ++j) {
        const int fj = map.free_index(static_cast<int>(j));
        if (fj < 0)
            continue;
        int p = outer[fj];
        for (SparseMatrix::InnerIterator it(A_upper, j); it; ++it) {
            const int fi = map.free_index(static_cast<int>(it.row()));
            if (fi < 0)
                continue;
            values[find(p, fj, fi)] += it.value();
            if (fi != fj)
                values[find(mirror[static_cast<std::size_t>(fi)], fi, fj)] += it.value();
        }
    }
}

/// r += A u and m += |A| |u| (entry by entry: the round-off scale of the sum), A
/// symmetric and stored by its upper triangle: one pass over it.
void add_symmetric_product(const SparseMatrix& A_upper, const Vector& u, Vector& r, Vector& m)
{
    for (Index j = 0; j < A_upper.outerSize(); ++j) {
        const double uj = u(j);
        double rj = 0, mj = 0;  // the mirrored entries' contributions to row j
        for (SparseMatrix::InnerIterator it(A_upper, j); it; ++it) {
            const Index i = it.row();
            const double a = it.value();
            r(i) += a * uj;
            m(i) += std::abs(a * uj);
            if (i != j) {
                rj += a * u(i);
                mj += std::abs(a * u(i));
            }
        }
        r(j) += rj;
        m(j) += mj;
    }
}

}  // namespace

SceneSystem::SceneSystem(Scene& scene, RunContext& context, int requested_threads, const Communicator& comm)
    : scene_(scene), context_(context), comm_(comm), element_force_(static_cast<std::size_t>(scene.n_element_blocks))
{
    IGA_CHECK(scene.partition.size == comm.size(), "SceneSystem: the scene was partitioned for another rank count");
    std::int64_t work = 0;  // entries of all element tangents
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        for (std::size_t e = 0; e < scene.bodies[b].elements.size(); ++e) {
            owner_.push_back({static_cast<int>(b), static_cast<int>(e)});
            const auto n_local = static_cast<std::int64_t>(scene.bodies[b].element_dofs[e].size());
            work += n_local * n_local;
        }
    IGA_CHECK(static_cast<int>(owner_.size()) == scene.n_element_blocks, "element blocks do not match the bodies");
    // The factorization's BLAS scales with the same work measure (the tangent's size);
    // small kinematics assembles K0 once on these threads, then only multiplies it.
    library_threads_ = assembly::choose_threads(requested_threads, work, assembly::hardware_threads(),
                                                requested_threads >= 1 ? 0.0 : assembly::system_load());
    if (scene.kinematics == mechanics::Kinematics::finite && library_threads_ > 1)
        team_ = std::make_unique<assembly::ThreadTeam>(library_threads_);
    if (comm.parallel()) {
        first_block_of_dof_.assign(static_cast<std::size_t>(scene.dofs->n_full()), scene.n_element_blocks);
        for (int block = scene.n_element_blocks - 1; block >= 0; --block) {
            const BlockOwner& o = owner_[static_cast<std::size_t>(block)];
            for (int dof : scene.bodies[static_cast<std::size_t>(o.body)].element_dofs[static_cast<std::size_t>(o.element)])
                first_block_of_dof_[static_cast<std::size_t>(dof)] = block;
        }
    }
    // Small kinematics: the threads assemble K0 once; each evaluation is then K0 u.
    const bool small = scene.kinematics == mechanics::Kinematics::small;
    context_.log(Verbosity::verbose,
                 fmt::format("  element {}: {} thread(s) ({} element-tangent entries{})",
                             small ? "stiffness (once, small kinematics)" : "assembly",
                             small ? library_threads_ : n_threads(), work,
                             requested_threads >= 1 ? ", --threads" : ", automatic"));
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
    const PairModel& pair = scene_.pairs[static_cast<std::size_t>(p)];
    if (pair.body[static_cast<std::size_t>(k)] < 0)
        return RowMatrix(0, scene_.dim);
    const assembly::DofMap& dofs = *scene_.dofs;
    const int d = scene_.dim;
    const int b = pair.body[static_cast<std::size_t>(k)];
    const auto& parent = pair.parent_index[static_cast<std::size_t>(k)];
    RowMatrix u(static_cast<Index>(parent.size()), d);
    for (std::size_t a = 0; a < parent.size(); ++a)
        for (int i = 0; i < d; ++i)
            u(static_cast<Index>(a), i) = u_full(dofs.dof(dofs.node_offset(b) + parent[a], i));
    return u;
}

const mechanics::ElementGeometry& SceneSystem::element_of(int block) const
{
    const BlockOwner& o = owner_[static_cast<std::size_t>(block)];
    return scene_.bodies[static_cast<std::size_t>(o.body)].elements[static_cast<std::size_t>(o.element)];
}

const BodyModel& SceneSystem::body_of(int block) const
{
    return scene_.bodies[static_cast<std::size_t>(owner_[static_cast<std::size_t>(block)].body)];
}

const std::vector<int>& SceneSystem::dofs_of(int block) const
{
    const BlockOwner& o = owner_[static_cast<std::size_t>(block)];
    return scene_.bodies[static_cast<std::size_t>(o.body)].element_dofs[static_cast<std::size_t>(o.element)];
}

void SceneSystem::assemble_constant_stiffness(const StopRequest& stop)
{
    if (scene_.kinematics != mechanics::Kinematics::small || full_stiffness_)
        return;
    const int d = scene_.dim;
    auto owns = [&](int block) { return scene_.partition.owns(block); };
    // A pattern over all dofs (none constrained) scatters the element matrices
    // without triplets, and without stored positions (each block is added once).
    const assembly::DofMap& map = *scene_.dofs;
    std::vector<int> nodes_per_body;
    for (int b = 0; b < map.n_bodies(); ++b)
        nodes_per_body.push_back(map.n_nodes(b));
    const assembly::DofMap unconstrained(d, nodes_per_body, {});
    std::vector<std::vector<int>> blocks;
    for (int block = 0; block < scene_.n_element_blocks; ++block)
        blocks.push_back(owns(block) ? dofs_of(block) : std::vector<int>{});
    const assembly::SparsePattern full_pattern(unconstrained, std::move(blocks), scene_.n_element_blocks);
    SparseMatrix K0;
    full_pattern.shape(K0);
    // Once per run, but 20 s on one core for a 3D model of 118k dofs (degree 2): worth the threads.
    std::unique_ptr<assembly::ThreadTeam> team;
    if (library_threads_ > 1)
        team = std::make_unique<assembly::ThreadTeam>(library_threads_);
    full_pattern.for_each_block(
        [&](int block) {
            if (!owns(block))
                return;
            stop.check();
            full_pattern.add(block, mechanics::small_strain_stiffness(element_of(block), body_of(block).material),
                             K0);
        },
        assembly::Execution{team.get()});
    // Symmetric: its upper triangle is kept, half the memory and half the traffic of each K0 u.
    full_stiffness_.emplace(K0.triangularView<Eigen::Upper>());
}

void SceneSystem::assemble_elements(const Vector& u_full, bool need_tangent, Vector& r_full, SparseMatrix& K,
                                    solver::Evaluation& out, Vector& magnitude,
                                    const StopRequest& stop)
{
    const assembly::SparsePattern& pattern = *scene_.pattern;
    const int d = scene_.dim;
    const bool small = scene_.kinematics == mechanics::Kinematics::small;
    auto owns = [&](int block) { return scene_.partition.owns(block); };

    // Small kinematics: the elastic stiffness is assembled once over ALL dofs
    // (constrained rows give the reactions, constrained columns the prescribed
    // displacements), so f_int = K0 u is one sparse product per evaluation. The
    // element matrices are not kept: their assembled form streams a few times
    // less memory than the element-by-element products (3D degree 2: 81^2 entries
    // per span), and each tangent takes K0's free block from it (no second copy).
    if (small && !full_stiffness_)
        assemble_constant_stiffness(stop);
    if (small) {
        // |K0| |u| too: a rigid motion makes K0 u cancel to zero, but not its round-off.
        add_symmetric_product(*full_stiffness_, u_full, r_full, magnitude);
        if (need_tangent)
            add_free_block(*full_stiffness_, *scene_.dofs, K);
    } else {
        std::atomic<bool> failed{false};
        std::mutex message_mutex;
        std::string failure;
        int failed_block = scene_.n_element_blocks;  // the lowest failed block names the failure (deterministic)
        pattern.for_each_block(
            [&](int block) {
                if (block >= scene_.n_element_blocks || !owns(block))
                    return;
                stop.check();  // every block after a stop throws: for_each_block rethrows once all have returned
                const std::vector<int>& dofs = dofs_of(block);
                Vector& f = element_force_[static_cast<std::size_t>(block)];
                const Matrix u_local = local_displacement(u_full, dofs, d);
                const mechanics::ElementResponse response =
                    mechanics::element_response(element_of(block), body_of(block).material, scene_.kinematics, u_local);
                if (response.status != mechanics::ResponseStatus::ok || !response.f_int.allFinite()) {
                    failed.store(true);
                    std::lock_guard<std::mutex> lock(message_mutex);
                    if (block < failed_block) {
                        failed_block = block;
                        failure = inadmissible_message(body_of(block).name, element_of(block), response, u_local);
                    }
                    f = Vector::Zero(static_cast<Index>(dofs.size()));
                    return;
                }
                f = response.f_int;
                if (need_tangent)
                    pattern.add(block, response.K, K);
            },
            assembly::Execution{team_.get()});
        if (failed.load()) {
            out.ok = false;
            out.message = failure;
        }
        // Vectors are scattered serially: cheap, and constrained entries (reactions)
        // may be shared between blocks of one color.
        for (int block = 0; block < scene_.n_element_blocks; ++block) {
            if (!owns(block))
                continue;
            const std::vector<int>& dofs = dofs_of(block);
            const Vector& f = element_force_[static_cast<std::size_t>(block)];
            for (std::size_t k = 0; k < dofs.size(); ++k) {
                r_full(dofs[k]) += f(static_cast<Index>(k));
                magnitude(dofs[k]) += std::abs(f(static_cast<Index>(k)));
            }
        }
    }
}

void SceneSystem::evaluate(const Vector& u_free, double load_factor, bool need_tangent, solver::Evaluation& out)
{
    evaluate_into(u_free, load_factor, need_tangent, out, &context_, nullptr, nullptr);
    // last_active_ counts every pair's Gauss points on every rank: the same verdict on all.
    out.singular_tangent = need_tangent && singular_without_contact_ && last_active_ == 0;
}

Vector SceneSystem::full_residual(const Vector& u_free, double load_factor,
                                  std::vector<contact::PairEvaluation>* contact_out)
{
    solver::Evaluation scratch;
    Vector r_full;
    evaluate_into(u_free, load_factor, false, scratch, nullptr, &r_full, contact_out);
    return r_full;
}

void SceneSystem::evaluate_into(const Vector& u_free, double t, bool need_tangent, solver::Evaluation& out,
                                RunContext* context, Vector* r_full_out,
                                std::vector<contact::PairEvaluation>* contact_out)
{
    const assembly::DofMap& dofs = *scene_.dofs;
    const assembly::SparsePattern& pattern = *scene_.pattern;
    const Partition& partition = scene_.partition;
    const bool root = comm_.root();  // adds the terms that are not split over the ranks
    const int d = scene_.dim;
    const Vector u_full = dofs.expand(u_free, t);
    // One rank alone must not leave on a stop request (see the header): polled in the sum.
    const StopRequest local_stop = context && !comm_.parallel() ? context->stop() : StopRequest{};

    // Contact first: a coupling that the pattern lacks (a Gauss point slid onto a
    // master element not registered yet) extends it before the tangent is made, so
    // every block of this evaluation has its place and K has one pattern throughout.
    std::vector<contact::PairEvaluation> contact;
    if (scene_.has_contact()) {  // no pairs: not even a timer runs
        ScopedTimer timer(context, "contact");
        contact.reserve(scene_.pairs.size());
        for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
            local_stop.check();
            contact.push_back(scene_.pairs[p].pair.evaluate(side_displacement(u_full, static_cast<int>(p), 0),
                                                            side_displacement(u_full, static_cast<int>(p), 1),
                                                            need_tangent, context, t));
            scene_.pairs[p].pair.adopt(std::move(contact.back().trial));
        }
        if (need_tangent)
            register_couplings(contact, context);
    }

    Vector r_full = Vector::Zero(dofs.n_full());
    if (need_tangent) {
        if (!pattern.matches(out.tangent))
            pattern.shape(out.tangent);
        else
            out.tangent.coeffs().setZero();
    } else if (out.tangent.nonZeros() > 0) {
        // A line search's trial states need no tangent: a stale one would keep a
        // tangent-sized block of memory per trial evaluation (docs/performance.md "Memory in 3D").
        release(out.tangent);
    }

    // Per dof, the sum of the absolute values of the terms summed into r: machine
    // epsilon times its norm is the round-off floor of ||r|| (solver::Evaluation).
    Vector magnitude = Vector::Zero(dofs.n_full());
    {
        ScopedTimer timer(context, "elements");
        // Polled per element block only for Newton's evaluations (context given): the
        // output's evaluations of a converged state always finish.
        assemble_elements(u_full, need_tangent, r_full, out.tangent, out, magnitude, local_stop);
    }
    Vector f_int = r_full;  // this rank's part; its constrained entries are the reactions

    // Weak springs on free rigid-body modes (free dofs only, in every element block).
    for (std::size_t k = 0; k < springs_.size(); ++k) {
        if (!owns_spring(k))
            continue;
        const NodeSpring& spring = springs_[k];
        const int n = static_cast<int>(spring.dofs.size());
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double s = spring.stiffness(i, j);
                if (s == 0.0)
                    continue;
                r_full(spring.dofs[static_cast<std::size_t>(i)]) += s * u_full(spring.dofs[static_cast<std::size_t>(j)]);
                if (need_tangent)
                    out.tangent.coeffRef(dofs.free_index(spring.dofs[static_cast<std::size_t>(i)]),
                                         dofs.free_index(spring.dofs[static_cast<std::size_t>(j)])) += s;
            }
    }

    // External loads, each scaled by its amplitude at t: dead ones fixed, follower pressures depending on u.
    double follower_norm = 0.0;  // ||external forces||, summed over the ranks below
    if (root) {
        Vector f_dead = Vector::Zero(dofs.n_full());
        for (const DeadLoad& load : scene_.dead_loads) {
            const double a = load.amplitude(t);
            f_dead += a * load.f;
            magnitude += std::abs(a) * load.f.cwiseAbs();
        }
        r_full -= f_dead;
        follower_norm = f_dead.norm();
    }
    for (const FollowerPressure& follower : scene_.followers) {
        const double a = follower.amplitude(t);
        for (std::size_t e = 0; e < follower.side.elements.size(); ++e) {
            const int block = follower.first_block + static_cast<int>(e);
            if (!partition.owns(block))
                continue;
            const auto& element_dofs = follower.element_dofs[e];
            const Matrix u_local = local_displacement(u_full, element_dofs, d);
            const mechanics::LocalForceTangent f = mechanics::follower_pressure(
                follower.side.elements[e], d, follower.pressure, scene_.kinematics, u_local);
            for (std::size_t k = 0; k < element_dofs.size(); ++k) {
                r_full(element_dofs[k]) -= a * f.f_ext(static_cast<Index>(k));
                magnitude(element_dofs[k]) += std::abs(a) * std::abs(f.f_ext(static_cast<Index>(k)));
            }
            follower_norm += std::abs(a) * f.f_ext.norm();
            if (need_tangent && f.df_ext_du.size() > 0)
                pattern.add(block, Matrix(-a * f.df_ext_du), out.tangent);
        }
    }

    // Contact pairs: residuals, and each coupling's block into its pattern block.
    double contact_norm = 0.0;
    double gap_round_off = 0.0;  // already times machine epsilon
    int active = 0;
    if (scene_.has_contact()) {
        ScopedTimer timer(context, "contact");
        for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
            const PairModel& pair = scene_.pairs[p];
            const contact::PairEvaluation& c = contact[p];
            if (!c.ok) {
                out.ok = false;
                out.message = fmt::format("contact pair '{}': {}", pair.name, c.message);
                continue;
            }
            active += c.n_active;
            if (root)
                for (std::size_t k = 0; k < pair.local_to_full.size(); ++k) {
                    r_full(pair.local_to_full[k]) += c.residual(static_cast<Index>(k));
                    magnitude(pair.local_to_full[k]) += std::abs(c.residual(static_cast<Index>(k)));
                }
            contact_norm += c.residual.norm();
            gap_round_off += contact_gap_round_off(c, pair.pair.settings().law.stiffness());
            if (need_tangent)
                for (const contact::LocalBlock& block : c.tangent) {
                    const int index = pair.blocks.at(block.element);
                    if (partition.owns(index))
                        pattern.add(index, block.K, out.tangent);
                }
        }
    }
    last_active_ = active;

    sum_over_ranks(r_full, magnitude, f_int, follower_norm, out, context);
    const double external_norm = follower_norm;
    double reaction_norm2 = 0.0;
    for (Index k = 0; k < f_int.size(); ++k)
        if (dofs.is_constrained(static_cast<int>(k)))
            reaction_norm2 += f_int(k) * f_int(k);
    const double f_int_norm = f_int.norm();

    out.residual = dofs.restrict(r_full);
    if (r_full_out)
        *r_full_out = r_full;
    if (contact_out)
        *contact_out = std::move(contact);
    out.force_scale = std::max({external_norm, std::sqrt(reaction_norm2), contact_norm, f_int_norm});
    out.residual_floor = std::numeric_limits<double>::epsilon() * dofs.restrict(magnitude).norm() + gap_round_off;
    if (!out.residual.allFinite() && out.ok) {
        out.ok = false;
        out.message = "the residual is not finite";
    }
}

void SceneSystem::sum_over_ranks(Vector& r_full, Vector& magnitude, Vector& f_int, double& follower_norm,
                                 solver::Evaluation& out, RunContext* context) const
{
    if (!comm_.parallel())
        return;
    // A stop request on any rank stops every rank here, together.
    if (comm_.any(context != nullptr && collective_stop_.requested()))
        throw Interrupted();
    comm_.sum(r_full);
    comm_.sum(magnitude);
    comm_.sum(f_int);
    follower_norm = comm_.sum(follower_norm);
    const std::string failure = comm_.first_message(out.ok ? std::string() : out.message);
    if (!failure.empty()) {
        out.ok = false;
        out.message = failure;
    }
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

bool SceneSystem::owns_spring(std::size_t k) const
{
    if (!comm_.parallel())
        return true;
    const int block = first_block_of_dof_[static_cast<std::size_t>(springs_[k].dofs.front())];
    return scene_.partition.owns(block);
}

double SceneSystem::spring_energy(const Vector& u_free, double load_factor) const
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    double energy = 0.0;
    for (const NodeSpring& spring : springs_) {
        VecN u(static_cast<Index>(spring.dofs.size()));
        for (std::size_t i = 0; i < spring.dofs.size(); ++i)
            u(static_cast<Index>(i)) = u_full(spring.dofs[i]);
        energy += 0.5 * u.dot(spring.stiffness * u);
    }
    return energy;
}

double SceneSystem::strain_energy(const Vector& u_free, double load_factor)
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    Vector f_int = Vector::Zero(scene_.dofs->n_full());
    SparseMatrix unused;
    solver::Evaluation scratch;
    Vector magnitude = Vector::Zero(scene_.dofs->n_full());  // the round-off estimate, unused here
    assemble_elements(u_full, false, f_int, unused, scratch, magnitude, StopRequest{});
    comm_.sum(f_int);
    return 0.5 * u_full.dot(f_int);
}

void SceneSystem::register_couplings(const std::vector<contact::PairEvaluation>& contact, RunContext* context)
{
    std::vector<std::vector<int>> new_blocks;
    std::vector<std::pair<std::size_t, contact::Coupling>> owners;
    // Every rank registers the same couplings (the contact evaluation is the same on
    // all); a block another rank assembles keeps its index but no entries here.
    const int first_index = scene_.pattern->n_blocks();
    for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
        const PairModel& pair = scene_.pairs[p];
        for (const contact::LocalBlock& block : contact[p].tangent)
            if (!pair.blocks.contains(block.element)) {
                const bool mine = scene_.partition.owns(first_index + static_cast<int>(owners.size()));
                owners.emplace_back(p, block.element);
                new_blocks.push_back(mine ? coupling_full_dofs(pair, block.element) : std::vector<int>{});
            }
    }
    if (new_blocks.empty())
        return;
    const Index nnz_before = scene_.pattern->n_nonzeros();
    const int first = scene_.pattern->extend(std::move(new_blocks), nullptr, coupling_blocks_searched(scene_.dim));
    for (std::size_t k = 0; k < owners.size(); ++k)
        scene_.pairs[owners[k].first].blocks.emplace(owners[k].second, first + static_cast<int>(k));
    if (context)
        context->log(Verbosity::verbose,
                     fmt::format("  contact: {} new coupling(s) registered, {} new tangent entries", owners.size(),
                                 scene_.pattern->n_nonzeros() - nnz_before));
}

std::vector<contact::PairEvaluation> SceneSystem::contact_state(const Vector& u_free, double load_factor)
{
    const Vector u_full = scene_.dofs->expand(u_free, load_factor);
    std::vector<contact::PairEvaluation> out;
    for (std::size_t p = 0; p < scene_.pairs.size(); ++p) {
        out.push_back(scene_.pairs[p].pair.evaluate(side_displacement(u_full, static_cast<int>(p), 0),
                                                    side_displacement(u_full, static_cast<int>(p), 1), false,
                                                    nullptr, load_factor));
        scene_.pairs[p].pair.adopt(std::move(out.back().trial));
    }
    return out;
}

}  // namespace iga::analysis
