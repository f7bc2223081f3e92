#pragma once
// Scene: the runtime model built from a deck — the refined patches with their
// precomputed element geometry, the dof map with the Dirichlet data, the dead
// external forces at full value (one vector per amplitude), follower pressures,
// the contact pairs and the load path — plus the sparsity pattern shared by
// every evaluation.
//
// Load path (core/amplitude.hpp): every load, prescribed displacement and
// obstacle motion carries an amplitude (the default ramp when the deck gives
// none); at pseudo-time t it acts at a(t) times its full value. The path ends at
// the last end time of those amplitudes.
//
// Block order in the pattern: every element of every body (body order, element
// order of Patch::elements()), then one block per side element carrying a
// follower pressure in finite kinematics, then for each contact pair one block
// per candidate coupling (a slave side element and a master side element within
// the search margin in the reference configuration, or a side element against a
// rigid obstacle; contact::ContactPair::candidate_couplings), in coupling order.
// Couplings met later (sliding) are appended by SceneSystem through
// SparsePattern::extend (PairModel::blocks records them all).
//
// Only the effects the deck calls for are built: no contact pairs means no
// contact data at all; small kinematics caches the constant element stiffness.

#include "analysis/contact_penalty.hpp"
#include "analysis/multipatch.hpp"
#include "assembly/dof_map.hpp"
#include "assembly/sparse_pattern.hpp"
#include "core/parallel.hpp"
#include "contact/contact_pair.hpp"
#include "core/stop.hpp"
#include "io/deck.hpp"
#include "mechanics/element_geometry.hpp"
#include "mechanics/loads.hpp"
#include "mechanics/material.hpp"
#include "nurbs/patch.hpp"
#include "nurbs/topology.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace iga::analysis {

/// One patch of a body: its geometry and where its control points sit in the
/// body's node numbering (interface control points share one node).
struct PatchModel {
    std::string name;         ///< deck name; "" for a single-patch body
    nurbs::Patch patch;
    std::vector<int> node;    ///< patch control point -> body node
    int first_element = 0;    ///< its elements are BodyModel::elements[first_element, + n_elements)
    int n_elements = 0;
    bool u_reversed = false;  ///< its transform reversed u: the deck's u0/u1 are swapped (geometry.hpp)
};

/// A deformable body: one or more patches glued conformingly (analysis/multipatch.hpp).
/// Nodes are the body's distinct control points (a single patch: its control points,
/// in order); element geometry lists every patch's elements in patch order, with
/// ElementGeometry::indices holding BODY NODES.
struct BodyModel {
    std::string name;
    std::vector<PatchModel> patches;
    bool multi_patch = false;                     ///< given as `patches:` / `geometry:` in the deck
    std::vector<nurbs::Interface> interfaces;
    int n_nodes = 0;
    RowMatrix node_points;                        ///< n_nodes x d reference coordinates
    mechanics::Material material;
    std::vector<mechanics::ElementGeometry> elements;
    std::vector<std::vector<int>> element_dofs;  ///< full dofs of each element (local dof a*d+i order)
    int first_block = 0;                         ///< pattern block of elements[0]

    std::vector<std::string> patch_names() const;
    /// Bounding-box diagonal of the reference control points.
    double size() const { return (node_points.colwise().maxCoeff() - node_points.colwise().minCoeff()).norm(); }
    /// (side, meaning) as `check` prints them: what each parametric side is on the shape.
    std::vector<std::pair<std::string, std::string>> side_names;
};

/// A follower pressure in finite kinematics (recomputed each evaluation).
struct FollowerPressure {
    int body = 0;
    double pressure = 0.0;  ///< full value, scaled by the amplitude
    Amplitude amplitude;
    mechanics::SideQuadrature side;
    std::vector<std::vector<int>> element_dofs;  ///< full dofs of each side element
    int first_block = 0;
};

/// Dead loads that share one amplitude, summed at full value (full dofs).
struct DeadLoad {
    Amplitude amplitude;
    Vector f;
};

/// A group of constrained dofs whose residual entries sum to one reported reaction:
/// a side (all constraint items on the same body.side together), a body's total or
/// one constraint item's share (analysis/constraints.hpp says how dofs are shared).
struct ReactionGroup {
    std::string name;       ///< path under reactions/: "body.side" ("body.patch.side", "body.surface"),
                            ///< "total/<body>" or "items/<k>"
    std::vector<int> dofs;  ///< full dofs the side prescribes (each once); component = dof % d
};

struct PairModel {
    std::string name;
    contact::ContactPair pair;
    std::array<int, 2> body{-1, -1};                 ///< deformable body index of each surface, -1 rigid
    std::array<std::vector<int>, 2> parent_index;    ///< surface control point -> body node
    std::array<std::string, 2> label;                ///< "cylinder.v0", "cyl.arc" or the rigid body's name
    /// Per surface: its patch sides in the surface's order ("left.v0", ...; "v0" on a
    /// single-patch body), i.e. the pieces of its DeformableSide; empty for a rigid one.
    std::array<std::vector<std::string>, 2> piece_label;
    std::vector<int> local_to_full;                  ///< pair-local dof -> full dof
    std::map<contact::Coupling, int> blocks;         ///< registered coupling -> pattern block
    int obstacle = -1;                               ///< surface index (0/1) of a rigid obstacle, -1 if none
    contact::Formulation formulation = contact::Formulation::two_half_pass;
    bool penalty_auto = false;     ///< the deck says `penalty: auto` (analysis/contact_penalty.hpp)
    double initial_penalty = 0.0;  ///< eps from the deck or the auto rule (the pair's may be raised later)
    bool augmented = false;        ///< enforcement: augmented_lagrangian (analysis/uzawa.hpp)
    double gap_tolerance = 0.0;    ///< augmented: the deck's gap_tolerance; 0 = automatic (contact_penalty.hpp)
    int max_updates = 0;           ///< augmented: Uzawa updates per increment
    AutoPenalty rule{};            ///< E', E*, h, l of the deformable sides and the auto eps (contact_penalty.hpp)
    double gap_tolerance_used = 0.0;  ///< augmented: the tolerance of the last Uzawa check (for output)
};

