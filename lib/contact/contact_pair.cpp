#include "contact/contact_pair.hpp"

#include "boundary/patch_side.hpp"
#include "contact/gpts_kernel.hpp"
#include "contact/projection.hpp"
#include "contact/search.hpp"
#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>

namespace iga::contact {
namespace {

/// Fraction of the larger side's reference size used as the automatic search
/// margin: far above any sensible penalty penetration, small enough to prune.
constexpr double auto_search_fraction = 0.1;
/// Control points closer than this fraction of the coordinates' magnitude count
/// as coincident (a few hundred ulps): such a side is collapsed.
constexpr double collapsed_relative_tolerance = 1e-13;

/// Spatial dimension of a surface: d of a deformable side's points, or the obstacle's.
int surface_dim(const Surface& s)
{
    if (const auto* side = std::get_if<DeformableSide>(&s))
        return side->side.patch.dim();
    return std::get<RigidObstacle>(s).dim();
}

void check_surface(const Surface& s, const char* which, int dim)
{
    if (surface_dim(s) != dim)
        throw Error(std::string("contact: the two surfaces of a pair live in different dimensions"));
    if (const auto* side = std::get_if<DeformableSide>(&s)) {
        const nurbs::Patch& p = side->side.patch;
        if (p.n_par() != dim - 1 || (dim != 2 && dim != 3))
            throw Error(std::string("contact: ") + which + " surface is not a curve in 2D or a surface in 3D");
        const double scale = std::max(1.0, p.control_points().cwiseAbs().maxCoeff());
        if (nurbs::is_collapsed(side->side, collapsed_relative_tolerance * scale))
            throw Error(std::string("contact: ") + which + " surface, side " +
                        std::string(side_name(side->side.side)) + ", is collapsed to a point");
        IGA_CHECK(side->outward_sign == 1 || side->outward_sign == -1, "contact: outward sign must be +1 or -1");
    }
}

/// Current control points of a side: reference + displacement.
RowMatrix current_points(const DeformableSide& s, const RowMatrix& disp)
{
    return s.side.patch.control_points() + disp;
}

class Stopwatch {
public:
    void start() { t0_ = std::chrono::steady_clock::now(); }
    void stop() { seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
    double seconds = 0.0;

private:
    std::chrono::steady_clock::time_point t0_;
};

std::string describe_point(int surface, int g, const VecN& xi, const VecN& x)
{
    std::ostringstream os;
    auto list = [&](const VecN& v) {
        for (Index i = 0; i < v.size(); ++i)
            os << (i ? ", " : "") << v(i);
    };
    os << "Gauss point " << g << " of surface " << (surface == 0 ? "first" : "second") << " (parameter ";
    list(xi);
    os << ", x = (";
    list(x);
    os << "))";
    return os.str();
}

}  // namespace

DeformableSide DeformableSide::make(const nurbs::Patch& parent, Side side)
{
    if (parent.n_par() != parent.dim() || (parent.dim() != 2 && parent.dim() != 3))
        throw Error("contact: a deformable contact side needs a solid patch (2 parameters in 2D, 3 in 3D)");
    const boundary::PatchSide patch_side(parent, side);
    if (patch_side.collapsed())
        throw Error("contact: side " + std::string(side_name(side)) + " is collapsed to a point");
    if (patch_side.outward_sign() == 0)
        throw Error("contact: side " + std::string(side_name(side)) +
                    " has no outward normal (it is degenerate: zero length or area)");
    return DeformableSide{patch_side.side(), patch_side.outward_sign()};
}

ContactPair::ContactPair(PairSettings settings, Surface first, Surface second)
    : settings_(settings), surfaces_{std::move(first), std::move(second)}
{
    IGA_CHECK(std::isfinite(settings_.penalty) && settings_.penalty > 0.0, "contact: penalty must be > 0");
    IGA_CHECK(settings_.quadrature >= 0, "contact: quadrature must be >= 0 (0 = degree + 2)");
    IGA_CHECK(std::isfinite(settings_.search_distance) && settings_.search_distance >= 0.0,
              "contact: search distance must be >= 0");
    dim_ = surface_dim(surfaces_[0]);
    check_surface(surfaces_[0], "first", dim_);
    check_surface(surfaces_[1], "second", dim_);
    const bool deformable[2] = {std::holds_alternative<DeformableSide>(surfaces_[0]),
                                std::holds_alternative<DeformableSide>(surfaces_[1])};
    if (!deformable[0] && !deformable[1])
        throw Error("contact: a pair of two rigid obstacles has no unknowns");

    if (deformable[0] && deformable[1]) {
        if (settings_.formulation == Formulation::two_half_pass)
            carriers_ = {{0, 1, false, {}}, {1, 0, false, {}}};
        else
            carriers_ = {{0, 1, true, {}}};
    } else {
        const int s = deformable[0] ? 0 : 1;
        carriers_ = {{s, 1 - s, false, {}}};
    }

    double size = 0.0;
    for (int i = 0; i < 2; ++i)
        if (deformable[i]) {
            const RowMatrix& cps = std::get<DeformableSide>(surfaces_[i]).side.patch.control_points();
            size = std::max(size, (cps.colwise().maxCoeff() - cps.colwise().minCoeff()).norm());
        }
    search_distance_ = settings_.search_distance > 0.0 ? settings_.search_distance : auto_search_fraction * size;

    for (int i = 0; i < 2; ++i) {
        if (!deformable[i])
            continue;
        const nurbs::Patch& patch = std::get<DeformableSide>(surfaces_[i]).side.patch;
        const std::vector<nurbs::Element> elements = patch.elements();
        for (std::size_t e = 0; e < elements.size(); ++e) {
            VecN mid(patch.n_par());
            for (int k = 0; k < patch.n_par(); ++k)
                mid(k) = 0.5 * (elements[e].lower[static_cast<std::size_t>(k)] + elements[e].upper[static_cast<std::size_t>(k)]);
            element_points_[i].push_back(nurbs::rational_basis(patch, elements[e].span, mid, 0).indices);
        }
    }

    for (Carrier& c : carriers_) {
        const nurbs::Patch& patch = std::get<DeformableSide>(surfaces_[c.slave]).side.patch;
        int max_degree = 0;
        for (int k = 0; k < patch.n_par(); ++k)
            max_degree = std::max(max_degree, patch.degree(k));
        const int n_q = settings_.quadrature > 0 ? settings_.quadrature : max_degree + 2;
        const std::vector<nurbs::Element> elements = patch.elements();
        for (std::size_t e = 0; e < elements.size(); ++e) {
            const nurbs::Element& element = elements[e];
            const quadrature::TensorRule rule = quadrature::element_rule(patch, element, n_q);
            for (Index q = 0; q < rule.weights.size(); ++q) {
                const VecN xi = rule.points.row(q).transpose();
                const nurbs::BasisValues basis = nurbs::rational_basis(patch, element.span, xi, 1);
                const nurbs::PointDerivatives X = nurbs::combine(basis, patch.control_points());
                GaussPoint gp;
                gp.element = static_cast<int>(e);
                gp.xi = xi;
                // W = w_g * reference length (2D) or area (3D) element, |raw normal|.
                gp.weight = rule.weights(q) * boundary::raw_normal(X.dx).norm();
                gp.reference = X.x;
                gp.indices = basis.indices;
                gp.N = basis.R;
                c.points.push_back(std::move(gp));
            }
        }
    }
    trial_xi_.resize(carriers_.size());
    multiplier_.resize(carriers_.size());
    for (std::size_t c = 0; c < carriers_.size(); ++c) {
        trial_xi_[c].assign(carriers_[c].points.size(), Foot{});
        multiplier_[c] = Vector::Zero(static_cast<Index>(carriers_[c].points.size()));
    }
    committed_xi_ = trial_xi_;
    committed_multiplier_ = multiplier_;
}

void ContactPair::update_multipliers(const PairEvaluation& state)
{
    IGA_CHECK(state.ok && state.carriers.size() == carriers_.size(),
              "contact: multipliers are updated from a complete evaluation of the same pair");
    for (std::size_t c = 0; c < carriers_.size(); ++c) {
        const CarrierResult& cr = state.carriers[c];
        IGA_CHECK(cr.pressure.size() == multiplier_[c].size(),
                  "contact: the evaluation has another number of Gauss points than the pair");
        // p = <lambda + eps g_N> where the point is ok, 0 elsewhere: the Uzawa step.
        multiplier_[c] = cr.pressure;
    }
}

void ContactPair::set_penalty(double penalty)
{
    IGA_CHECK(std::isfinite(penalty) && penalty > 0.0, "contact: penalty must be > 0");
    settings_.penalty = penalty;
}

int ContactPair::n_control_points(int i) const
{
    if (const auto* side = std::get_if<DeformableSide>(&surfaces_[i]))
        return side->side.patch.n_control_points();
    return 0;
}

std::vector<int> ContactPair::coupling_dofs(const Coupling& element) const
{
    std::vector<int> dofs;
    for (int i = 0; i < 2; ++i) {
        if (element[i] < 0)
            continue;
        IGA_CHECK(element[i] < n_elements(i), "contact: coupling element out of range");
        const int offset = i == 0 ? 0 : n_control_points(0);
        for (const int a : element_points_[i][static_cast<std::size_t>(element[i])])
            for (int k = 0; k < dim_; ++k)
                dofs.push_back((offset + a) * dim_ + k);
    }
    return dofs;
}

std::vector<Coupling> ContactPair::candidate_couplings() const
{
    std::vector<Coupling> out;
    std::vector<int> candidates;
    for (const Carrier& c : carriers_) {
        auto coupling = [&](int slave_element, int master_element) {
            Coupling e{-1, -1};
            e[static_cast<std::size_t>(c.slave)] = slave_element;
            e[static_cast<std::size_t>(c.master)] = master_element;
            return e;
        };
        const auto* master = std::get_if<DeformableSide>(&surfaces_[c.master]);
        if (!master) {
            for (int e = 0; e < n_elements(c.slave); ++e)
                out.push_back(coupling(e, -1));
            continue;
        }
        const ElementSearch search(master->side.patch, SearchOptions{.distance = search_distance_});
        for (const GaussPoint& gp : c.points) {
            search.candidates(gp.reference, candidates);
            for (const int k : candidates)  // element index of the master side (= span number on a curve)
                out.push_back(coupling(gp.element, k));
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

PairEvaluation ContactPair::evaluate(const RowMatrix& disp_first, const RowMatrix& disp_second, bool need_tangent,
                                     RunContext* ctx, double load_factor) const
{
    const int d = dim_;
    PairEvaluation ev;
    ev.residual = Vector::Zero(n_local_dofs());
    const RowMatrix* disp[2] = {&disp_first, &disp_second};
    const int offset[2] = {0, n_control_points(0)};
    for (int i = 0; i < 2; ++i) {
        const int n_cp = n_control_points(i);
        IGA_CHECK((n_cp == 0 && disp[i]->size() == 0) || (disp[i]->rows() == n_cp && disp[i]->cols() == d),
                  "contact: displacement of a pair surface must be n_cp_side x d (empty for a rigid one)");
        if (!disp[i]->allFinite()) {
            ev.ok = false;
            ev.message = "contact: non-finite displacement on a contact side";
            return ev;
        }
    }
    std::array<RowMatrix, 2> current;
    for (int i = 0; i < 2; ++i)
        if (const auto* side = std::get_if<DeformableSide>(&surfaces_[i]))
            current[i] = current_points(*side, *disp[i]);

    Stopwatch search_time, projection_time;
    auto flush = [&]() {
        if (!ctx)
            return;
        ctx->add_time("contact_search", search_time.seconds);
        ctx->add_time("projection", projection_time.seconds);
        ctx->add_count("contact_candidates", ev.candidates);
        ctx->add_count("projections", ev.projections);
        ctx->add_count("projection_iterations", ev.projection_iterations);
    };
    const KernelSettings kernel_base{.penalty = settings_.penalty, .master_rows = false, .need_tangent = need_tangent};
    std::vector<int> candidates;
    std::map<Coupling, std::size_t> block_of;  // coupling -> index in ev.tangent

    for (std::size_t ci = 0; ci < carriers_.size(); ++ci) {
        const Carrier& c = carriers_[ci];
        const int n_g = static_cast<int>(c.points.size());
        CarrierResult cr;
        cr.surface = c.slave;
        cr.parameter.resize(n_g, d - 1);
        cr.reference_coordinates.resize(n_g, d);
        cr.coordinates.resize(n_g, d);
        cr.gap = Vector::Constant(n_g, -search_distance_);
        cr.pressure = Vector::Zero(n_g);
        cr.multiplier = multiplier_[ci];
        cr.weight.resize(n_g);
        cr.state.assign(n_g, PointState::far);
        for (int g = 0; g < n_g; ++g) {
            const GaussPoint& gp = c.points[g];
            VecN x = VecN::Zero(d);
            for (std::size_t a = 0; a < gp.indices.size(); ++a)
                x += gp.N(a) * current[c.slave].row(gp.indices[a]).transpose();
            cr.parameter.row(g) = gp.xi.transpose();
            cr.reference_coordinates.row(g) = gp.reference.transpose();
            cr.coordinates.row(g) = x.transpose();
            cr.weight(g) = gp.weight;
        }

        // Scatters a kernel's local residual (slave cps then master cps) into the
        // pair's residual and its tangent into the block of the coupling.
        auto scatter = [&](const KernelResult& kr, const GaussPoint& gp, const std::vector<int>& master_indices,
                           int master_element) {
            const std::size_t n_slave = gp.indices.size();
            for (std::size_t a = 0; a < n_slave + master_indices.size(); ++a) {
                const int surface = a < n_slave ? c.slave : c.master;
                const int cp = a < n_slave ? gp.indices[a] : master_indices[a - n_slave];
                for (int i = 0; i < d; ++i)
                    ev.residual((offset[surface] + cp) * d + i) += kr.residual(static_cast<Index>(a) * d + i);
            }
            if (!need_tangent)
                return;
            Coupling key{-1, -1};
            key[static_cast<std::size_t>(c.slave)] = gp.element;
            key[static_cast<std::size_t>(c.master)] = master_element;
            auto [it, inserted] = block_of.try_emplace(key, ev.tangent.size());
            if (inserted) {
                LocalBlock block;
                block.element = key;
                block.dofs = coupling_dofs(key);
                block.K = Matrix::Zero(static_cast<Index>(block.dofs.size()), static_cast<Index>(block.dofs.size()));
                ev.tangent.push_back(std::move(block));
            }
            LocalBlock& block = ev.tangent[it->second];
            // Kernel row/column -> block position: the block lists the first
            // surface element's cps, then the second's (coupling_dofs).
            std::vector<Index> map;
            map.reserve(static_cast<std::size_t>(kr.residual.size()));
            auto position = [&](int surface, int element, int cp) {
                const std::vector<int>& points = element_points_[surface][static_cast<std::size_t>(element)];
                const auto found = std::find(points.begin(), points.end(), cp);
                IGA_ASSERT(found != points.end(), "contact: a basis function outside its element");
                const Index before = surface == 1 && key[0] >= 0
                                         ? static_cast<Index>(element_points_[0][static_cast<std::size_t>(key[0])].size())
                                         : 0;
                return (before + static_cast<Index>(found - points.begin())) * d;
            };
            for (const int a : gp.indices)
                for (int i = 0; i < d; ++i)
                    map.push_back(position(c.slave, gp.element, a) + i);
            for (const int b : master_indices)
                for (int i = 0; i < d; ++i)
                    map.push_back(position(c.master, master_element, b) + i);
            for (std::size_t col = 0; col < map.size(); ++col)
                for (std::size_t row = 0; row < map.size(); ++row)
                    block.K(map[row], map[col]) += kr.tangent(static_cast<Index>(row), static_cast<Index>(col));
        };

        if (const auto* obstacle = std::get_if<RigidObstacle>(&surfaces_[c.master])) {
            for (int g = 0; g < n_g; ++g) {
                const VecN x = cr.coordinates.row(g).transpose();
                const ObstacleFoot foot = obstacle->foot(x, load_factor);
                if (!foot.ok) {
                    ev.ok = false;
                    ev.message = "contact: " + describe_point(c.slave, g, c.points[g].xi, x) +
                                 " is at the centre of the rigid obstacle (no contact normal); the bodies overlap "
                                 "far too much: check the obstacle's position and motion";
                    flush();
                    return ev;
                }
                cr.gap(g) = foot.gap;
                cr.state[g] = PointState::ok;
                KernelSettings point_settings = kernel_base;
                point_settings.multiplier = cr.multiplier(g);
                const KernelResult kr = gpts_rigid_kernel(c.points[g].N, c.points[g].weight, foot.normal, foot.gap,
                                                          point_settings, foot.radius);
                cr.pressure(g) = kr.pressure;
                if (kr.pressure > 0.0) {
                    ++ev.n_active;
                    ev.max_penetration = std::max(ev.max_penetration, foot.gap);
                    scatter(kr, c.points[g], {}, -1);
                }
            }
            ev.carriers.push_back(std::move(cr));
            continue;
        }

        const DeformableSide& master = std::get<DeformableSide>(surfaces_[c.master]);
        const nurbs::Patch master_patch = master.side.patch.with_control_points(current[c.master]);
        search_time.start();
        const ElementSearch search(master_patch, SearchOptions{.distance = search_distance_});
        const bool may_touch = bounding_box(current[c.slave]).overlaps(search.bounds());
        search_time.stop();
        if (!may_touch) {  // the slave side's hull misses every inflated master span box
            ev.carriers.push_back(std::move(cr));
            continue;
        }
        KernelSettings kernel_settings = kernel_base;
        kernel_settings.master_rows = c.master_rows;

        for (int g = 0; g < n_g; ++g) {
            const GaussPoint& gp = c.points[g];
            const VecN x = cr.coordinates.row(g).transpose();
            search_time.start();
            search.candidates(x, candidates);
            search_time.stop();
            if (candidates.empty())
                continue;
            ev.candidates += static_cast<long long>(candidates.size());

            ProjectionOptions options;
            const Foot& warm = trial_xi_[ci][g];
            if (warm.element >= 0) {
                options.start = warm.xi;
                options.start_element = warm.element;
            }
            options.candidate_elements = candidates;  // elements of a curve = its spans, in order
            projection_time.start();
            Projection proj = project_to_surface(master_patch, master.outward_sign, x, options);
            projection_time.stop();
            ++ev.projections;
            ev.projection_iterations += proj.iterations;
            if (proj.status == Projection::Status::failed) {
                ev.ok = false;
                ev.message = "contact: closest-point projection failed at " + describe_point(c.slave, g, gp.xi, x);
                flush();
                return ev;
            }
            trial_xi_[ci][g] = Foot{proj.xi, proj.element};
            cr.gap(g) = proj.gap;
            if (proj.status != Projection::Status::ok) {
                cr.state[g] = proj.status == Projection::Status::off_end ? PointState::off_end : PointState::at_kink;
                continue;
            }
            cr.state[g] = PointState::ok;
            // Active when <lambda + eps g_N> > 0: with a multiplier, also at a small open gap.
            kernel_settings.multiplier = cr.multiplier(g);
            if (!(kernel_settings.multiplier + kernel_settings.penalty * proj.gap > 0.0))
                continue;
            const KernelResult kr = gpts_kernel(gp.N, gp.weight, proj, kernel_settings);
            if (!kr.ok) {
                ev.ok = false;
                ev.message = "contact: the penetration at " + describe_point(c.slave, g, gp.xi, x) +
                             " exceeds the master's radius of curvature (the projection is not a distance "
                             "minimum); try a larger penalty or smaller load steps";
                flush();
                return ev;
            }
            cr.pressure(g) = kr.pressure;
            ++ev.n_active;
            ev.max_penetration = std::max(ev.max_penetration, proj.gap);
            scatter(kr, gp, proj.basis.indices, proj.element);
        }
        ev.carriers.push_back(std::move(cr));
    }
    flush();
    std::sort(ev.tangent.begin(), ev.tangent.end(),
              [](const LocalBlock& a, const LocalBlock& b) { return a.element < b.element; });
    return ev;
}

}  // namespace iga::contact
