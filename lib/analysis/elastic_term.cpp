#include "analysis/elastic_term.hpp"

#include "core/text.hpp"
#include "assembly/threads.hpp"
#include "mechanics/element.hpp"
#include "mechanics/small_strain_stiffness.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>

namespace iga::analysis {

namespace {

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

ElasticTerm::ElasticTerm(const Scene& scene, RunContext& context, int requested_threads)
    : scene_(scene),
      element_force_(static_cast<std::size_t>(scene.n_element_blocks)),
      element_round_off_(static_cast<std::size_t>(scene.n_element_blocks))
{
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
    const bool small = scene.kinematics == mechanics::Kinematics::small;
    if (!small && library_threads_ > 1)
        team_ = std::make_unique<assembly::ThreadTeam>(library_threads_);
    context.log(Verbosity::verbose,
                fmt::format("  element {}: {} thread(s) ({} element-tangent entries{})",
                            small ? "stiffness (once, small kinematics)" : "assembly",
                            small ? library_threads_ : n_threads(), work,
                            requested_threads >= 1 ? ", --threads" : ", automatic"));
}

const mechanics::ElementGeometry& ElasticTerm::element_of(int block) const
{
    const BlockOwner& o = owner_[static_cast<std::size_t>(block)];
    return scene_.bodies[static_cast<std::size_t>(o.body)].elements[static_cast<std::size_t>(o.element)];
}

const BodyModel& ElasticTerm::body_of(int block) const
{
    return scene_.bodies[static_cast<std::size_t>(owner_[static_cast<std::size_t>(block)].body)];
}

const std::vector<int>& ElasticTerm::dofs_of(int block) const
{
    const BlockOwner& o = owner_[static_cast<std::size_t>(block)];
    return scene_.bodies[static_cast<std::size_t>(o.body)].element_dofs[static_cast<std::size_t>(o.element)];
}

void ElasticTerm::add_to(ModelAssembly& a)
{
    ScopedTimer timer(a.context, "elements");
    // Polled per element block only for Newton's evaluations: the output's
    // evaluations of a converged state always finish.
    Vector f = Vector::Zero(a.r_full.size());
    assemble(a.u_full, f, a.magnitude, a.tangent, &a, a.stop);
    a.r_full += f;
    a.f_int += f;
}

Vector ElasticTerm::internal_forces(const Vector& u_full)
{
    Vector f = Vector::Zero(u_full.size());
    Vector magnitude = Vector::Zero(u_full.size());  // the round-off estimate, unused here
    assemble(u_full, f, magnitude, nullptr, nullptr, StopRequest{});
    return f;
}

void ElasticTerm::assemble(const Vector& u_full, Vector& f, Vector& magnitude, SparseMatrix* tangent,
                           ModelAssembly* failures, const StopRequest& stop)
{
    if (scene_.kinematics != mechanics::Kinematics::small) {
        assemble_finite(u_full, f, magnitude, tangent, failures, stop);
        return;
    }
    // The element matrices are not kept: their assembled form streams a few times
    // less memory than the element-by-element products (3D degree 2: 81^2 entries
    // per span), and each tangent takes K0's free block from it (no second copy).
    if (!full_stiffness_)
        assemble_constant_stiffness(stop);
    add_symmetric_product(*full_stiffness_, u_full, f, magnitude);
    if (tangent)
        add_free_block(*full_stiffness_, *scene_.dofs, *tangent);
}

void ElasticTerm::assemble_finite(const Vector& u_full, Vector& f_out, Vector& magnitude, SparseMatrix* tangent,
                                  ModelAssembly* failures, const StopRequest& stop)
{
    const assembly::SparsePattern& pattern = *scene_.pattern;
    const int d = scene_.dim;
    std::atomic<bool> failed{false};
    std::mutex message_mutex;
    std::string failure;
    int failed_block = scene_.n_element_blocks;  // the lowest failed block names the failure (deterministic)
    pattern.for_each_block(
        [&](int block) {
            if (block >= scene_.n_element_blocks || !scene_.partition.owns(block))
                return;
            stop.check();  // every block after a stop throws: for_each_block rethrows once all have returned
            const std::vector<int>& dofs = dofs_of(block);
            Vector& f = element_force_[static_cast<std::size_t>(block)];
            Vector& round_off = element_round_off_[static_cast<std::size_t>(block)];
            const Matrix u_local = local_displacement(u_full, dofs, d);
            const mechanics::ElementResponse response =
                mechanics::element_response(element_of(block), body_of(block).material, scene_.kinematics, u_local,
                                            tangent != nullptr);
            if (response.status != mechanics::ResponseStatus::ok || !response.f_int.allFinite()) {
                failed.store(true);
                std::lock_guard<std::mutex> lock(message_mutex);
                if (block < failed_block) {
                    failed_block = block;
                    failure = inadmissible_message(body_of(block).name, element_of(block), response, u_local);
                }
                f = Vector::Zero(static_cast<Index>(dofs.size()));
                round_off = f;
                return;
            }
            f = response.f_int;
            round_off = f.cwiseAbs() + response.cancellation;
            if (tangent)
                pattern.add(block, response.K, *tangent);
        },
        assembly::Execution{team_.get()});
    if (failed.load() && failures)
        failures->fail(failure);
    // Vectors are scattered serially: cheap, and constrained entries (reactions)
    // may be shared between blocks of one color.
    for (int block = 0; block < scene_.n_element_blocks; ++block) {
        if (!scene_.partition.owns(block))
            continue;
        const std::vector<int>& dofs = dofs_of(block);
        const Vector& f = element_force_[static_cast<std::size_t>(block)];
        const Vector& round_off = element_round_off_[static_cast<std::size_t>(block)];
        for (std::size_t k = 0; k < dofs.size(); ++k) {
            f_out(dofs[k]) += f(static_cast<Index>(k));
            magnitude(dofs[k]) += round_off(static_cast<Index>(k));
        }
    }
}

void ElasticTerm::assemble_constant_stiffness(const StopRequest& stop)
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

}  // namespace iga::analysis
