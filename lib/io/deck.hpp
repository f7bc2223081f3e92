#pragma once
// The deck as plain typed structs: what io::read_deck produces from YAML
// (docs/deck.md, format 1) and what analysis/ turns into a scene.
// Nothing below io/ sees YAML or key strings; only io/, analysis/ and app/
// include this header.
//
// Defaults live here, in the member initializers, and agree with the deck schema
// (io/deck_schema.hpp, whose defaults tests/io/deck_schema_test.cpp holds to these).
// Enumerator spellings equal the deck spellings. Values are validated
// by the reader: a Deck that exists is well-formed (cross-references resolve,
// knot vectors are open, weights positive, ...).

#include "core/model_options.hpp"
#include "core/amplitude.hpp"
#include "core/error.hpp"
#include "core/side.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace iga::io {

// The modelling choices shared with the modules (core/model_options.hpp).
using iga::Formulation;
using iga::Kinematics;
using iga::MaterialModel;
using iga::PlaneMode;
using iga::SolverBackend;
using iga::SolverType;
enum class Enforcement { penalty, augmented_lagrangian };
enum class LawType { penalty, exponential };
enum class ShapeType { half_disc, quarter_disc, rectangle, sphere_octant, box };
enum class LoadKind { traction, force, pressure, gravity };
enum class ReferenceType { hertz_cylinder_plane, hertz_two_cylinders, hertz_sphere_plane, hertz_two_spheres };
enum class AccuracyQuantity { pressure_l2, force, contact_radius, stick_zone };

struct Analysis {
    int dimension = 2;                        ///< 2 or 3 (required in the deck)
    PlaneMode plane = PlaneMode::strain;      ///< 2D only
    Kinematics kinematics = Kinematics::small;

    bool operator==(const Analysis&) const = default;
};

struct Material {
    std::string name;
    MaterialModel model = MaterialModel::linear_elastic;
    double E = 0.0;   ///< Young's modulus, > 0
    double nu = 0.0;  ///< Poisson's ratio, in (-1, 0.5)

    bool operator==(const Material&) const = default;
};

// The steps of a `transform:` list (docs/deck.md, "Placing geometry"), applied in
// list order to the Cartesian control points of a shape or a raw NURBS patch
// (weights kept); d = analysis.dimension. Vectors are kept as written (not
// normalized), so a resolved deck reads back identically.

/// `{translate: [..]}`: x -> x + offset.
struct Translate {
    std::vector<double> offset;  ///< d numbers

    bool operator==(const Translate&) const = default;
};

/// `{rotate: {axis, angle_deg, about}}`: counter-clockwise by the right-hand rule about `axis`.
struct Rotate {
    std::vector<double> axis;   ///< 3D: 3 numbers, non-zero; 2D: empty (the rotation is about z)
    double angle_deg = 0.0;
    std::vector<double> about;  ///< d numbers, a point of the axis (the origin when not given)

    bool operator==(const Rotate&) const = default;
};

/// `{mirror: {normal, point}}`: reflection across the plane (a line in 2D) through `point`.
/// It turns the patch left-handed, so u is reversed after it (sides u0 and u1 trade places).
struct Mirror {
    std::vector<double> normal;  ///< d numbers, non-zero
    std::vector<double> point;   ///< d numbers (the origin when not given)

    bool operator==(const Mirror&) const = default;
};

/// `{scale: s}`: x -> s x, s > 0 (uniform, about the origin).
struct Scale {
    double factor = 1.0;

    bool operator==(const Scale&) const = default;
};

using TransformStep = std::variant<Translate, Rotate, Mirror, Scale>;

/// True when the steps turn orientations over (an odd number of mirrors): the
/// placed patch then has its u direction reversed.
inline bool reverses_u(const std::vector<TransformStep>& steps)
{
    const auto mirrors = std::count_if(steps.begin(), steps.end(),
                                       [](const TransformStep& s) { return std::holds_alternative<Mirror>(s); });
    return mirrors % 2 == 1;
}

/// Raw NURBS data of one patch as written in the deck.
struct NurbsData {
    std::vector<int> degrees;                       ///< one per parametric direction
    std::vector<std::vector<double>> knots;         ///< one open knot vector per direction
    std::vector<std::vector<double>> control_points;///< rows [x, y, (z,) w]; u index fastest
    std::vector<TransformStep> transform;           ///< applied to the control points; side names refer to the result

    bool operator==(const NurbsData&) const = default;
};

