#include "analysis/output.hpp"

#include "analysis/contact_term.hpp"

#include "analysis/geometry.hpp"
#include "analysis/point_contact_reference.hpp"
#include "io/deck_names.hpp"

#include "analytic/hertz.hpp"
#include "analytic/pressure_errors.hpp"
#include "boundary/patch_side.hpp"
#include "contact/pressure_recovery.hpp"
#include "nurbs/shapes.hpp"
#include "nurbs/side_patch.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace iga::analysis {

namespace {

const contact::DeformableSide* deformable(const contact::ContactPair& pair, int k)
{
    return std::get_if<contact::DeformableSide>(&pair.surface(k));
}

/// Reference point of `side` that lies deepest along -direction (the first point
/// to touch a plane with outward normal `direction`), by sampling and a parabola fit.
VecN first_touch_point(const nurbs::Patch& side, const VecN& direction)
{
    const auto& knots = side.knots(0);
    constexpr int samples_per_span = 64;
    double best_xi = knots.front(), best = std::numeric_limits<double>::infinity();
    const std::vector<double> breaks = knots.breakpoints();
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
        for (int k = 0; k <= samples_per_span; ++k) {
            const double xi = breaks[s] + (breaks[s + 1] - breaks[s]) * k / samples_per_span;
            VecN p(1);
            p(0) = xi;
            const double h = nurbs::evaluate(side, p, 0).x.dot(direction);
            if (h < best) {
                best = h;
                best_xi = xi;
            }
        }
    // Golden-section polish in a bracket of one sample spacing each way.
    const double spacing = (knots.back() - knots.front()) / (samples_per_span * (breaks.size() - 1));
    double lo = std::max(knots.front(), best_xi - spacing), hi = std::min(knots.back(), best_xi + spacing);
    auto height = [&](double xi) {
        VecN p(1);
        p(0) = xi;
        return nurbs::evaluate(side, p, 0).x.dot(direction);
    };
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int it = 0; it < 80; ++it) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        if (height(a) < height(b))
            hi = b;
        else
            lo = a;
    }
    VecN p(1);
    p(0) = 0.5 * (lo + hi);
    return nurbs::evaluate(side, p, 0).x;
}

/// Closest pair of points of two reference sides, by sampling: the parameter on
/// `a` and the two points.
struct ClosestPair {
    double xi_a;
    VecN x_a, x_b;
};
ClosestPair closest_points(const nurbs::Patch& a, const nurbs::Patch& b)
{
    auto samples = [](const nurbs::Patch& side) {
        std::vector<std::pair<double, VecN>> out;
        const std::vector<double> breaks = side.knots(0).breakpoints();
        for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
            for (int k = 0; k <= 32; ++k) {
                VecN p(1);
                p(0) = breaks[s] + (breaks[s + 1] - breaks[s]) * k / 32.0;
                out.emplace_back(p(0), nurbs::evaluate(side, p, 0).x);
            }
        return out;
    };
    const auto pa = samples(a), pb = samples(b);
    double best = std::numeric_limits<double>::infinity();
    ClosestPair out{pa.front().first, pa.front().second, pb.front().second};
    for (const auto& [xi, x] : pa)
        for (const auto& y : pb)
            if ((x - y.second).squaredNorm() < best) {
                best = (x - y.second).squaredNorm();
                out = {xi, x, y.second};
            }
    return out;
}

