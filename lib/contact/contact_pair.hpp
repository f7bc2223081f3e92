#pragma once
// One contact pair: its two surfaces (deformable sides -- curves in 2D, surfaces in
// 3D -- or a rigid obstacle), the
// Gauss points that carry the contact pressure, and the per-Newton-iteration evaluation
// of its residual and tangent (Kopacka et al. eqs. 5-7; docs/theory.md "Contact formulation").
//
// Who carries Gauss points:
//  - two_half_pass, both deformable: both sides; each is projected onto the
//    other and each half pass assembles ONLY its own (slave) rows, with the full
//    penalty (tangent non-symmetric: use a general sparse LU);
//  - single_pass, both deformable: the first surface is the slave, slave and
//    master rows are assembled (action-reaction; tangent symmetric);
//  - deformable vs rigid obstacle (plane or sphere): the deformable side, whatever the formulation.
// Gauss points: `quadrature` per knot span of the carrying side (0 means degree
// + 2, per direction on a surface), placed in the REFERENCE configuration;
// kinematics use the current configuration. Weight W = w_g * area element
// (length in 2D): the REFERENCE one, held fixed, for a single pass and against a
// rigid obstacle (the tangent stays symmetric; one integral, balanced by
// action-reaction); the CURRENT one in both half passes of two-half-pass, whose two
// integrals must cover the same contact zone: over reference areas each surface
// would count its own stretch and the forces on the two bodies would differ by the
// difference of their surface strains (docs/theory.md "Two-half-pass balance").
//
// Sign conventions as in gap.hpp (positive gap = penetration); the residual is
// the contact part r_c = dPi_c/du of the driver's r = f_int - lambda f_ext + r_c.
//
// Local numbering (shapes): the first surface's control points, then the
// second's (a rigid surface has none); dof = cp * d + component, d = 2 or 3; cp is
// the SURFACE control-point index (DeformableSide: one numbering over its pieces;
// for a one-piece surface the side's, which SidePatch::parent_index maps to the parent).
// Displacements are given per side, n_cp_side x d, row-major.
//
// Tangent (sparse coupling): evaluate() returns the tangent as small dense
// blocks, one per coupling = (element of the first surface, element of the second
// surface) that some active Gauss point connects (its own element on the slave
// side, the element of its foot point on the master side; the Gauss points of
// one coupling are summed; against a rigid obstacle the obstacle's element is -1).
// A block's dofs are pair-local: the first surface element's control points, then
// the second's (component fastest), so both half passes of a two-half-pass pair
// land in the same block. "Element" is the surface's element number
// (pieces in order, each in nurbs::Patch::elements() order). No n_local x n_local matrix is ever formed.
// candidate_couplings() lists the couplings the global search admits in the
// reference configuration: the caller registers them in its sparsity pattern up
// front and extends the pattern when evaluate() meets another one (sliding).
//
// Multi-piece master surfaces: each piece holding a candidate element is
// projected on; the nearest foot wins (at equal distance an orthogonal one). A
// foot clamped to an edge that another piece shares is not off the surface's end:
// the neighbour holds the point (then it is nearer or orthogonal and wins), or the
// point lies in the normal fan of the crease between them (at_kink, inactive, as
// at an interior C0 knot of one patch). off_end only at the surface's own boundary.
//
// Per-Gauss-point state (ContactPointState, a PairState per pair): each point carries
// a committed state and one in use -- its last foot point (warm start), its
// multipliers and its friction history (anchor, accumulated slip: friction.hpp's
// FrictionHistory), and the tangential response of the evaluation that made it, a
// (current, old) pair as in 4C and MOOSE. evaluate() is a pure function of the
// displacements and these two states: it reads the committed history and the state in
// use (warm-start feet, multipliers of the current attempt) and RETURNS the trial state
// it leads to (PairEvaluation::trial: new feet, friction history and response). The
// caller makes it the state in use with adopt() -- right after each evaluation, so that
// the next one warm-starts from it; commit() keeps the state in use as committed (call
// it after a converged increment), rollback() returns to the last committed one (after
// a cutback).
//
// Normal law (normal_law.hpp): the pressure p(g_N, lambda) of every Gauss point is the
// pair's NormalLaw -- the penalty law p = <lambda + eps g_N>, or the exponential
// (softened) law, which presses at gaps down to -c0; the pair's search margin is
// then at least search_reach_factor c0.
//
// Augmented Lagrangian (docs/theory.md "Augmented Lagrangian"): every Gauss point
// carries a multiplier lambda >= 0 (pressure units, 0 at the start) and its
// pressure is p = <lambda + eps g_N>; with all multipliers 0 this is the penalty
// law. update_multipliers() is the Uzawa step lambda <- <lambda + eps g_N>, i.e.
// lambda <- p of an evaluation at a converged state (NormalLaw::updated_multiplier).
// The multipliers are state like the foot points: commit() keeps them, rollback()
// restores the committed ones. set_penalty() changes eps (the safeguard that raises
// it); it is not rolled back.
// With friction each point also carries a tangential multiplier lambda_T (a traction, in
// the frame of its anchor: friction.hpp, gpts_friction.hpp), which shifts the trial
// traction; update_multipliers() adopts the returned traction, lambda_T <- t_T
// (docs/theory.md "Frictional augmented Lagrangian"). A point that is open at a committed
// state carries no lambda_T forward: a traction it had does not survive losing contact.
//
// Both surfaces live in the same dimension d (2 or 3), else the constructor throws
// iga::Error.