/// Built-in exact shape: see nurbs/shapes.hpp for the parametrizations and side
/// names. 2D shapes (half_disc, quarter_disc, rectangle) take 2 coordinates and,
/// in a 3D deck, an extrusion length; 3D shapes (sphere_octant, box) take 3.
struct Shape {
    ShapeType type = ShapeType::rectangle;
    std::vector<double> center;    ///< half_disc, quarter_disc, sphere_octant
    double radius = 0.0;           ///< half_disc, quarter_disc, sphere_octant
    std::vector<double> corner;    ///< rectangle, box
    std::vector<double> size;      ///< rectangle, box
    std::optional<double> extrude; ///< 2D shape in a 3D deck: swept along z over [0, extrude] (required there)
    std::vector<TransformStep> transform;  ///< applied after the extrusion; side names refer to the result

    bool operator==(const Shape&) const = default;
};

/// True for the shapes that are 3D solids as built (sphere_octant, box).
constexpr bool is_solid_shape(ShapeType type)
{
    return type == ShapeType::sphere_octant || type == ShapeType::box;
}

/// The degrees of a built-in shape as nurbs/shapes.hpp builds it, one per
/// parametric direction (io/ may not depend on nurbs/); every direction is a
/// single span on [0, 1] (open knot vectors, no interior knots).
inline std::vector<int> shape_degrees(const Shape& shape)
{
    switch (shape.type) {
    case ShapeType::half_disc: return shape.extrude ? std::vector<int>{3, 1, 1} : std::vector<int>{3, 1};
    case ShapeType::quarter_disc: return shape.extrude ? std::vector<int>{2, 1, 1} : std::vector<int>{2, 1};
    case ShapeType::rectangle: return shape.extrude ? std::vector<int>{1, 1, 1} : std::vector<int>{1, 1};
    case ShapeType::sphere_octant: return {2, 1, 2};
    case ShapeType::box: return {1, 1, 1};
    }
    return {};
}

/// The text of a side reference as the deck writes it: `surface`, `patch.side` or `side`.
inline std::string side_text(const std::string& patch, Side side, const std::string& surface)
{
    if (!surface.empty())
        return surface;
    return patch.empty() ? std::string(side_name(side)) : patch + "." + std::string(side_name(side));
}

/// Refinement, applied in this order: elevate, then uniform spans, then insert.
struct Refine {
    std::vector<int> elevate;                ///< empty: none; else one per direction
    std::vector<int> spans;                  ///< empty: none; else spans per direction
    std::vector<std::vector<double>> insert; ///< empty: none; else knots per direction

    bool operator==(const Refine&) const = default;
};

/// Gauss points per direction and knot span of a body's element integrals and of
/// its loaded sides (tractions, forces, pressures); 0 = the default, max degree + 1.
/// More points for rational patches, whose integrands no Gauss rule integrates exactly.
struct Quadrature {
    int element = 0;
    int side = 0;

    bool operator==(const Quadrature&) const = default;
};

struct RigidPlane {
    std::vector<double> point;   ///< d coordinates
    std::vector<double> normal;  ///< d coordinates, points out of the obstacle (normalized by the reader)

    bool operator==(const RigidPlane&) const = default;
};

/// A rigid circle (2D, deck key `circle`) or sphere (3D, `sphere`): the solid disc
/// or ball; its outward normal points away from the centre.
struct RigidSphere {
    std::vector<double> center;  ///< d coordinates
    double radius = 0.0;         ///< > 0

    bool operator==(const RigidSphere&) const = default;
};

/// One patch of a multi-patch body (`patches:` in the deck, or imported from a
/// geometry file). Its refine applies after the body's.
struct PatchData {
    std::string name;  ///< unique in the body, no '.'; imported patches are p<id>
    NurbsData nurbs;
    Refine refine;

    bool operator==(const PatchData&) const = default;
};

/// `patch.side` of a multi-patch body (patch empty: the side of a single-patch body).
struct PatchSideRef {
    std::string patch;
    Side side = Side::u0;

    bool operator==(const PatchSideRef&) const = default;
};

/// A named set of patch sides (`surfaces: {name: [patch.side, ...]}`), each side once.
struct NamedSurface {
    std::string name;  ///< no '.', not a side name
    std::vector<PatchSideRef> sides;

    bool operator==(const NamedSurface&) const = default;
};