/// Which connectivity blocks this rank assembles (the parallel model of
/// core/parallel.hpp): element blocks in contiguous ranges (a patch is cut into
/// slabs of knot spans, as its elements are numbered), the blocks after them
/// (follower sides, contact couplings, also those registered later) round robin.
/// One process owns every block.
struct Partition {
    int rank = 0;
    int size = 1;
    int first_element = 0, last_element = 0;  ///< owned element blocks [first, last)
    int n_element_blocks = 0;

    bool owns(int block) const
    {
        if (size == 1)
            return true;
        return block < n_element_blocks ? block >= first_element && block < last_element : block % size == rank;
    }
};

/// What a run needs of the deck beyond the model, read while the scene is built:
/// after build_scene nothing reads the deck.
struct RunSettings {
    std::string source_file;    ///< the deck, for messages located in it
    std::string resolved_yaml;  ///< the deck as resolved, stored in the results
    io::Output output;
    io::Steps steps;
    io::Newton newton;
    io::Solver solver;
    std::vector<std::string> load_body;  ///< per load item of the deck, the body it acts on
    /// Prescribed displacements and obstacle motions: full magnitude and amplitude
    /// (the imposed travel at t is the largest |a(t)| magnitude).
    std::vector<std::pair<double, Amplitude>> imposed_motions;
};

struct Scene {
    RunSettings settings;
    int dim = 2;
    mechanics::Kinematics kinematics = mechanics::Kinematics::small;
    std::vector<BodyModel> bodies;
    std::vector<int> body_of_deck;  ///< deck body index -> deformable body index (-1 for rigid)
    std::unique_ptr<assembly::DofMap> dofs;
    /// Dead tractions, forces, gravity and small-kinematics pressures, one entry per
    /// distinct amplitude (a deck without amplitudes: one, or none without loads).
    std::vector<DeadLoad> dead_loads;
    std::vector<FollowerPressure> followers;
    std::vector<PairModel> pairs;
    std::vector<ReactionGroup> reactions;  ///< sides, then body totals, then constraint items
    std::unique_ptr<assembly::SparsePattern> pattern;
    int n_element_blocks = 0;
    Partition partition;  ///< this rank's blocks; the pattern holds only those (and the diagonal)
    double model_size = 1.0;  ///< bounding-box diagonal of all deformable bodies
    LoadPath path;            ///< [0, T] and the breakpoints of the amplitudes
    /// What the set-up found doubtful but usable (a contact side met edge-on, a
    /// constraint on a collapsed side): said by a run and by `check`.
    std::vector<std::string> setup_warnings;

    bool has_contact() const { return !pairs.empty(); }
    /// The dead external force at pseudo-time t (full dofs): sum of a_k(t) f_k.
    Vector f_ext(double t) const;
};

/// Frees the quadrature data (shape functions and gradients at the Gauss points) of
/// the element blocks for which keep(block) is false; their dof lists stay. Nothing
/// may evaluate those elements afterwards: on several ranks the blocks another rank
/// assembles, under small kinematics every block once K0 is assembled
/// (SceneSystem::assemble_constant_stiffness). In 3D quadratic elements they are a
/// sixth of a run's memory (docs/performance.md "Memory in 3D").
void release_element_geometry(Scene& scene, const std::function<bool(int block)>& keep);

/// The sides a deck reference names on deformable body b of the scene.
std::vector<BodySide> sides_of(const io::Deck& deck, const Scene& scene, const std::string& body,
                               const std::string& patch, Side side, const std::string& surface);

/// Full dofs of a coupling of pair p, in contact::LocalBlock::dofs order.
std::vector<int> coupling_full_dofs(const PairModel& pair, const contact::Coupling& coupling);

/// Whether contact coupling blocks keep no entry positions in the pattern
/// (assembly/sparse_pattern.hpp): in 3D a coupling of two quadratic spans has 162
/// dofs and 105 kB of positions (the candidate couplings of the crossed cylinders,
/// 35k dofs, held 919 MB), so its entries are searched; a 2D one has 5 kB.
inline bool coupling_blocks_searched(int dim)
{
    return dim == 3;
}

/// The load path of a deck: its loads, prescribed displacements (items with a
/// non-zero value or an amplitude) and obstacle motions, each with its amplitude.
LoadPath deck_load_path(const io::Deck& deck);

/// Builds the scene. Geometry problems (a refinement that cannot be applied, a
/// non-positive Jacobian) are reported as DeckError naming the body.
/// `refine_levels` > 0 halves every knot span of every body that many times after
/// the deck's refinement (RunOptions::refine_levels). `stop` is polled per patch
/// (and inside the gluing): a requested stop throws Interrupted.
/// On several ranks (`comm`), each rank's pattern holds only the blocks it owns
/// (Scene::partition); everything else is the same on every rank.
/// A deck material as the element code uses it (the deck's plane mode in 2D).
mechanics::Material to_material(const io::Material& m, const io::Analysis& analysis);

Scene build_scene(const io::Deck& deck, int refine_levels = 0, const StopRequest& stop = {},
                  const Communicator& comm = Communicator());

}  // namespace iga::analysis