#include "contact/friction.hpp"
#include "contact/gpts_friction.hpp"
#include "contact/gpts_kernel.hpp"
#include "contact/normal_law.hpp"
#include "contact/projection.hpp"
#include "contact/rigid_obstacle.hpp"
#include "contact/search.hpp"
#include "core/model_options.hpp"
#include "core/run_context.hpp"
#include "core/side.hpp"
#include "core/types.hpp"
#include "nurbs/side_patch.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace iga::contact {

/// Fraction of the larger side's reference size used as the automatic search
/// margin: far above any sensible penalty penetration, small enough to prune.
inline constexpr double auto_search_fraction = 0.1;
/// A law that presses at open gaps down to -reach (NormalLaw::reach(): the exponential
/// law's clearance c0) widens the search margin to at least this many times its reach,
/// so that no point the law presses is pruned, with room for a step's motion.
inline constexpr double search_reach_factor = 4.0;
/// A projection that did not settle (Projection::Status::unsettled) is taken as open
/// only where the law stays inactive with its gap this fraction of the master's size
/// nearer: above the distance by which the nearest point found may miss the surface's
/// nearest (2.2e-4 of a size of 1.4 near a shell's pole, tests/contact/projection_test.cpp).
inline constexpr double unsettled_margin = 1e-3;

using iga::Formulation;  // core/model_options.hpp

struct PairSettings {
    Formulation formulation = Formulation::two_half_pass;
    NormalLaw law;                ///< p(g_N, lambda): penalty (eps_N > 0) or exponential
    int quadrature = 0;           ///< Gauss points per knot span of a carrying side; 0 = degree + 2
    double search_distance = 0.0; ///< global search margin; 0 = auto (a tenth of the larger side's size);
                                  ///< at least search_reach_factor * law.reach() either way
    FrictionLaw friction{};       ///< Coulomb friction; mu = 0: frictionless
};

/// One patch side of a deformable contact surface, in its REFERENCE configuration.
struct SidePiece {
    nurbs::SidePatch side;           ///< side.parent_index: control points of its parent patch
    int outward_sign = 1;
    std::vector<int> surface_index;  ///< side control point -> surface control point
};

/// A deformable contact surface: one patch side, or several patch sides of one
/// body glued along their edges (a named surface of a multi-patch body). It is ONE
/// surface for search, projection and post-processing: its control points are
/// numbered once (a control point on an interface between two pieces is one
/// surface control point) and its elements are numbered consecutively over the
/// pieces (piece order, each in Patch::elements() order).
struct DeformableSide {
    std::vector<SidePiece> pieces;
    int n_control_points = 0;  ///< surface control points