struct Body {
    std::string name;
    bool rigid = false;
    // Deformable body: a material and exactly one of nurbs / shape / patches
    // (`geometry: {file}` fills `patches` when read).
    std::string material;
    std::optional<NurbsData> nurbs;
    std::optional<Shape> shape;
    std::vector<PatchData> patches;  ///< a multi-patch body: its patches; empty otherwise
    std::string geometry_file;       ///< `geometry: {file}` as written (relative to the deck folder); "" if inline
    /// `geometry: {transform}`: copied into every imported patch's nurbs.transform.
    std::vector<TransformStep> geometry_transform;
    Refine refine;                   ///< applies to every patch
    Quadrature quadrature;           ///< applies to every patch
    std::vector<NamedSurface> surfaces;
    // Rigid obstacle: exactly one of plane / sphere, and its motion.
    std::optional<RigidPlane> plane;
    std::optional<RigidSphere> sphere;   ///< `circle` in 2D, `sphere` in 3D
    std::vector<double> motion;          ///< rigid translation at full value; empty: fixed
    std::optional<Amplitude> amplitude{};  ///< `rigid.amplitude` of the motion; unset: the default ramp

    /// True when the body is given as a list of patches (inline or from a file).
    bool multi_patch() const { return !patches.empty(); }
    const NamedSurface* find_surface(const std::string& surface) const
    {
        for (const auto& s : surfaces)
            if (s.name == surface)
                return &s;
        return nullptr;
    }

    bool moves() const { return std::any_of(motion.begin(), motion.end(), [](double m) { return m != 0.0; }); }

    bool operator==(const Body&) const = default;
};

/// Dirichlet condition on every control point of a side. `fix: [x]` and
/// `displacement: [~, -0.1]` (a null leaves that component free) may be combined:
/// a component is prescribed when it is fixed or given a value.
struct Constraint {
    std::string body;
    Side side = Side::u0;
    std::vector<bool> fixed;    ///< d entries: which components are prescribed
    std::vector<double> value;  ///< d entries: prescribed values at full value (0 for `fix` and free ones)
    std::optional<Amplitude> amplitude{};  ///< of the values (only with `displacement`); unset: the default ramp
    std::string patch{};          ///< multi-patch body: the patch of `side` (`patch.side`)
    std::string surface{};        ///< a named surface of the body instead of patch/side

    bool operator==(const Constraint&) const = default;
};

struct Load {
    std::string body;
    std::optional<Side> side;     ///< all kinds but gravity (unset for a named surface)
    LoadKind kind = LoadKind::traction;
    std::vector<double> vector;   ///< traction, force, gravity: d components
    double pressure = 0.0;        ///< pressure: follower, along the inward normal
    double density = 0.0;         ///< gravity: mass per unit reference volume (area in 2D)
    std::string patch{};            ///< multi-patch body: the patch of `side`
    std::string surface{};          ///< a named surface of the body instead of patch/side
    std::optional<Amplitude> amplitude{};  ///< unset: the default ramp

    bool operator==(const Load&) const = default;
};

/// One side of a contact pair: a deformable body's side (`side`, `patch.side`, or
/// a named surface), or a rigid body (no side, no surface).
struct ContactSurface {
    std::string body;
    std::optional<Side> side;
    std::string patch{};    ///< multi-patch body: the patch of `side`
    std::string surface{};  ///< a named surface of the body (then side is unset)

    bool deformable() const { return side.has_value() || !surface.empty(); }

    bool operator==(const ContactSurface&) const = default;
};

/// contact.<pair>.augmented_lagrangian (only with enforcement: augmented_lagrangian).
struct AugmentedLagrangian {
    /// Largest penetration accepted (length units, > 0); 0 = automatic: 1e-3 h p_max / E'
    /// (h the smallest contact-side element, p_max the largest pressure; docs/deck.md).
    double gap_tolerance = 0.0;
    int max_updates = 30;  ///< Uzawa updates per increment before the attempt is cut back, >= 1

    bool operator==(const AugmentedLagrangian&) const = default;
};

/// contact.<pair>.friction: Coulomb friction with a tangential penalty.
struct Friction {
    double coefficient = 0.0;          ///< mu >= 0; 0 (or no key): frictionless
    double tangential_penalty = 0.0;   ///< eps_T > 0, or `auto` (then 0 here and tangential_penalty_auto)
    bool tangential_penalty_auto = true;  ///< `auto`: eps_T = the pair's normal penalty

    bool operator==(const Friction&) const = default;
};

/// contact.<pair>.law: the normal contact law (contact/normal_law.hpp). Absent, or
/// type penalty: the penalty law of `penalty` and `enforcement`.
struct ContactLaw {
    LawType type = LawType::penalty;
    double clearance = 0.0;  ///< exponential: c0 > 0, no pressure at gaps <= -c0
    double pressure = 0.0;   ///< exponential: p0 > 0, the pressure at touch (gap 0)