std::vector<double> to_std(const VecN& v)
{
    return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

std::vector<io::BodyGeometry> body_geometry(const Scene& scene)
{
    std::vector<io::BodyGeometry> out;
    for (const BodyModel& body : scene.bodies) {
        io::BodyGeometry g;
        g.name = body.name;
        for (const PatchModel& model : body.patches) {
            const nurbs::Patch& patch = model.patch;
            io::PatchGeometry p;
            p.name = model.name;
            for (int dir = 0; dir < patch.n_par(); ++dir) {
                p.degrees.push_back(patch.degree(dir));
                p.knots.push_back(patch.knots(dir).knot_values());
            }
            p.control_points.resize(patch.n_control_points(), patch.dim() + 1);
            p.control_points.leftCols(patch.dim()) = patch.control_points();
            p.control_points.col(patch.dim()) = patch.weights();
            if (body.multi_patch) {
                g.patches.push_back(std::move(p));
            } else {
                g.degrees = std::move(p.degrees);
                g.knots = std::move(p.knots);
                g.control_points = std::move(p.control_points);
            }
        }
        // The table `check` prints: extruded shapes have six sides, a mirror swaps u0 and u1.
        g.side_names = body.side_names;
        out.push_back(std::move(g));
    }
    return out;
}

std::vector<io::Reaction> reactions(const Scene& scene, const Vector& r_full)
{
    std::vector<io::Reaction> out;
    const int d = scene.dim;
    for (const ReactionGroup& group : scene.reactions) {
        io::Reaction r{group.name, std::vector<double>(static_cast<std::size_t>(d), 0.0)};
        for (int dof : group.dofs)
            r.force[static_cast<std::size_t>(dof % d)] += r_full(dof);
        out.push_back(std::move(r));
    }
    return out;
}

namespace {

/// The outward unit normal of the MASTER at a point of a deformable carrying side:
/// minus the side's own current outward normal there (at contact the two agree up
/// to the penalty's discretization error; the slave's is defined everywhere).
VecN master_normal_at(const contact::DeformableSide& side, const RowMatrix& side_displacement, int piece,
                      const VecN& xi)
{
    const contact::SidePiece& p = side.pieces[static_cast<std::size_t>(piece)];
    RowMatrix points = p.side.patch.control_points();
    for (std::size_t a = 0; a < p.surface_index.size(); ++a)
        points.row(static_cast<Index>(a)) += side_displacement.row(p.surface_index[a]);
    const nurbs::BasisValues basis = nurbs::rational_basis(p.side.patch, xi, 1);
    const nurbs::PointDerivatives x = nurbs::combine(basis, points);
    return -static_cast<double>(p.outward_sign) * boundary::raw_normal(x.dx).normalized();
}

/// The friction part of a contact side's results: the converged increment's
/// tangential state (ContactPair::converged_friction: the evaluation behind these
/// results comes after the commit), in space and in the local tangent basis of the
/// master's normal (contact::tangent_basis along the x axis, or y where the
/// normal is near x; the obstacle's normal, or minus the side's own against a
/// deformable master), recovered at the samples component by component as the
/// pressure is, and its resultant. `per_reference_area` (small kinematics): the
/// traction is shown per unit reference area, t j/J, as the pressure is (step_data), so
/// that a slipping point keeps |t| = mu p and sum t W (reference weights) is the friction
/// force; `carrier` is then the rescaled one, whose `stretch` is j/J (1 but for
/// two-half-pass).
void add_friction(io::ContactSideResult& r, const PairModel& model, int carrier_index,
                  const contact::CarrierResult& carrier, const contact::DeformableSide& side,
                  const RowMatrix& side_displacement, double load_factor, int samples_per_span,
                  bool per_reference_area)
{
    const contact::FrictionState& state = model.pair.converged_friction(carrier_index);
    RowMatrix traction = state.traction;
    if (per_reference_area)
        traction.array().colwise() *= carrier.stretch.array();
    const auto* obstacle = std::get_if<contact::RigidObstacle>(&model.pair.surface(1 - carrier.surface));
    const Index n_g = carrier.coordinates.rows();
    const Index d = carrier.coordinates.cols();
    // normal(i): the master's normal at row i of `points` (a Gauss point or a sample).
    auto local = [&](const RowMatrix& traction, const auto& normal) {
        RowMatrix out(traction.rows(), d - 1);
        for (Index i = 0; i < traction.rows(); ++i) {
            const VecN n = normal(i);
            VecN along = VecN::Zero(d);
            along(std::abs(n(0)) > 0.9 ? 1 : 0) = 1.0;
            out.row(i) = (contact::tangent_basis(n, along).transpose() * traction.row(i).transpose()).transpose();
        }
        return out;
    };
    auto gauss_normal = [&](Index g) -> VecN {
        if (obstacle)
            return obstacle->foot(carrier.coordinates.row(g).transpose(), load_factor).normal;
        return master_normal_at(side, side_displacement, carrier.piece[static_cast<std::size_t>(g)],
                                carrier.parameter.row(g).transpose());
    };
    io::GaussPointData& gp = r.gauss_points;
    gp.tangential_traction_vector = traction;
    gp.tangential_traction = local(traction, gauss_normal);
    gp.status.resize(static_cast<std::size_t>(n_g));
    for (Index g = 0; g < n_g; ++g)
        gp.status[static_cast<std::size_t>(g)] = static_cast<int>(state.status[static_cast<std::size_t>(g)]);
    gp.slip_increment = state.slip_increment;
    gp.slip = state.slip;
    if (model.augmented)  // what the Uzawa loop held to gap_tolerance
        gp.elastic_slip = state.elastic_slip;
    r.friction_force.assign(static_cast<std::size_t>(d), 0.0);
    for (Index g = 0; g < n_g; ++g)
        for (Index i = 0; i < d; ++i)
            r.friction_force[static_cast<std::size_t>(i)] += carrier.weight(g) * traction(g, i);

    contact::CarrierResult component = carrier;
    io::PostProcessedData& pp = r.postprocessed;
    pp.tangential_traction_vector.resize(pp.coordinates.rows(), d);
    contact::RecoveredPressure recovered;
    for (Index i = 0; i < d; ++i) {
        component.pressure = traction.col(i);
        recovered = contact::recover_pressure(side, side_displacement, component, samples_per_span);
        pp.tangential_traction_vector.col(i) = recovered.pressure;
    }
    // The samples' pieces: one grid per piece, in piece order (a one-piece side: all piece 0).
    std::vector<int> sample_piece(static_cast<std::size_t>(pp.coordinates.rows()), 0);
    for (std::size_t k = 0, first = 0; k < recovered.grids.size(); ++k) {
        const std::size_t n = static_cast<std::size_t>(recovered.grids[k][0] * recovered.grids[k][1]);
        std::fill(sample_piece.begin() + static_cast<std::ptrdiff_t>(first),
                  sample_piece.begin() + static_cast<std::ptrdiff_t>(first + n), static_cast<int>(k));
        first += n;
    }
    auto sample_normal = [&](Index s) -> VecN {
        if (obstacle)
            return obstacle->foot(pp.coordinates.row(s).transpose(), load_factor).normal;
        return master_normal_at(side, side_displacement, sample_piece[static_cast<std::size_t>(s)],
                                recovered.parameter.row(s).transpose());
    };
    pp.tangential_traction = local(pp.tangential_traction_vector, sample_normal);
}

}  // namespace

namespace {

/// The displacements of every body at a state: per body, or per patch of a multi-patch body.
void add_displacements(const Scene& scene, const SceneSystem& system, const Vector& u_full, io::StepData& step)
{
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
        const BodyModel& body = scene.bodies[b];
        const RowMatrix u = system.body_displacement(u_full, static_cast<int>(b));
        if (!body.multi_patch) {
            step.displacement.emplace_back(body.name, u);
            continue;
        }
        std::vector<std::pair<std::string, RowMatrix>> patches;
        for (const PatchModel& patch : body.patches) {
            RowMatrix up(static_cast<Index>(patch.node.size()), u.cols());
            for (std::size_t a = 0; a < patch.node.size(); ++a)
                up.row(static_cast<Index>(a)) = u.row(patch.node[a]);
            patches.emplace_back(patch.name, std::move(up));
        }
        step.patch_displacement.emplace_back(body.name, std::move(patches));
    }
}

/// The pair's attributes: its counts, the enforcement in effect and where it came
/// from, and the force on a rigid obstacle.
void add_pair_attributes(const Scene& scene, const PairModel& model, const contact::PairEvaluation& state,
                         io::ContactPairResult& result)
{
    result.attributes["n_active"] = state.n_active;
    result.attributes["max_penetration"] = state.max_penetration;
    result.attributes["candidates"] = static_cast<double>(state.candidates);
    result.attributes["projections"] = static_cast<double>(state.projections);
    // The penalty in effect (the augmented Lagrangian's safeguard may have raised it) and where it came from;
    // the exponential law's parameters and slope at touch instead (contact/normal_law.hpp).
    const contact::NormalLaw& law = model.pair.settings().law;
    result.text_attributes["law"] = law.name();
    if (const auto* exponential = law.as_exponential()) {
        result.attributes["law_clearance"] = exponential->clearance;
        result.attributes["law_pressure"] = exponential->pressure;
        result.attributes["law_stiffness"] = law.stiffness();
    } else {
        result.attributes["penalty"] = law.stiffness();
        result.attributes["penalty_initial"] = model.initial_penalty;
        result.text_attributes["penalty_rule"] = model.penalty_auto ? "auto" : "value";
    }
    result.text_attributes["enforcement"] = model.augmented ? "augmented_lagrangian" : "penalty";
    if (model.augmented)
        result.attributes["gap_tolerance"] = model.gap_tolerance_used;
    if (model.pair.settings().friction.active()) {
        result.attributes["friction_coefficient"] = model.pair.settings().friction.coefficient;
        result.attributes["tangential_penalty"] = model.pair.settings().friction.tangential_penalty;
    }
    if (model.penalty_auto) {  // the inputs of the rule eps = min(kappa_side E*/l, c_max E'/h)
        result.attributes["penalty_modulus"] = model.rule.modulus;
        result.attributes["penalty_element_size"] = model.rule.element_size;
        result.attributes["penalty_hertz_modulus"] = model.rule.hertz_modulus;
        result.attributes["penalty_side_size"] = model.rule.side_size;
    }
    if (model.obstacle >= 0) {
        // The body's contact force is -r_c; the obstacle feels the opposite, +r_c.
        const int d = scene.dim;
        result.obstacle_force.assign(static_cast<std::size_t>(d), 0.0);
        for (Index k = 0; k < state.residual.size(); ++k)
            result.obstacle_force[static_cast<std::size_t>(k % d)] += state.residual(k);
    }
}

/// Active points, largest penetration and the measure in contact of one carrying side.
void add_side_attributes(const contact::CarrierResult& carrier, io::ContactSideResult& r)
{
    int active = 0;
    double penetration = 0.0, contact_measure = 0.0;
    for (Index g = 0; g < carrier.pressure.size(); ++g)
        if (carrier.pressure(g) > 0.0) {
            ++active;
            penetration = std::max(penetration, carrier.gap(g));
            contact_measure += carrier.weight(g);
        }
    r.attributes["n_active"] = active;
    r.attributes["max_penetration"] = penetration;
    r.attributes["contact_measure"] = contact_measure;  // length (area in 3D) in contact, measured as the weights
    r.attributes["contact_area"] = contact_measure;     // the same, by the name /history and friction use
}

/// One carrying side of pair p: its Gauss points, the pressure recovered at its
/// control points and sampled, its force, and the friction state.
io::ContactSideResult side_result(const Scene& scene, const PairModel& model, int c,
                                  const contact::CarrierResult& computed, const RowMatrix& side_displacement,
                                  double load_factor, int samples_per_span)
{
    // Small kinematics know one area, the reference one: a pressure integrated over
    // the current surface (two-half-pass) is shown per unit reference area, p j/J,
    // the traction the linear-elastic body carries (docs/theory.md "Two-half-pass balance").
    contact::CarrierResult carrier = computed;
    if (scene.kinematics == mechanics::Kinematics::small) {
        carrier.pressure = carrier.pressure.cwiseProduct(carrier.stretch);
        carrier.weight = carrier.weight.cwiseQuotient(carrier.stretch);
    }
    const contact::DeformableSide* side = deformable(model.pair, carrier.surface);
    IGA_CHECK(side != nullptr, "a rigid surface cannot carry Gauss points");
    const contact::RecoveredPressure recovered =
        contact::recover_pressure(*side, side_displacement, carrier, samples_per_span);
    io::ContactSideResult r;
    r.side_name = model.label[static_cast<std::size_t>(carrier.surface)];
    r.gauss_points.coordinates = carrier.coordinates;
    r.gauss_points.reference_coordinates = carrier.reference_coordinates;
    r.gauss_points.parameter = carrier.parameter;
    r.gauss_points.gap = carrier.gap;
    r.gauss_points.pressure = carrier.pressure;
    r.gauss_points.weight = carrier.weight;
    if (model.augmented)
        r.gauss_points.multiplier = carrier.multiplier;
    r.postprocessed.control_point_pressure = recovered.control_point_pressure;
    r.postprocessed.coordinates = recovered.coordinates;
    r.postprocessed.reference_coordinates = recovered.reference_coordinates;
    r.postprocessed.pressure = recovered.pressure;
    if (side->pieces.size() > 1) {
        // One grid per patch side, samples patch side after patch side.
        r.patch_sides = model.piece_label[static_cast<std::size_t>(carrier.surface)];
        r.gauss_points.patch = carrier.piece;
        for (const std::array<Index, 2>& grid : recovered.grids)
            r.postprocessed.patch_grids.push_back({grid[1], grid[0]});  // [n_v, n_u]; a curve [1, n]
    } else if (recovered.parameter.cols() == 2) {
        r.postprocessed.grid = {recovered.grid[1], recovered.grid[0]};  // [n_v, n_u]
    }
    r.normal_force = recovered.normal_force;
    add_side_attributes(carrier, r);
    if (model.pair.settings().friction.active())
        add_friction(r, model, c, carrier, *side, side_displacement, load_factor, samples_per_span,
                     scene.kinematics == mechanics::Kinematics::small);
    return r;
}

}  // namespace