    /// Side `side` of a solid patch (2 parameters in 2D, 3 in 3D), with its outward
    /// sign (boundary::PatchSide); throws iga::Error for a collapsed or degenerate side.
    /// The surface numbering is the side's.
    static DeformableSide make(const nurbs::Patch& parent, Side side);
    /// Several sides: sides[k] of parents[k], where parent_node[k] maps the parent's
    /// control points to body nodes; side control points on the same body node are
    /// one surface control point (numbered by first appearance). surface_node
    /// receives the body node of each surface control point.
    static DeformableSide make(const std::vector<const nurbs::Patch*>& parents, const std::vector<Side>& sides,
                               const std::vector<std::vector<int>>& parent_node, std::vector<int>& surface_node);

    /// Reference control points of the surface, n_control_points x d.
    RowMatrix control_points() const;
    /// Elements of the surface (all pieces).
    int n_elements() const;
    /// First surface element of piece k.
    int first_element(int k) const;
};

using Surface = std::variant<DeformableSide, RigidObstacle>;

/// What happened at one Gauss point.
enum class PointState {
    far,      ///< pruned by the global search (gap not computed)
    ok,       ///< projected (or plane gap); active when gap > 0
    off_end,  ///< nearest master point at the surface's boundary, not orthogonal: inactive
    at_kink,  ///< nearest master point at a C0 corner, not orthogonal: inactive
};

/// The tangential state of a carrying side's Gauss points (zeros and `open`
/// without friction).
struct FrictionState {
    std::vector<StickSlip> status;  ///< n_g: open, stick or slip
    RowMatrix traction;             ///< n_g x d, t_T on the slave (tangential, force per area)
    Vector slip_increment;          ///< n_g, slip length since the last converged increment
    Vector slip;                    ///< n_g, accumulated slip length (with this increment's)
    Vector elastic_slip;            ///< n_g, |t_T - lambda_T| / eps_T (0 where open)
    RowMatrix frame_traction;       ///< n_g x d, t_T in the anchor's frame: what an Uzawa update adopts as lambda_T
};

/// Gauss point data of one carrying side, n_g points in element order.
struct CarrierResult {
    int surface = 0;                    ///< 0: the pair's first surface, 1: the second
    std::vector<int> piece;             ///< n_g, the piece (patch side) of the surface holding the Gauss point
    RowMatrix parameter;                ///< n_g x q, the Gauss point's parameters on its piece
    RowMatrix reference_coordinates;    ///< n_g x d
    RowMatrix coordinates;              ///< n_g x d, current configuration
    Vector gap;                         ///< n_g, g_N (positive = penetration); far: -search distance, a bound
    Vector pressure;                    ///< n_g, p(g_N, lambda), e.g. <lambda + eps g_N> (0 unless state ok)
    Vector multiplier;                  ///< n_g, the multipliers lambda of this evaluation (0: penalty)
    Vector weight;                      ///< n_g, W = w_g * area element (current for two-half-pass, see above)
    Vector stretch;                     ///< n_g, W / (w_g * reference area element): the surface stretch j/J
                                        ///< of a current-measure carrier, 1 elsewhere
    std::vector<PointState> state;      ///< n_g
    FrictionState friction;             ///< tangential traction, stick/slip, slip
};

/// The state of one Gauss point (see the header paragraph).
struct ContactPointState {
    struct Foot {                  ///< the last foot point (warm start)
        VecN xi;
        int element = -1;          ///< -1: none yet
    };
    Foot foot;
    double multiplier = 0.0;   ///< lambda >= 0 in use (trial) or at the last commit
    VecN tangential_multiplier; ///< lambda_T, d, in the anchor's frame; like `multiplier`
    FrictionHistory friction;  ///< committed: what evaluate() starts from; trial: what it leads to
    // The tangential response of the evaluation that made this state (the results
    // report a committed one): open and zeros where no friction kernel ran.
    StickSlip status = StickSlip::open;
    VecN traction;             ///< t_T on the slave, d
    VecN frame_traction;       ///< t_T in the anchor's frame, d
    double slip_increment = 0.0;
    double elastic_slip = 0.0;