    bool operator==(const ContactLaw&) const = default;
};

struct ContactPair {
    std::string name;
    ContactSurface first, second;
    Formulation formulation = Formulation::two_half_pass;
    Enforcement enforcement = Enforcement::penalty;
    ContactLaw law;
    double penalty = 0.0;       ///< required unless law is exponential: > 0, or `auto` (then 0 here and penalty_auto)
    bool penalty_auto = false;  ///< `penalty: auto`: chosen from the materials and element size (docs/deck.md)
    AugmentedLagrangian augmented_lagrangian;
    Friction friction;
    int quadrature = 0;    ///< Gauss points per knot span; 0 means degree + 2 of the side

    bool operator==(const ContactPair&) const = default;
};

struct Steps {
    int count = 1;
    bool adaptive = true;
    int max_cutbacks = 8;

    bool operator==(const Steps&) const = default;
};

struct Newton {
    double tolerance = 1e-10;
    int max_iterations = 25;
    bool line_search = true;

    bool operator==(const Newton&) const = default;
};

/// `solver:` the linear solver of Newton's steps (docs/deck.md, "Linear solver").
struct Solver {
    SolverBackend backend = SolverBackend::suitesparse;
    SolverType type = SolverType::direct;
    std::string options;  ///< PETSc options database text (backend petsc)

    bool operator==(const Solver&) const = default;
};

/// True for the references of 3D decks (point contact of spheres).
constexpr bool is_point_contact(ReferenceType type)
{
    return type == ReferenceType::hertz_sphere_plane || type == ReferenceType::hertz_two_spheres;
}

/// True for the references against a rigid plane (they take `radius`; the others take `radii`).
constexpr bool is_against_plane(ReferenceType type)
{
    return type == ReferenceType::hertz_cylinder_plane || type == ReferenceType::hertz_sphere_plane;
}

struct Reference {
    std::string pair;
    ReferenceType type = ReferenceType::hertz_cylinder_plane;  ///< *_cylinder* in 2D decks, *_sphere* in 3D
    double radius = 0.0;                 ///< hertz_cylinder_plane, hertz_sphere_plane
    std::vector<double> radii;           ///< hertz_two_cylinders, hertz_two_spheres: two radii
    /// 2D: total force per unit thickness on the whole cylinder; 3D: total force on
    /// the whole sphere (also when the deck models a symmetric part of it).
    double force = 0.0;

    bool operator==(const Reference&) const = default;
};

struct Output {
    std::string file;              ///< resolved: deck name with .h5 when not given (relative to the deck folder)
    bool every_step = true;
    int samples_per_span = 16;
    std::optional<Reference> reference;
    bool paraview = false;
    /// Stress fields at the tessellation points; the reader defaults it to `paraview`.
    bool fields = false;

    bool operator==(const Output&) const = default;
};

/// `accuracy:` (docs/deck.md "Accuracy on demand"): refine toward the contact zone of `pair`
/// until the estimated relative error of `quantity` is at most `error`, within the budget.
struct Accuracy {
    std::string pair;
    AccuracyQuantity quantity = AccuracyQuantity::pressure_l2;
    double error = 0.0;    ///< relative, > 0
    int levels = 6;        ///< levels at most, the deck's mesh included
    double dofs = 0.0;     ///< a level above this many dofs is not run; 0: no limit
    double seconds = 0.0;  ///< no level starts that would end after this; 0: no limit

    bool operator==(const Accuracy&) const = default;
};

struct Deck {
    int format = 1;
    std::string title;
    Analysis analysis;
    std::vector<Material> materials;
    std::vector<Body> bodies;
    std::vector<Constraint> constraints;
    std::vector<Load> loads;
    std::vector<ContactPair> contact;
    Steps steps;
    Newton newton;
    Solver solver;
    Output output;
    std::optional<Accuracy> accuracy;  ///< `accuracy:`; empty: the deck's mesh is solved once

    std::string source_file;  ///< path of the deck file as given
    std::string resolved_yaml;///< the resolved deck (after --set, defaults filled in), for /deck and `check`


    bool operator==(const Deck&) const = default;

    const Material* find_material(const std::string& name) const
    {
        for (const auto& m : materials)
            if (m.name == name)
                return &m;
        return nullptr;
    }
    const Body* find_body(const std::string& name) const
    {
        for (const auto& b : bodies)
            if (b.name == name)
                return &b;
        return nullptr;
    }
};

}  // namespace iga::io