io::StepData step_data(const Scene& scene, SceneSystem& system, const Vector& u_free, double load_factor,
                       int samples_per_span)
{
    io::StepData step;
    step.load_factor = load_factor;
    const Vector u_full = scene.dofs->expand(u_free, load_factor);
    add_displacements(scene, system, u_full, step);
    // One evaluation gives the reactions and every term's state at this increment,
    // which each term then reports (analysis/term.hpp).
    step.reactions = reactions(scene, system.full_residual(u_free, load_factor));
    system.report(u_free, load_factor, samples_per_span, step);
    return step;
}

namespace {

/// The point-wise disagreement of two half passes: the largest |p_1(x) - p_2(x')| over
/// the post-processed samples x of either side, x' the other side's nearest sample,
/// relative to the larger peak; NaN when neither side is pressed. Only samples in the
/// box of the pressed ones (widened by a tenth) are compared: the zone, not the sides.
double half_pass_pressure_difference(const io::PostProcessedData& first, const io::PostProcessedData& second)
{
    const Index d = first.coordinates.cols();
    double peak = 0.0;
    Eigen::VectorXd lower = Eigen::VectorXd::Constant(d, std::numeric_limits<double>::infinity());
    Eigen::VectorXd upper = -lower;
    for (const io::PostProcessedData* side : {&first, &second})
        for (Index i = 0; i < side->pressure.size(); ++i)
            if (side->pressure(i) > 0.0) {
                peak = std::max(peak, side->pressure(i));
                lower = lower.cwiseMin(side->coordinates.row(i).transpose());
                upper = upper.cwiseMax(side->coordinates.row(i).transpose());
            }
    if (!(peak > 0.0))
        return std::numeric_limits<double>::quiet_NaN();
    const double margin = 0.1 * (upper - lower).norm();
    auto in_zone = [&](const io::PostProcessedData& side) {
        std::vector<Index> out;
        for (Index i = 0; i < side.pressure.size(); ++i)
            if (((side.coordinates.row(i).transpose() - lower).array() >= -margin).all() &&
                ((side.coordinates.row(i).transpose() - upper).array() <= margin).all())
                out.push_back(i);
        return out;
    };
    const std::vector<Index> zone[2] = {in_zone(first), in_zone(second)};
    const io::PostProcessedData* sides[2] = {&first, &second};
    double largest = 0.0;
    for (int s = 0; s < 2; ++s) {
        const io::PostProcessedData& here = *sides[s];
        const io::PostProcessedData& there = *sides[1 - s];
        for (Index i : zone[s]) {
            double nearest = std::numeric_limits<double>::infinity(), p = 0.0;
            for (Index j : zone[1 - s]) {
                const double distance = (here.coordinates.row(i) - there.coordinates.row(j)).squaredNorm();
                if (distance < nearest) {
                    nearest = distance;
                    p = there.pressure(j);
                }
            }
            if (std::isfinite(nearest))
                largest = std::max(largest, std::abs(here.pressure(i) - p));
        }
    }
    return largest / peak;
}

}  // namespace