    /// Clears the tangential response (before an evaluation; d the dimension).
    void clear_response(int d);
    /// Keeps a friction kernel's response: the history it leads to and what it found.
    void record(const TangentialResponse& t);
};

/// The per-point state of a pair: per carrier (PairEvaluation::carriers order), n_g points.
struct PairState {
    std::vector<std::vector<ContactPointState>> carriers;
    std::array<RowMatrix, 2> points;  ///< the control points of each deformable surface it was evaluated at
};

/// A coupling: element number on the first and second surface (-1 on a rigid obstacle).
using Coupling = std::array<int, 2>;

/// The tangent of one coupling (see the header paragraph).
struct LocalBlock {
    Coupling element{-1, -1};
    std::vector<int> dofs;  ///< pair-local dofs: first surface element's cps x d, then the second's
    Matrix K;               ///< dofs.size() square: d r_c[dofs] / d u[dofs], Gauss points of the coupling summed
};

struct PairEvaluation {
    bool ok = true;               ///< false: a numerical failure (see message); residual incomplete
    std::string message;
    Vector residual;              ///< n_local_dofs()
    std::vector<LocalBlock> tangent; ///< one block per coupling met, sorted by coupling; empty unless requested
    int n_active = 0;             ///< Gauss points with positive pressure
    long long candidates = 0;     ///< (Gauss point, master span) pairs from the global search
    long long projections = 0;
    long long projection_iterations = 0;
    double max_penetration = 0.0; ///< largest positive gap of an ok point, 0 if none
    double max_elastic_slip = 0.0; ///< largest elastic slip |t_T - lambda_T| / eps_T (friction), 0 if none
    std::vector<CarrierResult> carriers;  ///< one per carrying side (2 for two_half_pass, else 1)
    PairState trial;              ///< the per-point state this evaluation leads to: pass it to ContactPair::adopt
};

class ContactPair {
public:
    ContactPair(PairSettings settings, Surface first, Surface second);

    const PairSettings& settings() const { return settings_; }
    const Surface& surface(int i) const { return surfaces_[i]; }
    /// Side control points of surface i (0 for a rigid obstacle).
    int n_control_points(int i) const;
    int n_local_dofs() const { return (n_control_points(0) + n_control_points(1)) * dim_; }
    int dim() const { return dim_; }
    double search_distance() const { return search_distance_; }
    /// Gauss points of the carrying sides, in the order of PairEvaluation::carriers.
    int n_carriers() const { return static_cast<int>(carriers_.size()); }
    int n_gauss_points(int carrier) const { return static_cast<int>(carriers_[carrier].points.size()); }

    /// Elements of surface i (0 for a rigid obstacle).
    int n_elements(int i) const { return static_cast<int>(element_points_[i].size()); }
    /// Pair-local dofs of a coupling, in LocalBlock::dofs order.
    std::vector<int> coupling_dofs(const Coupling& element) const;
    /// Couplings the global search admits in the reference configuration (zero
    /// displacements, obstacles at load factor 0): for every Gauss point, its
    /// element with each master element whose search box holds it; against a rigid
    /// obstacle every element of the deformable side. Sorted, each once.
    std::vector<Coupling> candidate_couplings() const;

    /// Residual (and tangent) at the displacements of the two sides (n_cp_i x d,
    /// an empty matrix for a rigid surface); a moving obstacle sits at its
    /// position for `load_factor`. Adds the timers "contact_search" and
    /// "projection" and the counters "contact_candidates", "projections",
    /// "projection_iterations" to ctx when it is not null.
    PairEvaluation evaluate(const RowMatrix& disp_first, const RowMatrix& disp_second, bool need_tangent,
                            RunContext* ctx = nullptr, double load_factor = 0.0) const;

