#include "contact/contact_pair.hpp"

#include "nurbs/coincidence.hpp"

#include "boundary/patch_side.hpp"
#include "contact/gpts_friction.hpp"
#include "contact/gpts_kernel.hpp"
#include "contact/projection.hpp"
#include "contact/search.hpp"
#include "core/error.hpp"
#include "quadrature/gauss.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

namespace iga::contact {
namespace {

/// A Gauss point at rest within this fraction of the master's size from it touches:
/// round-off of the closest-point projection (which is accurate to ~1e-15 of it).
constexpr double touching_tolerance = 1e-12;

/// A penalty point at the kink of <lambda + eps g_N>, to round-off of the master's size:
/// touching, neither pressed nor apart (KernelSettings::touching).
bool touches_at_kink(double gap, const KernelSettings& settings, double size)
{
    const NormalLaw::Penalty* law = settings.law.as_penalty();
    return law && std::abs(settings.multiplier + law->penalty * (gap - settings.gap_offset)) <=
                      law->penalty * touching_tolerance * size;
}

/// Spatial dimension of a surface: d of a deformable side's points, or the obstacle's.
int surface_dim(const Surface& s)
{
    if (const auto* side = std::get_if<DeformableSide>(&s))
        return side->pieces.front().side.patch.dim();
    return std::get<RigidObstacle>(s).dim();
}

void check_surface(const Surface& s, const char* which, int dim)
{
    if (surface_dim(s) != dim)
        throw Error(std::string("contact: the two surfaces of a pair live in different dimensions"));
    if (const auto* surface = std::get_if<DeformableSide>(&s)) {
        IGA_CHECK(!surface->pieces.empty(), "contact: a deformable surface needs at least one side");
        for (const SidePiece& piece : surface->pieces) {
            const nurbs::Patch& p = piece.side.patch;
            if (p.dim() != dim)
                throw Error(std::string("contact: the pieces of a surface live in different dimensions"));
            if (p.n_par() != dim - 1 || (dim != 2 && dim != 3))
                throw Error(std::string("contact: ") + which + " surface is not a curve in 2D or a surface in 3D");
            if (nurbs::is_collapsed(piece.side, nurbs::coincidence_tolerance(p.control_points())))
                throw Error(std::string("contact: ") + which + " surface, side " +
                            std::string(side_name(piece.side.side)) + ", is collapsed to a point");
            IGA_CHECK(piece.outward_sign == 1 || piece.outward_sign == -1, "contact: outward sign must be +1 or -1");
            IGA_CHECK(static_cast<int>(piece.surface_index.size()) == p.n_control_points(),
                      "contact: a surface piece needs a surface index per control point");
        }
    }
}

/// W = w_g j and dW/du (n_s d) at a Gauss point whose carrying surface has current
/// control points `points` (rows `indices`): with the current tangents a = sum_c x_c dN_c
/// (d x q) and metric m = a^T a, j = sqrt(det m) and dj/dx_c = j a m^-1 dN_c^T (the
/// contravariant basis a^al = a m^-1 along dN_c,al), in 2D dj/dx_c = dN_c a / |a|.
std::pair<double, Vector> current_weight(double rule_weight, const Matrix& dN, const std::vector<int>& indices,
                                         const RowMatrix& points)
{
    const Index d = points.cols();
    const Index n_s = dN.rows();
    Matrix a = Matrix::Zero(d, dN.cols());
    for (Index c = 0; c < n_s; ++c)
        a += points.row(indices[static_cast<std::size_t>(c)]).transpose() * dN.row(c);
    const Matrix m = a.transpose() * a;
    const double j = std::sqrt(std::max(m.determinant(), 0.0));
    Vector dW = Vector::Zero(n_s * d);
    if (j > 0.0) {
        const Matrix contravariant = a * m.inverse();  // d x q
        for (Index c = 0; c < n_s; ++c)
            dW.segment(c * d, d) = rule_weight * j * contravariant * dN.row(c).transpose();
    }
    return {rule_weight * j, dW};
}

/// Current control points of a surface: reference + displacement.
RowMatrix current_points(const DeformableSide& s, const RowMatrix& disp)
{
    return s.control_points() + disp;
}

/// The rows of `surface_points` of a piece's control points.
RowMatrix piece_points(const SidePiece& piece, const RowMatrix& surface_points)
{
    RowMatrix out(static_cast<Index>(piece.surface_index.size()), surface_points.cols());
    for (std::size_t a = 0; a < piece.surface_index.size(); ++a)
        out.row(static_cast<Index>(a)) = surface_points.row(piece.surface_index[a]);
    return out;
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

namespace {

SidePiece make_piece(const nurbs::Patch& parent, Side side)
{
    if (parent.n_par() != parent.dim() || (parent.dim() != 2 && parent.dim() != 3))
        throw Error("contact: a deformable contact side needs a solid patch (2 parameters in 2D, 3 in 3D)");
    const boundary::PatchSide patch_side(parent, side);
    if (patch_side.collapsed())
        throw Error("contact: side " + std::string(side_name(side)) + " is collapsed to a point");
    if (patch_side.outward_sign() == 0)
        throw Error("contact: side " + std::string(side_name(side)) +
                    " has no outward normal (it is degenerate: zero length or area)");
    return SidePiece{patch_side.side(), patch_side.outward_sign(), {}};
}

}  // namespace

DeformableSide DeformableSide::make(const nurbs::Patch& parent, Side side)
{
    DeformableSide out;
    out.pieces.push_back(make_piece(parent, side));
    SidePiece& piece = out.pieces.front();
    out.n_control_points = piece.side.patch.n_control_points();
    piece.surface_index.resize(static_cast<std::size_t>(out.n_control_points));
    for (int a = 0; a < out.n_control_points; ++a)
        piece.surface_index[static_cast<std::size_t>(a)] = a;
    return out;
}

DeformableSide DeformableSide::make(const std::vector<const nurbs::Patch*>& parents, const std::vector<Side>& sides,
                                    const std::vector<std::vector<int>>& parent_node, std::vector<int>& surface_node)
{
    IGA_CHECK(!parents.empty() && parents.size() == sides.size() && parents.size() == parent_node.size(),
              "contact: one side and one node map per parent patch");
    DeformableSide out;
    surface_node.clear();
    std::map<int, int> surface_of_node;
    for (std::size_t k = 0; k < parents.size(); ++k) {
        SidePiece piece = make_piece(*parents[k], sides[k]);
        for (const int parent_cp : piece.side.parent_index) {
            const int node = parent_node[k][static_cast<std::size_t>(parent_cp)];
            const auto [it, fresh] = surface_of_node.try_emplace(node, static_cast<int>(surface_node.size()));
            if (fresh)
                surface_node.push_back(node);
            piece.surface_index.push_back(it->second);
        }
        out.pieces.push_back(std::move(piece));
    }
    out.n_control_points = static_cast<int>(surface_node.size());
    return out;
}

RowMatrix DeformableSide::control_points() const
{
    RowMatrix out(n_control_points, pieces.front().side.patch.dim());
    for (const SidePiece& piece : pieces)
        for (std::size_t a = 0; a < piece.surface_index.size(); ++a)
            out.row(piece.surface_index[a]) = piece.side.patch.control_points().row(static_cast<Index>(a));
    return out;
}

int DeformableSide::n_elements() const
{
    int n = 0;
    for (const SidePiece& piece : pieces)
        n += static_cast<int>(piece.side.patch.elements().size());
    return n;
}

int DeformableSide::first_element(int k) const
{
    int n = 0;
    for (int j = 0; j < k; ++j)
        n += static_cast<int>(pieces[static_cast<std::size_t>(j)].side.patch.elements().size());
    return n;
}

/// The evaluation's stopwatches and the candidate list reused over its Gauss points.
struct ContactPair::Timing {
    Stopwatch& search;
    Stopwatch& projection;
    std::vector<int>& candidates;
};

ContactPair::ContactPair(PairSettings settings, Surface first, Surface second)
    : settings_(settings), surfaces_{std::move(first), std::move(second)}
{
    IGA_CHECK(settings_.law.valid(), settings_.law.as_penalty()
                                         ? "contact: penalty must be > 0"
                                         : "contact: the exponential law's clearance and pressure must be > 0");
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
    IGA_CHECK(std::isfinite(settings_.friction.coefficient) && settings_.friction.coefficient >= 0.0,
              "contact: the friction coefficient must be >= 0");
    IGA_CHECK(!settings_.friction.active() || (std::isfinite(settings_.friction.tangential_penalty) &&
                                               settings_.friction.tangential_penalty > 0.0),
              "contact: friction needs a tangential penalty > 0");

    if (deformable[0] && deformable[1]) {
        if (settings_.formulation == Formulation::two_half_pass)
            carriers_ = {{0, 1, false, true, {}}, {1, 0, false, true, {}}};
        else
            carriers_ = {{0, 1, true, false, {}}};
    } else {
        const int s = deformable[0] ? 0 : 1;
        carriers_ = {{s, 1 - s, false, false, {}}};
    }

    double size = 0.0;
    for (int i = 0; i < 2; ++i)
        if (deformable[i]) {
            const RowMatrix cps = std::get<DeformableSide>(surfaces_[i]).control_points();
            size = std::max(size, (cps.colwise().maxCoeff() - cps.colwise().minCoeff()).norm());
        }
    search_distance_ = settings_.search_distance > 0.0 ? settings_.search_distance : auto_search_fraction * size;
    search_distance_ = std::max(search_distance_, search_reach_factor * settings_.law.reach());

    for (int i = 0; i < 2; ++i) {
        if (!deformable[i])
            continue;
        const DeformableSide& surface = std::get<DeformableSide>(surfaces_[i]);
        reference_points_[static_cast<std::size_t>(i)] = surface.control_points();
        trial_points_[static_cast<std::size_t>(i)] = committed_points_[static_cast<std::size_t>(i)] =
            surface.control_points();
        for (const SidePiece& piece : surface.pieces) {
            const nurbs::Patch& patch = piece.side.patch;
            const std::vector<nurbs::Element> elements = patch.elements();
            for (std::size_t e = 0; e < elements.size(); ++e) {
                VecN mid(patch.n_par());
                for (int k = 0; k < patch.n_par(); ++k)
                    mid(k) = 0.5 * (elements[e].lower[static_cast<std::size_t>(k)] + elements[e].upper[static_cast<std::size_t>(k)]);
                std::vector<int> points = nurbs::rational_basis(patch, elements[e].span, mid, 0).indices;
                for (int& a : points)
                    a = piece.surface_index[static_cast<std::size_t>(a)];
                element_points_[i].push_back(std::move(points));
            }
            // Edges shared with another piece: all their control points belong to it too.
            std::array<std::array<bool, 2>, 2> inner{};
            const int q = patch.n_par();
            const std::array<int, 2> n{patch.n_basis(0), q > 1 ? patch.n_basis(1) : 1};
            for (int k = 0; k < q; ++k)
                for (int end = 0; end < 2; ++end) {
                    bool shared = surface.pieces.size() > 1;
                    for (int a = 0; a < n[0] * n[1] && shared; ++a) {
                        const int ik = k == 0 ? a % n[0] : a / n[0];
                        if (ik != (end ? n[k] - 1 : 0))
                            continue;
                        const int s = piece.surface_index[static_cast<std::size_t>(a)];
                        bool elsewhere = false;
                        for (const SidePiece& other : surface.pieces)
                            if (&other != &piece &&
                                std::find(other.surface_index.begin(), other.surface_index.end(), s) !=
                                    other.surface_index.end())
                                elsewhere = true;
                        shared = elsewhere;
                    }
                    inner[k][end] = shared;
                }
            inner_edge_[i].push_back(inner);
        }
    }

    for (Carrier& c : carriers_) {
        const DeformableSide& surface = std::get<DeformableSide>(surfaces_[c.slave]);
        for (std::size_t piece_index = 0; piece_index < surface.pieces.size(); ++piece_index) {
        const SidePiece& piece = surface.pieces[piece_index];
        const nurbs::Patch& patch = piece.side.patch;
        const int first = surface.first_element(static_cast<int>(piece_index));
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
                gp.piece = static_cast<int>(piece_index);
                gp.element = first + static_cast<int>(e);
                gp.xi = xi;
                // W = w_g * reference length (2D) or area (3D) element, |raw normal|.
                gp.rule_weight = rule.weights(q);
                gp.weight = rule.weights(q) * boundary::raw_normal(X.dx).norm();
                gp.reference = X.x;
                gp.indices = basis.indices;
                for (int& a : gp.indices)
                    a = piece.surface_index[static_cast<std::size_t>(a)];
                gp.N = basis.R;
                gp.dN = basis.dR;
                c.points.push_back(std::move(gp));
            }
        }
        }
    }
    // Friction: every point anchored where it starts, in the frame of an obstacle
    // placed where it is at t = 0 (an amplitude may start away from zero).
    committed_.resize(carriers_.size());
    initial_overlap_.resize(carriers_.size());
    for (std::size_t c = 0; c < carriers_.size(); ++c) {
        const auto* obstacle = std::get_if<RigidObstacle>(&surfaces_[static_cast<std::size_t>(carriers_[c].master)]);
        const VecN start = obstacle ? obstacle->shift(0.0) : VecN(VecN::Zero(dim_));
        for (const GaussPoint& gp : carriers_[c].points) {
            ContactPointState point;
            // Against a deformable master the anchor is a material point of the master: none
            // until the point first touches (gpts_friction.hpp).
            point.friction = FrictionHistory{gp.reference - start, 0.0, obstacle != nullptr, false};
            point.tangential_multiplier = VecN::Zero(dim_);
            point.clear_response(dim_);
            committed_[c].push_back(std::move(point));
        }
        // Zeros: no overclosure until set_initial_overlap().
        initial_overlap_[c] = Vector::Zero(static_cast<Index>(carriers_[c].points.size()));
    }
    if (settings_.friction.active())
        anchor_on_reference_masters();
    trial_ = committed_;
}

void ContactPointState::clear_response(int d)
{
    status = StickSlip::open;
    traction = VecN::Zero(d);
    frame_traction = VecN::Zero(d);
    slip_increment = 0.0;
    elastic_slip = 0.0;
}

void ContactPointState::record(const TangentialResponse& t)
{
    friction = t.next;
    status = t.status;
    traction = t.traction;
    frame_traction = t.frame_traction;
    slip_increment = t.slip_increment;
    elastic_slip = t.elastic_slip;
}

void ContactPair::adopt(PairState trial)
{
    IGA_CHECK(trial.carriers.size() == trial_.size(), "contact: a pair adopts the state of its own evaluation");
    for (std::size_t c = 0; c < trial_.size(); ++c)
        IGA_CHECK(trial.carriers[c].size() == trial_[c].size(),
                  "contact: a pair adopts the state of its own evaluation");
    trial_ = std::move(trial.carriers);
    trial_points_ = std::move(trial.points);
}

void ContactPair::commit()
{
    // Lost contact, lost traction: an open point starts its next touch from lambda_T = 0.
    for (std::vector<ContactPointState>& points : trial_)
        for (ContactPointState& point : points)
            if (point.status == StickSlip::open)
                point.tangential_multiplier.setZero();
    committed_ = trial_;
    committed_points_ = trial_points_;
}

bool ContactPair::hold_open(int carrier, int g)
{
    IGA_CHECK(carrier >= 0 && carrier < n_carriers() && g >= 0 && g < n_gauss_points(carrier),
              "contact: hold_open of a Gauss point the pair does not have");
    if (held_.empty())
        for (const Carrier& c : carriers_)
            held_.emplace_back(c.points.size(), 0);
    char& flag = held_[static_cast<std::size_t>(carrier)][static_cast<std::size_t>(g)];
    const bool was_free = !flag;
    flag = 1;
    return was_free;
}

void ContactPair::release_hold(int carrier, int g)
{
    if (held(static_cast<std::size_t>(carrier), g))
        held_[static_cast<std::size_t>(carrier)][static_cast<std::size_t>(g)] = 0;
}

FrictionState ContactPair::friction_state(const std::vector<ContactPointState>& points) const
{
    const Index n_g = static_cast<Index>(points.size());
    FrictionState out;
    out.status.resize(points.size());
    out.traction.resize(n_g, dim_);
    out.slip_increment.resize(n_g);
    out.slip.resize(n_g);
    out.elastic_slip.resize(n_g);
    out.frame_traction.resize(n_g, dim_);
    for (Index g = 0; g < n_g; ++g) {
        const ContactPointState& point = points[static_cast<std::size_t>(g)];
        out.status[static_cast<std::size_t>(g)] = point.status;
        out.traction.row(g) = point.traction.transpose();
        out.slip_increment(g) = point.slip_increment;
        out.slip(g) = point.friction.slip;
        out.elastic_slip(g) = point.elastic_slip;
        out.frame_traction.row(g) = point.frame_traction.transpose();
    }
    return out;
}

FrictionState ContactPair::converged_friction(int carrier) const
{
    return friction_state(committed_[static_cast<std::size_t>(carrier)]);
}

RowMatrix ContactPair::tangential_multipliers(int carrier) const
{
    const std::vector<ContactPointState>& points = trial_[static_cast<std::size_t>(carrier)];
    RowMatrix out(static_cast<Index>(points.size()), dim_);
    for (std::size_t g = 0; g < points.size(); ++g)
        out.row(static_cast<Index>(g)) = points[g].tangential_multiplier.transpose();
    return out;
}

Vector ContactPair::multipliers(int carrier) const
{
    const std::vector<ContactPointState>& points = trial_[static_cast<std::size_t>(carrier)];
    Vector out(static_cast<Index>(points.size()));
    for (std::size_t g = 0; g < points.size(); ++g)
        out(static_cast<Index>(g)) = points[g].multiplier;
    return out;
}

void ContactPair::anchor_on_reference_masters()
{
    // A point touching at rest (gap >= 0, to round-off of the surface's size) sticks to
    // the master material point under it: the foot of its reference position on the
    // master's reference surface. Others are anchored where they first touch.
    PairEvaluation scratch;
    Stopwatch search, projection;
    std::vector<int> candidates;
    Timing timing{search, projection, candidates};
    for (std::size_t ci = 0; ci < carriers_.size(); ++ci) {
        const Carrier& c = carriers_[ci];
        const auto* master = std::get_if<DeformableSide>(&surfaces_[static_cast<std::size_t>(c.master)]);
        if (!master)
            continue;
        const MasterView view = master_view(*master, reference_points_[static_cast<std::size_t>(c.master)],
                                            search_distance_);
        for (std::size_t g = 0; g < c.points.size(); ++g) {
            bool failed = false;
            const std::optional<Projection> foot =
                project_on_master(c.master, view, c.points[g].reference, Foot{}, scratch, timing, failed);
            if (!failed && foot && foot->status == Projection::Status::ok &&
                foot->gap >= -touching_tolerance * view.size)
                committed_[ci][g].friction = FrictionHistory{foot->point, 0.0, true, false};
        }
    }
}

bool ContactPair::has_initial_overlap() const
{
    for (const Vector& g0 : initial_overlap_)
        if (g0.size() > 0 && g0.maxCoeff() > 0.0)
            return true;
    return false;
}

void ContactPair::set_initial_overlap(std::vector<Vector> g0, double release_end)
{
    IGA_CHECK(std::isfinite(release_end) && release_end > 0.0, "contact: the overlap is released by a load factor > 0");
    release_end_ = release_end;
    IGA_CHECK(g0.size() == carriers_.size(), "contact: one initial overlap vector per carrier");
    for (std::size_t c = 0; c < carriers_.size(); ++c)
        IGA_CHECK(g0[c].size() == static_cast<Index>(carriers_[c].points.size()) && g0[c].allFinite() &&
                      (g0[c].array() >= 0.0).all(),
                  "contact: an initial overlap is finite, >= 0, one per Gauss point");
    initial_overlap_ = std::move(g0);
}

void ContactPair::update_multipliers(const PairEvaluation& state)
{
    IGA_CHECK(state.ok && state.carriers.size() == carriers_.size(),
              "contact: multipliers are updated from a complete evaluation of the same pair");
    for (std::size_t c = 0; c < carriers_.size(); ++c) {
        const CarrierResult& cr = state.carriers[c];
        std::vector<ContactPointState>& points = trial_[c];
        IGA_CHECK(cr.pressure.size() == static_cast<Index>(points.size()),
                  "contact: the evaluation has another number of Gauss points than the pair");
        // p = <lambda + eps g_N> where the point is ok, 0 elsewhere: the Uzawa step;
        // with friction lambda_T <- t_T, the traction returned to the cone of that p.
        const bool friction = settings_.friction.active();
        IGA_CHECK(!friction || cr.friction.frame_traction.rows() == cr.pressure.size(),
                  "contact: a frictional evaluation reports each point's traction in its anchor's frame");
        for (std::size_t g = 0; g < points.size(); ++g) {
            points[g].multiplier = settings_.law.updated_multiplier(cr.pressure(static_cast<Index>(g)));
            if (friction)
                points[g].tangential_multiplier = cr.friction.frame_traction.row(static_cast<Index>(g)).transpose();
        }
    }
}

void ContactPair::set_penalty(double penalty)
{
    settings_.law.set_penalty(penalty);
}

int ContactPair::n_control_points(int i) const
{
    if (const auto* side = std::get_if<DeformableSide>(&surfaces_[i]))
        return side->n_control_points;
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
        for (std::size_t k = 0; k < master->pieces.size(); ++k) {
            const ElementSearch search(master->pieces[k].side.patch, SearchOptions{.distance = search_distance_});
            const int first = master->first_element(static_cast<int>(k));
            for (const GaussPoint& gp : c.points) {
                search.candidates(gp.reference, candidates);
                for (const int e : candidates)  // element index of the piece (= span number on a curve)
                    out.push_back(coupling(gp.element, first + e));
            }
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

/// One evaluation's shared state: what it fills (the pair's residual, coupling
/// blocks, counters), the kinematics, the settings of its kernels and its timers.
struct ContactPair::Sweep {
    PairEvaluation& ev;
    const std::array<RowMatrix, 2>& current;  ///< current control points of each deformable surface
    bool need_tangent = true;
    double load_factor = 0.0;
    KernelSettings kernel_base;
    std::map<Coupling, std::size_t> block_of;  ///< coupling -> index in ev.tangent
    Stopwatch search_time, projection_time;
    std::vector<int> candidates;

    /// Records a numerical failure; the evaluation stops there.
    bool fail(std::string message)
    {
        ev.ok = false;
        ev.message = std::move(message);
        return false;
    }
};

PairEvaluation ContactPair::evaluate(const RowMatrix& disp_first, const RowMatrix& disp_second, bool need_tangent,
                                     RunContext* ctx, double load_factor) const
{
    const int d = dim_;
    PairEvaluation ev;
    ev.residual = Vector::Zero(n_local_dofs());
    // The trial state starts as the state in use; the sweeps write its feet, histories and responses.
    ev.trial.carriers = trial_;
    const RowMatrix* disp[2] = {&disp_first, &disp_second};
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

    ev.trial.points = current;
    Sweep sweep{ev, current, need_tangent, load_factor,
                KernelSettings{.law = settings_.law, .master_rows = false, .need_tangent = need_tangent},
                {}, {}, {}, {}};
    // The part of the initial overlap not yet released enters the pressure law as a
    // shift: p(g_N - (1 - r) g_0, lambda), for the penalty law the multiplier
    // lambda - eps (1 - r) g_0 (NormalLaw::shifted).
    const double unreleased = releasing_ ? 1.0 - std::clamp(load_factor / release_end_, 0.0, 1.0) : 0.0;
    for (std::size_t ci = 0; ci < carriers_.size() && ev.ok; ++ci) {
        CarrierResult cr = carrier_kinematics(ci, current);
        for (ContactPointState& point : ev.trial.carriers[ci])
            point.clear_response(d);
        std::vector<NormalLaw::Shifted> law_input(static_cast<std::size_t>(cr.multiplier.size()));
        for (Index g = 0; g < cr.multiplier.size(); ++g)
            law_input[static_cast<std::size_t>(g)] =
                settings_.law.shifted(cr.multiplier(g), unreleased, initial_overlap_[ci](g));
        const bool ok = std::holds_alternative<RigidObstacle>(surfaces_[carriers_[ci].master])
                            ? evaluate_on_obstacle(ci, cr, law_input, sweep)
                            : evaluate_on_surface(ci, cr, law_input, sweep);
        if (!ok)
            break;
        cr.friction = friction_state(ev.trial.carriers[ci]);
        ev.carriers.push_back(std::move(cr));
    }
    if (ctx) {
        ctx->add_time("contact_search", sweep.search_time.seconds);
        ctx->add_time("projection", sweep.projection_time.seconds);
        ctx->add_count("contact_candidates", ev.candidates);
        ctx->add_count("projections", ev.projections);
        ctx->add_count("projection_iterations", ev.projection_iterations);
    }
    std::sort(ev.tangent.begin(), ev.tangent.end(),
              [](const LocalBlock& a, const LocalBlock& b) { return a.element < b.element; });
    return ev;
}

CarrierResult ContactPair::carrier_kinematics(std::size_t ci, const std::array<RowMatrix, 2>& current) const
{
    const int d = dim_;
    const Carrier& c = carriers_[ci];
    const int n_g = static_cast<int>(c.points.size());
    CarrierResult cr;
    cr.surface = c.slave;
    cr.piece.resize(static_cast<std::size_t>(n_g));
    cr.parameter.resize(n_g, d - 1);
    cr.reference_coordinates.resize(n_g, d);
    cr.coordinates.resize(n_g, d);
    cr.gap = Vector::Constant(n_g, -search_distance_);
    cr.pressure = Vector::Zero(n_g);
    cr.multiplier = multipliers(static_cast<int>(ci));
    cr.weight.resize(n_g);
    cr.stretch = Vector::Ones(n_g);
    cr.state.assign(n_g, PointState::far);
    for (int g = 0; g < n_g; ++g) {
        const GaussPoint& gp = c.points[g];
        VecN x = VecN::Zero(d);
        for (std::size_t a = 0; a < gp.indices.size(); ++a)
            x += gp.N(a) * current[c.slave].row(gp.indices[a]).transpose();
        cr.piece[static_cast<std::size_t>(g)] = gp.piece;
        cr.parameter.row(g) = gp.xi.transpose();
        cr.reference_coordinates.row(g) = gp.reference.transpose();
        cr.coordinates.row(g) = x.transpose();
        cr.weight(g) = c.current_measure ? current_weight(gp.rule_weight, gp.dN, gp.indices, current[c.slave]).first
                                         : gp.weight;
        cr.stretch(g) = cr.weight(g) / gp.weight;
    }
    return cr;
}

void ContactPair::scatter(const KernelResult& kr, const Carrier& c, const GaussPoint& gp,
                          const std::vector<int>& master_indices, int master_element, Sweep& sweep) const
{
    const int d = dim_;
    PairEvaluation& ev = sweep.ev;
    const int offset[2] = {0, n_control_points(0)};
    const std::size_t n_slave = gp.indices.size();
    for (std::size_t a = 0; a < n_slave + master_indices.size(); ++a) {
        const int surface = a < n_slave ? c.slave : c.master;
        const int cp = a < n_slave ? gp.indices[a] : master_indices[a - n_slave];
        for (int i = 0; i < d; ++i)
            ev.residual((offset[surface] + cp) * d + i) += kr.residual(static_cast<Index>(a) * d + i);
    }
    if (!sweep.need_tangent)
        return;
    Coupling key{-1, -1};
    key[static_cast<std::size_t>(c.slave)] = gp.element;
    key[static_cast<std::size_t>(c.master)] = master_element;
    auto [it, inserted] = sweep.block_of.try_emplace(key, ev.tangent.size());
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
}

bool ContactPair::evaluate_on_obstacle(std::size_t ci, CarrierResult& cr,
                                       const std::vector<NormalLaw::Shifted>& law_input, Sweep& sweep) const
{
    const int d = dim_;
    const Carrier& c = carriers_[ci];
    const auto& obstacle = std::get<RigidObstacle>(surfaces_[c.master]);
    PairEvaluation& ev = sweep.ev;
    for (int g = 0; g < static_cast<int>(c.points.size()); ++g) {
        const VecN x = cr.coordinates.row(g).transpose();
        const ObstacleFoot foot = obstacle.foot(x, sweep.load_factor);
        if (!foot.ok)
            return sweep.fail("contact: " + describe_point(c.slave, g, c.points[g].xi, x) +
                              " is at the centre of the rigid obstacle (no contact normal); the bodies overlap "
                              "far too much: check the obstacle's position and motion");
        cr.gap(g) = foot.gap;
        cr.state[g] = PointState::ok;
        KernelSettings point_settings = sweep.kernel_base;
        point_settings.multiplier = law_input[static_cast<std::size_t>(g)].multiplier;
        point_settings.gap_offset = law_input[static_cast<std::size_t>(g)].gap_offset;
        KernelResult kr = held(ci, g) ? KernelResult{}
                                      : gpts_rigid_kernel(c.points[g].N, c.points[g].weight, foot.normal, foot.gap,
                                                          point_settings, foot.radius);
        cr.pressure(g) = kr.pressure;
        if (settings_.friction.active()) {
            // Slip in the obstacle's frame; dp/dy = -p' n where the point presses.
            const VecN y = x - obstacle.shift(sweep.load_factor);
            const VecN d_pressure = kr.pressure > 0.0 ? VecN(-kr.slope * foot.normal)
                                                      : VecN(VecN::Zero(d));
            const FrictionHistory& committed = committed_[ci][static_cast<std::size_t>(g)].friction;
            ContactPointState& point = ev.trial.carriers[ci][static_cast<std::size_t>(g)];
            const TangentialResponse t = coulomb_response(settings_.friction, committed, point.tangential_multiplier,
                                                          y, foot.normal, kr.pressure, d_pressure, foot.radius);
            if (!held(ci, g))
                add_tangential(kr, c.points[g].N, c.points[g].weight, t);
            point.record(t);
            ev.max_elastic_slip = std::max(ev.max_elastic_slip, t.elastic_slip);
        }
        if (kr.pressure > 0.0) {
            ++ev.n_active;
            ev.max_penetration = std::max(ev.max_penetration, foot.gap);
            scatter(kr, c, c.points[g], {}, -1, sweep);
        }
    }
    return true;
}

bool ContactPair::evaluate_on_surface(std::size_t ci, CarrierResult& cr,
                                      const std::vector<NormalLaw::Shifted>& law_input, Sweep& sweep) const
{
    const Carrier& c = carriers_[ci];
    const int n_g = static_cast<int>(c.points.size());
    PairEvaluation& ev = sweep.ev;
    const DeformableSide& master = std::get<DeformableSide>(surfaces_[c.master]);
    sweep.search_time.start();
    const MasterView view = master_view(master, sweep.current[c.master], search_distance_);
    const Box slave_box = bounding_box(sweep.current[c.slave]);
    bool may_touch = false;
    for (const ElementSearch& search : view.searches)
        may_touch = may_touch || slave_box.overlaps(search.bounds());
    sweep.search_time.stop();
    const bool friction = settings_.friction.active();
    // Against a deformable master a point is unanchored until it finds a foot.
    std::vector<ContactPointState>& points = ev.trial.carriers[ci];
    if (friction)
        for (int g = 0; g < n_g; ++g) {
            points[g].friction = committed_[ci][g].friction;
            points[g].friction.anchored = false;
            points[g].friction.open_gap = 0.0;
        }
    if (!may_touch)  // the slave side's hull misses every inflated master span box
        return true;
    KernelSettings kernel_settings = sweep.kernel_base;
    kernel_settings.master_rows = c.master_rows;
    Timing timing{sweep.search_time, sweep.projection_time, sweep.candidates};

    for (int g = 0; g < n_g; ++g) {
        const GaussPoint& gp = c.points[g];
        const VecN x = cr.coordinates.row(g).transpose();
        bool failed = false;
        std::optional<Projection> best = project_on_master(c.master, view, x, points[g].foot, ev, timing, failed);
        if (failed)
            return sweep.fail("contact: closest-point projection failed at " + describe_point(c.slave, g, gp.xi, x));
        if (!best)
            continue;
        const Projection& proj = *best;
        points[g].foot = Foot{proj.xi, proj.element};
        cr.gap(g) = proj.gap;
        const bool unsettled = proj.status == Projection::Status::unsettled;
        if (proj.status != Projection::Status::ok && !unsettled) {
            cr.state[g] = proj.status == Projection::Status::off_end ? PointState::off_end : PointState::at_kink;
            continue;
        }
        cr.state[g] = PointState::ok;
        // Active where the law presses (p > 0): with a multiplier or the exponential law,
        // also at an open gap. An unsettled foot (Newton did not settle, near a collapsed
        // pole) is only the nearest point found: it stands for an open point if the point
        // stays open with the gap unsettled_margin of the master's size nearer, else the
        // projection has failed (no force may depend on where exactly that foot is).
        kernel_settings.multiplier = law_input[static_cast<std::size_t>(g)].multiplier;
        kernel_settings.gap_offset = law_input[static_cast<std::size_t>(g)].gap_offset;
        const double margin = unsettled ? unsettled_margin * view.size : 0.0;
        const MasterReference reference = friction ? master_reference(c.master, proj.basis) : MasterReference{};
        if (held(ci, g) ||
            !settings_.law.active(proj.gap - kernel_settings.gap_offset + margin, kernel_settings.multiplier)) {
            if (friction)
                points[g].friction = open_history(committed_[ci][g].friction, reference,
                                                  proj.gap - kernel_settings.gap_offset);
            if (sweep.need_tangent && !held(ci, g) && !unsettled && touches_at_kink(proj.gap, kernel_settings, view.size))
                scatter_touching(ci, g, proj, reference, kernel_settings, sweep);
            continue;
        }
        if (unsettled)
            return sweep.fail("contact: closest-point projection failed at " + describe_point(c.slave, g, gp.xi, x));
        const MasterFoot foot = master_foot(proj);
        Vector dW;
        double W = gp.weight;
        if (c.current_measure)
            std::tie(W, dW) = current_weight(gp.rule_weight, gp.dN, gp.indices, sweep.current[c.slave]);
        KernelResult kr = gpts_kernel(gp.N, W, foot, kernel_settings, sweep.need_tangent ? dW : Vector());
        if (!kr.ok)
            return sweep.fail("contact: the penetration at " + describe_point(c.slave, g, gp.xi, x) +
                              " exceeds the master's radius of curvature (the projection is not a distance "
                              "minimum); try a stiffer contact law or smaller load steps");
        cr.pressure(g) = kr.pressure;
        if (friction) {
            const TangentialResponse t =
                gpts_friction(kr, gp.N, W, foot, reference, settings_.friction, committed_[ci][g].friction,
                              points[g].tangential_multiplier, kernel_settings, sweep.need_tangent ? dW : Vector(),
                              committed_[ci][g].friction.anchored ? ConvergedPositions{}
                                                                  : converged_positions(c, gp, proj.basis));
            points[g].record(t);
            ev.max_elastic_slip = std::max(ev.max_elastic_slip, t.elastic_slip);
        }
        ++ev.n_active;
        ev.max_penetration = std::max(ev.max_penetration, foot.gap);
        scatter(kr, c, gp, proj.basis.indices, proj.element, sweep);
    }
    return true;
}

void ContactPair::scatter_touching(std::size_t ci, int g, const Projection& proj, const MasterReference& reference,
                                   const KernelSettings& settings, Sweep& sweep) const
{
    const Carrier& c = carriers_[ci];
    const GaussPoint& gp = c.points[static_cast<std::size_t>(g)];
    KernelSettings touching = settings;
    touching.touching = true;
    const MasterFoot foot = master_foot(proj);
    KernelResult kr = gpts_kernel(gp.N, gp.weight, foot, touching, Vector());
    const FrictionHistory& committed = committed_[ci][static_cast<std::size_t>(g)].friction;
    if (settings_.friction.active() && committed.anchored)
        gpts_friction(kr, gp.N, gp.weight, foot, reference, settings_.friction, committed,
                      sweep.ev.trial.carriers[ci][static_cast<std::size_t>(g)].tangential_multiplier, touching, Vector(),
                      ConvergedPositions{});
    scatter(kr, c, gp, proj.basis.indices, proj.element, sweep);
}

ConvergedPositions ContactPair::converged_positions(const Carrier& c, const GaussPoint& gp,
                                                   const nurbs::BasisValues& foot) const
{
    const RowMatrix& slave = committed_points_[static_cast<std::size_t>(c.slave)];
    const RowMatrix& master = committed_points_[static_cast<std::size_t>(c.master)];
    ConvergedPositions out{VecN::Zero(dim_), RowMatrix(static_cast<Index>(foot.indices.size()), dim_)};
    for (std::size_t a = 0; a < gp.indices.size(); ++a)
        out.slave += gp.N(static_cast<Index>(a)) * slave.row(gp.indices[a]).transpose();
    for (std::size_t b = 0; b < foot.indices.size(); ++b)
        out.master.row(static_cast<Index>(b)) = master.row(foot.indices[b]);
    return out;
}

MasterReference ContactPair::master_reference(int master_surface, const nurbs::BasisValues& basis) const
{
    const RowMatrix& X = reference_points_[static_cast<std::size_t>(master_surface)];
    const Index d = X.cols();
    MasterReference out{VecN::Zero(d), Matrix::Zero(d, basis.dR.cols()), Matrix::Zero(d, basis.d2R.cols())};
    for (std::size_t b = 0; b < basis.indices.size(); ++b) {
        const VecN Xb = X.row(basis.indices[b]).transpose();
        const Index k = static_cast<Index>(b);
        out.point += basis.R(k) * Xb;
        out.tangents += Xb * basis.dR.row(k);
        out.second += Xb * basis.d2R.row(k);
    }
    return out;
}

ContactPair::MasterView ContactPair::master_view(const DeformableSide& master, const RowMatrix& points,
                                                 double distance) const
{
    MasterView view;
    for (std::size_t k = 0; k < master.pieces.size(); ++k) {
        const SidePiece& piece = master.pieces[k];
        view.patches.push_back(piece.side.patch.with_control_points(piece_points(piece, points)));
        view.first_element.push_back(master.first_element(static_cast<int>(k)));
    }
    for (const nurbs::Patch& patch : view.patches)  // after the patches: searches keep no reference to them
        view.searches.emplace_back(patch, SearchOptions{.distance = distance});
    view.size = (points.colwise().maxCoeff() - points.colwise().minCoeff()).norm();
    return view;
}

std::optional<Projection> ContactPair::project_on_master(int master_surface, const MasterView& view, const VecN& x,
                                                         const Foot& warm, PairEvaluation& ev, Timing& timing,
                                                         bool& failed) const
{
    const DeformableSide& master = std::get<DeformableSide>(surfaces_[static_cast<std::size_t>(master_surface)]);
    const std::size_t n_pieces = master.pieces.size();
    std::optional<Projection> best;
    std::size_t best_piece = 0;
    failed = false;
    for (std::size_t k = 0; k < n_pieces; ++k) {
        timing.search.start();
        view.searches[k].candidates(x, timing.candidates);
        timing.search.stop();
        if (timing.candidates.empty())
            continue;
        ev.candidates += static_cast<long long>(timing.candidates.size());

        ProjectionOptions options;
        const int n_piece_elements = view.searches[k].n_elements();
        if (warm.element >= view.first_element[k] && warm.element < view.first_element[k] + n_piece_elements) {
            options.start = warm.xi;
            options.start_element = warm.element - view.first_element[k];
        }
        options.candidate_elements = timing.candidates;  // elements of a curve = its spans, in order
        timing.projection.start();
        Projection proj = project_to_surface(view.patches[k], master.pieces[k].outward_sign, x, options);
        timing.projection.stop();
        ++ev.projections;
        ev.projection_iterations += proj.iterations;
        if (proj.status == Projection::Status::failed) {
            failed = true;
            return std::nullopt;
        }
        if (!best || nearer_foot(proj.distance, proj.status == Projection::Status::ok, best->distance,
                                 best->status == Projection::Status::ok, view.size)) {
            best = std::move(proj);
            best_piece = k;
        }
    }
    if (!best || n_pieces == 1)
        return best;
    // Piece numbering -> surface numbering; an end shared with another piece is a crease.
    Projection& proj = *best;
    for (int& a : proj.basis.indices)
        a = master.pieces[best_piece].surface_index[static_cast<std::size_t>(a)];
    proj.element += view.first_element[best_piece];
    if (proj.status == Projection::Status::off_end) {
        const nurbs::Patch& patch = view.patches[best_piece];
        bool outer = false;
        for (int k = 0; k < patch.n_par(); ++k)
            for (int end = 0; end < 2; ++end) {
                const auto& kv = patch.knots(k);
                const bool at = end ? proj.xi(k) >= kv.back() : proj.xi(k) <= kv.front();
                if (at && !inner_edge_[static_cast<std::size_t>(master_surface)][best_piece][k][end])
                    outer = true;
            }
        if (!outer)
            proj.status = Projection::Status::at_kink;
    }
    return best;
}

}  // namespace iga::contact