io::ContactPairResult pair_result(const Scene& scene, int p, const contact::PairEvaluation& state,
                                  const Vector& u_full, double load_factor, int samples_per_span)
{
    const PairModel& model = scene.pairs[static_cast<std::size_t>(p)];
    io::ContactPairResult result;
    result.name = model.name;
    add_pair_attributes(scene, model, state, result);
    for (std::size_t c = 0; c < state.carriers.size(); ++c) {
        const contact::CarrierResult& carrier = state.carriers[c];
        result.sides.push_back(side_result(scene, model, static_cast<int>(c), carrier,
                                           side_displacement(scene, model, u_full, carrier.surface), load_factor,
                                           samples_per_span));
    }
    if (result.sides.size() == 2)  // two half passes: how far apart their pressures are, point by point
        if (const double difference = half_pass_pressure_difference(result.sides[0].postprocessed,
                                                                     result.sides[1].postprocessed);
            std::isfinite(difference))
            result.attributes["half_pass_pressure_difference"] = difference;
    return result;
}

namespace {

/// E and the nu that enters E* of surface k of a pair (a rigid one: E infinite).
void elastic_constants(const Scene& scene, const PairModel& model, int k, double& E, double& nu)
{
    const int b = model.body[static_cast<std::size_t>(k)];
    if (b < 0) {
        E = std::numeric_limits<double>::infinity();
        nu = 0.0;
        return;
    }
    const mechanics::Material& m = scene.bodies[static_cast<std::size_t>(b)].material;
    E = m.E;
    // Plane stress: E* = E (nu drops out); plane strain: E / (1 - nu^2).
    nu = m.plane == mechanics::PlaneMode::stress ? 0.0 : m.nu;
}

/// A 2D Hertz solution placed on the pair: where the first touch is, and the tangent
/// its x runs along (increasing to the right, for plots).
struct PlacedLineContact {
    analytic::HertzLineContact hertz{};
    VecN center = VecN::Zero(2);
    VecN tangent = VecN::Zero(2);
};

PlacedLineContact cylinder_on_plane(const Scene& scene, const PairModel& model, const io::Reference& ref,
                                    io::ReferenceData& data)
{
    PlacedLineContact out;
    data.type = "hertz_cylinder_plane";
    const int k_body = deformable(model.pair, 0) ? 0 : 1;
    const int k_plane = 1 - k_body;
    double E, nu;
    elastic_constants(scene, model, k_body, E, nu);
    out.hertz = analytic::hertz_cylinder_plane(E, nu, ref.radius, ref.force);
    VecN normal(2);
    const auto* obstacle = std::get_if<contact::RigidObstacle>(&model.pair.surface(k_plane));
    if (const auto* plane = obstacle ? std::get_if<contact::RigidPlane>(&obstacle->shape) : nullptr)
        normal = plane->normal;
    else
        normal << 0.0, 1.0;
    out.tangent << normal(1), -normal(0);
    // The deepest of the pieces' first-touch points.
    const contact::DeformableSide* surface = deformable(model.pair, k_body);
    double deepest = std::numeric_limits<double>::infinity();
    for (const contact::SidePiece& piece : surface->pieces) {
        const VecN x = first_touch_point(piece.side.patch, normal);
        if (x.dot(normal) < deepest) {
            deepest = x.dot(normal);
            out.center = x;
        }
    }
    data.inputs["radius"] = ref.radius;
    data.inputs["E"] = E;
    data.inputs["nu"] = nu;
    return out;
}

PlacedLineContact two_cylinders(const Scene& scene, const PairModel& model, const io::Reference& ref,
                                io::ReferenceData& data)
{
    PlacedLineContact out;
    data.type = "hertz_two_cylinders";
    double E1, nu1, E2, nu2;
    elastic_constants(scene, model, 0, E1, nu1);
    elastic_constants(scene, model, 1, E2, nu2);
    out.hertz = analytic::hertz_two_cylinders(E1, nu1, ref.radii[0], E2, nu2, ref.radii[1], ref.force);
    const contact::DeformableSide* s0 = deformable(model.pair, 0);
    const contact::DeformableSide* s1 = deformable(model.pair, 1);
    IGA_CHECK(s0 && s1, "hertz_two_cylinders needs two deformable sides");
    double nearest = std::numeric_limits<double>::infinity();
    for (const contact::SidePiece& a : s0->pieces)
        for (const contact::SidePiece& b : s1->pieces) {
            const ClosestPair closest = closest_points(a.side.patch, b.side.patch);
            const double gap = (closest.x_a - closest.x_b).norm();
            if (gap >= nearest)
                continue;
            nearest = gap;
            out.center = 0.5 * (closest.x_a + closest.x_b);
            VecN p(1);
            p(0) = closest.xi_a;
            out.tangent = nurbs::evaluate(a.side.patch, p, 1).dx.col(0).normalized();
        }
    data.inputs["radius_first"] = ref.radii[0];
    data.inputs["radius_second"] = ref.radii[1];
    return out;
}

/// The analytic pressure curve over [-1.5 a, 1.5 a] along the tangent.
void sample_curve(const PlacedLineContact& placed, io::ReferenceData& data)
{
    constexpr int n_curve = 601;
    const analytic::HertzLineContact& hertz = placed.hertz;
    data.x.resize(n_curve);
    data.pressure.resize(n_curve);
    data.coordinates.resize(n_curve, 2);
    for (int i = 0; i < n_curve; ++i) {
        const double x = -1.5 * hertz.a + 3.0 * hertz.a * i / (n_curve - 1);
        data.x(i) = x;
        data.pressure(i) = hertz.pressure(x);
        data.coordinates.row(i) = (placed.center + x * placed.tangent).transpose();
    }
}

/// Peak, half-width and L2 errors of pressures p at reference coordinates X, named
/// `tag` + peak / half_width / l2.
void add_line_errors(const PlacedLineContact& placed, const RowMatrix& X, const Vector& p, const std::string& tag,
                     io::ReferenceData& data)
{
    std::vector<double> xs, ps;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (Index i = 0; i < X.rows(); ++i) {
        const double x = (X.row(i).transpose() - placed.center).dot(placed.tangent);
        xs.push_back(x);
        ps.push_back(p(i));
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    if (xs.empty())
        return;
    // A symmetric half model covers one side of x = 0 only: count it twice.
    const double slack = 1e-8 * std::max(1.0, placed.hertz.a);
    const bool mirror = lo >= -slack || hi <= slack;
    const analytic::PressureErrors e = analytic::pressure_errors(placed.hertz, xs, ps, mirror);
    data.errors[tag + "peak"] = e.peak;
    data.errors[tag + "half_width"] = e.half_width;
    data.errors[tag + "l2"] = e.l2;
}

/// Errors of this run (last converged increment) over reference coordinates.
void add_step_errors(const PlacedLineContact& placed, const io::StepData& step, const std::string& pair_name,
                     io::ReferenceData& data)
{
    for (const io::ContactPairResult& pair : step.contact) {
        if (pair.name != pair_name)
            continue;
        for (std::size_t s = 0; s < pair.sides.size(); ++s) {
            const io::ContactSideResult& side = pair.sides[s];
            const std::string prefix = s == 0 ? "" : side.side_name + ".";
            add_line_errors(placed, side.postprocessed.reference_coordinates, side.postprocessed.pressure, prefix,
                            data);
            add_line_errors(placed, side.gauss_points.reference_coordinates, side.gauss_points.pressure,
                            prefix + "gauss_", data);
            // Force balance: the contact resultant against the force of the (modelled part of the) load.
            if (s == 0)
                data.errors["normal_force"] = side.normal_force;
        }
    }
}

}  // namespace

std::vector<io::ReferenceData> references(const Scene& scene, const io::StepData* step)
{
    std::vector<io::ReferenceData> out;
    if (!scene.settings.output.reference)
        return out;
    const io::Reference& ref = *scene.settings.output.reference;
    const PairModel* model = nullptr;
    for (const PairModel& p : scene.pairs)
        if (p.name == ref.pair)
            model = &p;
    IGA_CHECK(model != nullptr, "the deck reader let a reference to an unknown pair through");
    if (io::is_point_contact(ref.type)) {  // 3D: sphere on a plane, two spheres
        out.push_back(point_contact_reference(scene, *model, step));
        return out;
    }
    io::ReferenceData data;
    data.pair = ref.pair;
    PlacedLineContact placed = ref.type == io::ReferenceType::hertz_cylinder_plane
                                   ? cylinder_on_plane(scene, *model, ref, data)
                                   : two_cylinders(scene, *model, ref, data);
    if (placed.tangent(0) < 0 || (placed.tangent(0) == 0 && placed.tangent(1) < 0))
        placed.tangent = -placed.tangent;  // x increases to the right, for plots
    data.inputs["force"] = ref.force;
    data.inputs["E_star"] = placed.hertz.E_star;
    data.inputs["R_star"] = placed.hertz.R_star;
    data.a = placed.hertz.a;
    data.p0 = placed.hertz.p0;
    data.center = to_std(placed.center);
    data.tangent = to_std(placed.tangent);
    sample_curve(placed, data);
    if (step)
        add_step_errors(placed, *step, ref.pair, data);
    out.push_back(std::move(data));
    return out;
}

}  // namespace iga::analysis