    /// Makes an evaluation's trial state (PairEvaluation::trial) the state in use: its
    /// warm-start feet, trial friction history and tangential response; the multipliers
    /// in use are the ones it was evaluated with. Call it right after each evaluate().
    void adopt(PairState trial);
    /// Keeps the state in use, that of the last adopted evaluation (call it after a
    /// converged increment, whose final evaluation is the last one), as committed: foot
    /// points, multipliers, friction anchors and slip, and the tangential response.
    void commit();
    /// Returns to the state of the last commit() (after a cutback).
    void rollback()
    {
        trial_ = committed_;
        trial_points_ = committed_points_;
        release_holds();
    }
    /// Holds Gauss point g of carrier c open (no normal or tangential force, whatever
    /// its gap) until release_hold(), release_holds() or rollback(): Newton asks for it where the
    /// point's contact flips at every step and no state of it has an equilibrium nearby
    /// (docs/solver.md, "A point held open"). Whether it was free before.
    bool hold_open(int carrier, int g);
    /// Frees a point hold_open() held (nothing if it is free).
    void release_hold(int carrier, int g);
    /// Frees every held point.
    void release_holds() { held_.clear(); }
    bool is_held(int carrier, int g) const { return held(static_cast<std::size_t>(carrier), g); }
    /// The friction state of carrier c at the last committed increment (what the
    /// results report; an evaluation after the commit measures slip from there).
    FrictionState converged_friction(int carrier) const;

    /// Uzawa update lambda_g <- <lambda_g + eps g_N,g> = p_g for every Gauss point,
    /// from `state`, an evaluation of this pair (all carriers, in order) at a
    /// converged state. Points that are not `ok` (far, off an end, at a kink) get 0.
    /// With friction also lambda_T,g <- t_T,g (its frame_traction; 0 where open).
    void update_multipliers(const PairEvaluation& state);
    /// The multipliers in use on carrier c, n_gauss_points(c).
    Vector multipliers(int carrier) const;
    /// The tangential multipliers in use on carrier c, n_gauss_points(c) x d, each in
    /// its anchor's frame (zeros without friction or before any update).
    RowMatrix tangential_multipliers(int carrier) const;
    /// Replaces eps_N (> 0, finite) of the penalty law; the multipliers are kept.
    void set_penalty(double penalty);

    /// Initial overclosure (docs/theory.md "Initial overclosure"): g0[c]
    /// (n_gauss_points(c), >= 0) is the overlap of carrier c's Gauss points at rest.
    /// Once release_overlap() is called the pressure becomes
    /// p = p(g_N - (1 - r) g_0, lambda), e.g. <lambda + eps (g_N - (1 - r) g_0)>, with
    /// r = clamp(load factor / release_end, 0, 1):
    /// the overlap is pushed out by load factor release_end > 0 and cutbacks shrink it
    /// like any load. Before that call the overlap acts at once, as placed.
    void set_initial_overlap(std::vector<Vector> g0, double release_end);
    void release_overlap() { releasing_ = true; }
    bool has_initial_overlap() const;
    const Vector& initial_overlap(int carrier) const { return initial_overlap_[static_cast<std::size_t>(carrier)]; }

private:
    struct GaussPoint {
        int piece;                 ///< piece of the carrying surface
        int element;               ///< element number on the carrying surface
        VecN xi;                   ///< d - 1 parameters on the side
        double rule_weight;        ///< w_g, the Gauss weight in the side's parameters
        double weight;             ///< W = w_g * reference length / area element
        VecN reference;            ///< X(xi)
        std::vector<int> indices;  ///< surface control points with non-zero basis
        Vector N;                  ///< their basis values
        Matrix dN;                 ///< their derivatives, n_s x (d - 1)
    };
    struct Carrier {
        int slave;
        int master;
        bool master_rows;
        /// Two-half-pass: W = w_g * CURRENT area element, so that both passes integrate
        /// over the same (current) contact zone and their forces balance.
        bool current_measure;
        std::vector<GaussPoint> points;
    };

