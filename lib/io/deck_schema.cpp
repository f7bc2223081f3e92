// The deck schema's table: every key of the deck format, one row each
// (io/deck_schema.hpp says what derives from it). To add a key, add its row here,
// then see docs/architecture.md, "Where to change X: a deck key".
#include "io/deck_schema_rows.hpp"

namespace iga::io::schema_rows {
namespace {

// Groups: maps and lists that appear in several places of the deck. Their paths
// are relative to the map, or to an item of the list.

/// The steps of a `transform:` list; each item has exactly one of the four keys, in
/// the order of io::transform_step_keys.
constexpr Row transform_steps[] = {
    {"translate", numbers("d numbers"), needed("one of four"), "x → x + t: `{translate: [dx, dy(, dz)]}`"},
    {"rotate", map(), needed("one of four"),
     "`{rotate: {axis: [ax, ay, az], angle_deg: a, about: [..]}}`: by a degrees, counter-clockwise by the "
     "right-hand rule about `axis`, around the line through `about`"},
    {"rotate.axis", numbers("3 numbers, non-zero"), needed("3D"),
     "any non-zero length. 3D: required. 2D: the rotation is about z; leave `axis` out or write `[0, 0, 1]` (a "
     "negative angle turns clockwise)"},
    {"rotate.angle_deg", number(), required, "the angle in degrees"},
    {"rotate.about", numbers("d numbers"), fallback("the origin"), "a point of the axis"},
    {"mirror", map(), needed("one of four"),
     "`{mirror: {normal: [..], point: [..]}}`: reflection across the plane (a line in 2D) through `point` with "
     "the normal `normal`"},
    {"mirror.normal", numbers("d numbers, non-zero"), required, "the plane's normal, any length"},
    {"mirror.point", numbers("d numbers"), fallback("the origin"), "a point of the plane"},
    {"scale", number(above(0, "a uniform scale factor; use mirror to turn the patch over")), needed("one of four"),
     "`{scale: s}`: x → s x, uniform, about the origin. To scale about a point p, translate by −p, scale, "
     "translate by p"},
};

/// A NURBS patch given by its data (`nurbs:` of a body or of one of its `patches`).
constexpr Row nurbs_patch[] = {
    {"degrees", integers("list of d integers", at_least(1)), required,
     "polynomial degree per parametric direction (u, v[, w])"},
    {"knots", other("list of d number lists"), required, "one open knot vector per direction"},
    {"control_points", other("list of rows"), required,
     "`[x, y, w]` in 2D, `[x, y, z, w]` in 3D; w is the weight (> 0), and x, y, z are the Cartesian point "
     "itself, not x·w. The u index runs fastest, then v, then w"},
    {"transform", list_of(transform_steps, "transform").shown_as("list of steps"), fallback("none"),
     "moves the patch into place before `refine` ([placing geometry](#placing-geometry-transform))"},
};

/// Refinement of a body or of one of its patches, applied in row order.
constexpr Row refinement[] = {
    {"elevate", integers("list of d integers", at_least(0)), fallback("none"),
     "first, raise each degree by this much (interior knots are repeated along with it, so continuity is kept)"},
    {"spans", integers("list of d integers", at_least(1)), fallback("none"),
     "then insert knots uniformly in the parameter, so that each direction has this many spans. This counts "
     "spans, not knots. Existing breakpoints that are off the uniform grid are kept, and so add spans"},
    {"insert", other("list of d number lists"), fallback("none"),
     "then insert these parameter values (`[]` for none). A value already present raises its multiplicity, "
     "which lowers the continuity there. Values must lie strictly inside the parameter interval, and no knot "
     "may end up repeated more than the (elevated) degree"},
};

// The deck. "d" is analysis.dimension; a default "— (case)" means required in that case.

constexpr Row deck_rows[] = {
    {"format", integer(), required, "the deck format version; must be `1`"},
    {"title", text(), fallback("`\"\"`"), "free text; it travels with the deck into `/deck` of the results"},
    {"analysis", map(), required, "dimension, plane mode, kinematics"},
    {"materials", list(), required, "at least one material"},
    {"bodies", list(), required, "at least one deformable body; rigid obstacles are optional"},
    {"constraints", list(), fallback("none"), "Dirichlet conditions on patch sides"},
    {"loads", list(), fallback("none"), "tractions, forces, pressures, gravity"},
    {"contact", list(), fallback("none"), "contact pairs. Without any, no contact work is done at all"},
    {"steps", map(), fallback("one increment"), "load stepping (over the whole [load path](#load-paths-amplitude))"},
    {"newton", map(), fallback("see below"), "nonlinear solver settings"},
    {"solver", map(), fallback("SuiteSparse, direct"),
     "the linear solver: backend, direct or iterative, PETSc options"},
    {"output", map(), fallback("see below"), "results file and what goes in it"},

    {"analysis.dimension", integer().shown_as("`2` or `3`"), required,
     "2: plane problems on bivariate patches (everything is per unit thickness). 3: solids on trivariate patches"},
    {"analysis.plane", choice<PlaneMode>(), fallback("`strain`"),
     "plane strain or plane stress. 2D only: giving it in 3D is an error"},
    {"analysis.kinematics", choice<Kinematics>(), fallback("`small`"),
     "`small`: linearized strain, equilibrium in the reference configuration. `finite`: total Lagrangian, "
     "geometrically nonlinear"},

    {"materials.*.name", text("word"), required, "what bodies refer to"},
    {"materials.*.model", choice<MaterialModel>(), fallback("`linear_elastic`"), "the elastic law"},
    {"materials.*.E", number(above(0)), required, "Young's modulus"},
    {"materials.*.nu", number(inside(-1, 0.5)), required, "Poisson's ratio"},

    {"bodies.*.name", text("word"), required, "what constraints, loads and contact pairs refer to"},
    {"bodies.*.material", text("name"), needed("deformable"), "one of `materials`"},
    {"bodies.*.nurbs", map_of(nurbs_patch, "nurbs"), needed("one of four"),
     "the patch itself ([below](#deformable-body)); give exactly one of `nurbs`, `shape`, `patches`, `geometry`"},
    {"bodies.*.shape", map(), needed("one of four"),
     "a built-in exact shape ([below](#built-in-shapes)); it may take `transform` too"},
    {"bodies.*.patches", list(), needed("one of four"),
     "several patches glued along whole sides ([below](#multi-patch-bodies-and-named-surfaces))"},
    {"bodies.*.geometry", map(), needed("one of four"),
     "the patches from a G+Smo XML file ([below](#gsmo-xml-geometry-files))"},
    {"bodies.*.geometry.file", text("path"), required, "the XML file, relative to the deck's folder"},
    {"bodies.*.geometry.transform", list_of(transform_steps, "transform").shown_as("list of steps"), fallback("none"),
     "places every patch of the file ([placing geometry](#placing-geometry-transform)); they are glued after it"},
    {"bodies.*.refine", map_of(refinement, "refine"), fallback("no refinement"),
     "refinement that keeps the geometry exactly ([below](#deformable-body)); it applies to every patch"},
    {"bodies.*.quadrature", map(), fallback("max degree + 1"),
     "Gauss points per direction and knot span, for every patch of the body ([below](#deformable-body))"},
    {"bodies.*.quadrature.element", integer(at_least(1)), fallback("max degree + 1"),
     "of the body's element integrals (stiffness, internal force, gravity)"},
    {"bodies.*.quadrature.side", integer(at_least(1)), fallback("max degree + 1"),
     "of its loaded sides (traction, force, pressure)"},
    {"bodies.*.surfaces", other("map of names to lists of sides"), fallback("none"),
     "named sets of patch sides of a multi-patch body ([below](#multi-patch-bodies-and-named-surfaces))"},
    {"bodies.*.rigid", map(), needed("obstacle"),
     "makes the item a rigid obstacle ([below](#rigid-obstacle)), which takes no other key but `name`"},

    {"bodies.*.shape.type", choice<ShapeType>(), required, "which shape ([below](#built-in-shapes))"},
    {"bodies.*.shape.center", numbers("2 or 3 numbers"), needed("discs, sphere_octant"),
     "the centre c of a `half_disc`, `quarter_disc` (2 numbers, also in a 3D deck) or `sphere_octant` (3)"},
    {"bodies.*.shape.radius", number(above(0)), needed("discs, sphere_octant"), "its radius R"},
    {"bodies.*.shape.corner", numbers("2 or 3 numbers"), needed("rectangle, box"),
     "the lowest corner of a `rectangle` (2 numbers, also in a 3D deck) or `box` (3)"},
    {"bodies.*.shape.size", numbers("2 or 3 numbers", above(0)), needed("rectangle, box"),
     "its width and height (and depth)"},
    {"bodies.*.shape.extrude", number(above(0)), needed("2D shape in 3D"),
     "a 2D shape in a 3D deck is swept along z from z = 0 to z = `extrude`"},
    {"bodies.*.shape.transform", list_of(transform_steps, "transform").shown_as("list of steps"), fallback("none"),
     "places the shape, after the extrusion ([placing geometry](#placing-geometry-transform))"},

    {"bodies.*.patches.*.name", text("word"), required,
     "unique in the body; its sides are `name.side` (`left.v0`)"},
    {"bodies.*.patches.*.nurbs", map_of(nurbs_patch, "nurbs"), required,
     "the patch, as for a single-patch body ([nurbs](#deformable-body))"},
    {"bodies.*.patches.*.refine", map_of(refinement, "refine"), fallback("none"),
     "after the body's `refine`, this patch only ([refine](#deformable-body))"},

    {"bodies.*.rigid.plane", map(), needed("one shape"),
     "a half-space bounded by a plane (a line in 2D); give one of `plane` and `circle` (2D) / `sphere` (3D)"},
    {"bodies.*.rigid.plane.point", numbers("d numbers"), required, "any point of the plane (a line in 2D)"},
    {"bodies.*.rigid.plane.normal", numbers("d numbers, non-zero"), required,
     "the normal pointing **out of** the obstacle, towards the bodies. Its length does not matter (it is "
     "normalized)"},
    {"bodies.*.rigid.circle", map(), needed("one shape"),
     "2D: the solid disc; its surface normal points away from the centre. The projection onto it is exact (no "
     "discretization)"},
    {"bodies.*.rigid.circle.center", numbers("2 numbers"), required, "its centre"},
    {"bodies.*.rigid.circle.radius", number(above(0)), required, "its radius"},
    {"bodies.*.rigid.sphere", map(), needed("one shape"), "3D: the solid ball, as `circle` in 2D"},
    {"bodies.*.rigid.sphere.center", numbers("3 numbers"), required, "its centre"},
    {"bodies.*.rigid.sphere.radius", number(above(0)), required, "its radius"},
    {"bodies.*.rigid.motion", numbers("d numbers"), fallback("none (fixed)"),
     "the obstacle translates by `load factor × motion`. A punch or indenter driven by displacement is one deck"},
    {"bodies.*.rigid.amplitude", other("list of `[time, value]`"), fallback("`[[0, 0], [1, 1]]`"),
     "only with `motion`: the obstacle translates by `a(t) × motion` instead ([load "
     "paths](#load-paths-amplitude)). It sits next to the `motion` it scales"},

    {"constraints.*.body", text("name"), required, "a deformable body"},
    {"constraints.*.side", other("side"), required,
     "`u0`, `u1`, `v0`, `v1` (and `w0`, `w1` in 3D); `patch.side` or a named surface of a multi-patch body"},
    {"constraints.*.fix", other("list of components"), needed("or `displacement`"),
     "from `x`, `y` (`z`): these components are held at zero"},
    {"constraints.*.displacement", other("d entries, numbers or `~`"), needed("or `fix`"),
     "the components given a number are prescribed, with this value at load factor 1 (scaled by the load factor "
     "like the loads); a `~` (YAML null) leaves that component free"},
    {"constraints.*.amplitude", other("list of `[time, value]`"), fallback("`[[0, 0], [1, 1]]`"),
     "only with `displacement`: the prescribed values follow `a(t) × value` ([load "
     "paths](#load-paths-amplitude)); `fix` components stay at zero. A `fix`-only item has nothing to scale and "
     "takes none"},

    {"loads.*.body", text("name"), required, "a deformable body"},
    {"loads.*.side", other("side"), needed("not gravity"),
     "required for `traction`, `force` and `pressure`. Not allowed for `gravity`, which acts on the whole body"},
    {"loads.*.traction", numbers("d numbers"), needed("one kind"),
     "dead traction per unit **reference** length (area in 3D)"},
    {"loads.*.force", numbers("d numbers"), needed("one kind"),
     "the total force on the side, applied as the uniform dead traction force / (reference length of the side). "
     "The nodal forces add up to it exactly. A side collapsed to a point cannot carry one"},
    {"loads.*.pressure", number(), needed("one kind"),
     "pressure on the side, acting along the inward normal (positive pushes into the body; a side collapsed to a "
     "point, or of zero area, carries none). Under `finite` kinematics it follows the deformed side (follower "
     "load, with its tangent). Under `small` kinematics it acts on the reference side"},
    {"loads.*.gravity", numbers("d numbers"), needed("one kind"), "acceleration vector"},
    {"loads.*.density", number(above(0)), needed("gravity"),
     "with `gravity` only, and required there: mass per unit reference volume (area in 2D)"},
    {"loads.*.amplitude", other("list of `[time, value]`"), fallback("`[[0, 0], [1, 1]]`"),
     "on every kind of load: the load acts at `a(t) ×` its value ([load paths](#load-paths-amplitude)); a "
     "follower pressure is scaled the same way"},

    {"contact.*.name", text("word"), required,
     "names the pair in `--set` paths, in the results (`contact/<name>`) and in `output.reference`"},
    {"contact.*.between", other("list of two surfaces"), required,
     "each is `body.side` for a deformable body, or the bare name of a rigid body. At least one must be "
     "deformable, and the two must differ"},
    {"contact.*.formulation", choice<Formulation>(), fallback("`two_half_pass`"),
     "how the penalty is applied (below, and [theory.md, \"Contact formulation\"](theory.md#contact-formulation))"},
    {"contact.*.enforcement", choice<Enforcement>(), fallback("`penalty`"),
     "how the contact constraint is enforced (below); not `augmented_lagrangian` with `law: exponential`"},
    {"contact.*.penalty", number_or_auto(above(0)), needed("unless `law` is exponential"),
     "the penalty parameter ε: contact pressure per unit penetration; with `augmented_lagrangian` the "
     "augmentation parameter. `auto`: ε = min(1e4·E*/l, 100·E′/h) (below). Not with `law: exponential`"},
    {"contact.*.law", map(), fallback("the penalty law (`penalty`, `enforcement`)"),
     "the normal contact law, pressure against gap (below, [Contact laws](#contact-laws))"},
    {"contact.*.law.type", choice<LawType>(), required,
     "`exponential`: softened pressure-overclosure; `penalty`: as if `law` were absent"},
    {"contact.*.law.clearance", number(above(0)), needed("`type: exponential`"),
     "c₀, a length: the open gap at which the pressure starts (zero at gaps ≤ −c₀)"},
    {"contact.*.law.pressure", number(above(0)), needed("`type: exponential`"),
     "p₀: the pressure at touch (gap 0); beyond it the pressure grows linearly with the slope at touch"},
    {"contact.*.augmented_lagrangian", map(), fallback("see its keys"),
     "only with `enforcement: augmented_lagrangian` (below)"},
    {"contact.*.augmented_lagrangian.gap_tolerance", number(above(0)), fallback("automatic"),
     "the largest penetration accepted, a length (below)"},
    {"contact.*.augmented_lagrangian.max_updates", integer(at_least(1)), fallback("`30`"),
     "multiplier updates per increment before the attempt counts as failed (below)"},
    {"contact.*.friction", map(), fallback("none (frictionless)"),
     "Coulomb friction, in any pair (below)"},
    {"contact.*.friction.coefficient", number(at_least(0, "0: frictionless")), required,
     "the friction coefficient μ; 0 is frictionless"},
    {"contact.*.friction.tangential_penalty", number_or_auto(above(0)), fallback("`auto`"),
     "the tangential penalty ε_T; `auto`: ε_T = the pair's normal penalty"},
    {"contact.*.quadrature", integer(at_least(1)), fallback("degree + 2 of the carrying side"),
     "Gauss points per knot span on each side that carries them"},

    {"steps.count", integer(at_least(1)), fallback("`1`"),
     "initial number of increments. The load factor goes from 0 to 1 in steps of 1/`count`; 1/`count` is also "
     "the largest increment an adaptive run takes. With [amplitudes](#load-paths-amplitude) the pseudo-time goes "
     "from 0 to T in steps of T/`count` (read 1/`count` as T/`count` in this table)"},
    {"steps.adaptive", boolean(), fallback("`true`"),
     "if an increment fails, halve it and retry. After a converged increment of n Newton iterations, scale the "
     "next one by 6/n if n < 6 (at most 2; an increment converged at its start state: 2), keep it for n = 6 to 10, "
     "and scale it by 10/n (at least 0.5) if n > 10; never beyond 1/`count`"},
    {"steps.max_cutbacks", integer(at_least(0)), fallback("`8`"),
     "how many halvings one increment may take before the run stops as failed. An increment never becomes "
     "smaller than 1/`count`/2^`max_cutbacks`"},

    {"newton.tolerance", number(above(0)), fallback("`1e-10`"), "convergence when ‖r‖ / (force scale) ≤ tolerance"},
    {"newton.max_iterations", integer(at_least(1)), fallback("`25`"), "per attempt at an increment"},
    {"newton.line_search", boolean(), fallback("`true`"),
     "if the full step does not reduce ‖r‖, search along it (a directional search on the work done by the "
     "residual, with backtracking on ‖r‖ as a fallback). `false` takes full steps, still capped by the trust "
     "radius when there is contact"},

    {"solver.backend", choice<SolverBackend>(), fallback("`suitesparse`; `petsc` when `type: iterative` or `options` is given"),
     "`suitesparse`: CHOLMOD (symmetric tangents) or UMFPACK (two-half-pass pairs, follower loads), one process. "
     "`petsc`: a distributed matrix on the MPI ranks of the run (one without `mpirun`); needs a build with PETSc "
     "(`scripts/setup.sh` installs it). Under `mpirun -np N` with N > 1 the backend is `petsc` whatever the deck "
     "says"},
    {"solver.type", choice<SolverType>(), fallback("`direct`"),
     "`petsc` only for `iterative` (without a `backend`, `iterative` chooses `petsc`). `direct`: MUMPS "
     "(Cholesky/LDLᵀ for symmetric tangents, LU otherwise). `iterative`: CG (symmetric) or GMRES(100) (otherwise) "
     "with an algebraic multigrid (GAMG, or hypre BoomerAMG where a penalty is stiff; [parallel.md](parallel.md)), "
     "to a relative true residual of 1e-8; GMRES with a MUMPS LU where two deformable bodies are in two-half-pass "
     "contact (no multigrid fits that tangent). A Krylov solve that stalls stops early, with a warning"},
    {"solver.options", text(), fallback("none"),
     "`petsc` only (without a `backend`, `options` choose `petsc`): PETSc options of the linear solver (`-ksp_*`, "
     "`-pc_*`, `-mat_*` and the inner solvers' `-mg_*`, `-sub_*`, ...), applied after igacontact's defaults, so they "
     "win (e.g. `-pc_type gamg`, `-ksp_rtol 1e-10`, `-ksp_monitor`); the `PETSC_OPTIONS` environment variable is "
     "read after them and wins over both. Both are checked before PETSc sees them: an option that would make PETSc "
     "write or read a file or print its help or a log, or a tolerance out of range, is refused, and what PETSc "
     "prints goes to standard error ([parallel.md](parallel.md#petsc-options))"},

    {"output.file", text("path"), fallback("the deck's name with `.h5`, next to the deck"),
     "results file, relative to the deck's folder. `-o FILE` on the command line wins, and is relative to the "
     "current folder"},
    {"output.every_step", boolean(), fallback("`true`"),
     "store every converged increment under `/steps`. With `false`, only the last converged one is stored"},
    {"output.samples_per_span", integer(at_least(1)), fallback("`16`"),
     "points per knot span at which the post-processed contact pressure is sampled"},
    {"output.reference", map(), fallback("none"),
     "an analytic solution stored beside the results, with this run's errors against it (below)"},
    {"output.reference.pair", text("name"), required, "the contact pair to measure"},
    {"output.reference.type", choice<ReferenceType>(), required,
     "`hertz_cylinder_plane`: an elastic cylinder on a rigid plane (the pair is a deformable side and a rigid "
     "plane). `hertz_two_cylinders`: two elastic cylinders (the pair has two deformable sides). "
     "`hertz_sphere_plane` and `hertz_two_spheres`: the same for spheres (3D point contact)"},
    {"output.reference.radius", number(above(0)), needed("`*_plane`"),
     "for `hertz_cylinder_plane` and `hertz_sphere_plane`"},
    {"output.reference.radii", numbers("two numbers", above(0)), needed("`hertz_two_*`"),
     "for `hertz_two_cylinders` and `hertz_two_spheres`, in the order of `between`"},
    {"output.reference.force", number(above(0)), required,
     "2D: the total force per unit thickness on the **whole** cylinder, also when the deck models only a "
     "symmetric half of it. 3D: the total force on the **whole** sphere, also when the deck models an octant or "
     "a quarter of it"},
    {"output.paraview", boolean(), fallback("`false`"),
     "also write an XDMF file next to the results file, for ParaView"},
    {"output.fields", boolean(), fallback("`false` (`true` when `paraview` is)"),
     "Cauchy stress and von Mises stress at the tessellation points of every stored increment "
     "(`/steps/<kkkk>/fields/<body>/`, docs/results.md), shown in the XDMF"},

    {"accuracy", map(), fallback("none: the deck's mesh is solved once"),
     "refine toward the contact zone until a contact quantity meets an error target: the deck's mesh is level 0, "
     "each level halves the knot spans over and around the zone of `target.pair` and solves again "
     "(docs/accuracy_on_demand.md)"},
    {"accuracy.target", map(), required, "what to reach"},
    {"accuracy.target.pair", text("name"), required, "the contact pair whose zone is refined and measured"},
    {"accuracy.target.quantity", choice<AccuracyQuantity>(), fallback("`pressure_l2`"),
     "`pressure_l2`: the post-processed pressure over the contact side, in the L2 norm. `force`: the contact "
     "normal force. `contact_radius`: the contact zone's half-width (2D) or radius (3D), of the whole zone on a "
     "half or quarter model (its symmetry planes are read from the constraints: "
     "[accuracy_on_demand.md](accuracy_on_demand.md#symmetry-planes)). `stick_zone`: the sticking part of the "
     "zone at the end of the load path, its length (2D) or the radius of a disc of its area (3D), also of the "
     "whole zone; the pair needs friction"},
    {"accuracy.target.error", number(above(0)), required,
     "the relative error allowed, e.g. `0.01`; the run ends at the first level whose estimated error, times the "
     "safety factor 1.25, is at most this"},
    {"accuracy.budget", map(), fallback("`{levels: 6}`"), "when to give up: exit 1, with the error reached"},
    {"accuracy.budget.levels", integer(at_least(2, "level 0 has no estimate: at least two levels")),
     fallback("`6`"), "levels at most, level 0 (the deck's mesh) included"},
    {"accuracy.budget.dofs", number(at_least(0)), fallback("`0`: no limit"),
     "a level with more dofs than this is not run"},
    {"accuracy.budget.seconds", number(at_least(0)), fallback("`0`: no limit"),
     "no level starts that would, at the pace of the last one, end after this many seconds of the run"},
};

}  // namespace

std::span<const Row> deck_table()
{
    return deck_rows;
}

}  // namespace iga::io::schema_rows