    PairSettings settings_;
    std::array<Surface, 2> surfaces_;
    int dim_ = 2;
    double search_distance_ = 0.0;
    std::vector<Carrier> carriers_;
    std::array<std::vector<std::vector<int>>, 2> element_points_;  ///< surface control points of each element
    std::array<RowMatrix, 2> reference_points_;  ///< reference control points of a deformable surface
    /// Per surface and piece: per side direction k, whether its lower / upper edge
    /// is shared with another piece (an interface inside the surface).
    std::array<std::vector<std::array<std::array<bool, 2>, 2>>, 2> inner_edge_;
    using Foot = ContactPointState::Foot;
    std::vector<std::vector<ContactPointState>> committed_;  ///< per carrier, n_g
    std::vector<std::vector<ContactPointState>> trial_;      ///< in use: the last adopted evaluation's
    /// The control points of each deformable surface in use and at the last commit (a
    /// first touch measures its slide from the committed ones).
    std::array<RowMatrix, 2> trial_points_, committed_points_;
    std::vector<std::vector<char>> held_;  ///< per carrier, n_g: held open (hold_open); empty: none held
    bool held(std::size_t carrier, int g) const
    {
        return !held_.empty() && held_[carrier][static_cast<std::size_t>(g)];
    }
    std::vector<Vector> initial_overlap_;       ///< per carrier, n_g: g_0 >= 0, released up to release_end_
    double release_end_ = 1.0;                  ///< load factor by which the initial overlap is released
    bool releasing_ = false;                    ///< release_overlap() called

    /// A master surface's pieces at given control points, with their element searches.
    struct MasterView {
        std::vector<nurbs::Patch> patches;
        std::vector<ElementSearch> searches;
        std::vector<int> first_element;  ///< first surface element of each piece
        double size = 0.0;               ///< diagonal of the surface's control points
    };
    struct Timing;
    struct Sweep;  ///< one evaluation's shared state (contact_pair.cpp)
    /// evaluate() in its steps: the carrying side's Gauss points in the current
    /// configuration; then, per Gauss point, the foot on the master (the obstacle's
    /// exact foot, or global search and closest-point projection), the kernels (normal
    /// and tangential) and the scatter of their results into the pair's residual and
    /// coupling blocks. The two evaluate_on_* return false on a numerical failure
    /// (recorded in the sweep's evaluation).
    CarrierResult carrier_kinematics(std::size_t carrier, const std::array<RowMatrix, 2>& current) const;
    /// `law_input`: per Gauss point, the multiplier and gap offset its law is evaluated with.
    bool evaluate_on_obstacle(std::size_t carrier, CarrierResult& cr, const std::vector<NormalLaw::Shifted>& law_input,
                              Sweep& sweep) const;
    bool evaluate_on_surface(std::size_t carrier, CarrierResult& cr, const std::vector<NormalLaw::Shifted>& law_input,
                             Sweep& sweep) const;
    void scatter(const KernelResult& kr, const Carrier& c, const GaussPoint& gp, const std::vector<int>& master_indices,
                 int master_element, Sweep& sweep) const;
    /// A point touching at the kink (KernelSettings::touching): the pressing and, with
    /// friction, sticking branch's tangent, and no force.
    void scatter_touching(std::size_t carrier, int g, const Projection& proj, const MasterReference& reference,
                          const KernelSettings& settings, Sweep& sweep) const;
    /// The tangential state of one carrier's points as the results report it.
    FrictionState friction_state(const std::vector<ContactPointState>& points) const;
    /// Friction against a deformable master: anchors each Gauss point at the foot of
    /// its reference position on the master's reference surface (constructor).
    void anchor_on_reference_masters();
    /// The reference geometry of a deformable master at a foot with basis `basis` (surface numbering).
    MasterReference master_reference(int master_surface, const nurbs::BasisValues& basis) const;
    /// Where a slave Gauss point and the master control points of its foot's basis were
    /// at the last commit (a first touch measures its slide from there).
    ConvergedPositions converged_positions(const Carrier& c, const GaussPoint& gp,
                                           const nurbs::BasisValues& foot) const;
    MasterView master_view(const DeformableSide& master, const RowMatrix& points, double distance) const;
    /// The nearest foot of x over the master's pieces (surface numbering); nullopt when
    /// no piece has a candidate element; `failed` when a projection failed.
    std::optional<Projection> project_on_master(int master_surface, const MasterView& view, const VecN& x,
                                                const Foot& warm, PairEvaluation& ev, Timing& timing,
                                                bool& failed) const;
};

}  // namespace iga::contact
