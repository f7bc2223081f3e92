// Tests of io::read_deck / read_deck_text and write_resolved_yaml against
// docs/deck.md: the values and defaults of valid decks, paths, and the
// read -> write -> read round trip of the resolved deck.

#include "deck_test_support.hpp"

#include "io/deck_writer.hpp"
#include "io/yaml_cursor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>

namespace iga::io {
namespace {

using test::cube_deck_3d;
using test::hertz_deck;
using test::minimal_deck;
using test::read;
using test::replaced;
using test::shapes_deck_3d;
using test::two_cylinders_deck;

// ---------------------------------------------------------------------------
// Valid decks

TEST(DeckReader, ReadsEveryValueOfACompleteHertzDeck)
{
    const Deck d = read(hertz_deck);
    EXPECT_EQ(d.format, 1);
    EXPECT_EQ(d.title, "Hertz cylinder on a rigid plane");
    EXPECT_EQ(d.analysis.dimension, 2);
    EXPECT_EQ(d.analysis.plane, PlaneMode::strain);
    EXPECT_EQ(d.analysis.kinematics, Kinematics::finite);

    ASSERT_EQ(d.materials.size(), 1u);
    EXPECT_EQ(d.materials[0], (Material{"rubber", MaterialModel::neo_hookean, 1000.0, 0.3}));

    ASSERT_EQ(d.bodies.size(), 2u);
    const Body& cyl = d.bodies[0];
    EXPECT_EQ(cyl.name, "cylinder");
    EXPECT_FALSE(cyl.rigid);
    EXPECT_EQ(cyl.material, "rubber");
    ASSERT_TRUE(cyl.nurbs.has_value());
    EXPECT_FALSE(cyl.shape.has_value());
    EXPECT_EQ(cyl.nurbs->degrees, (std::vector<int>{2, 1}));
    EXPECT_EQ(cyl.nurbs->knots,
              (std::vector<std::vector<double>>{{0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}}));
    ASSERT_EQ(cyl.nurbs->control_points.size(), 6u);
    EXPECT_EQ(cyl.nurbs->control_points[1], (std::vector<double>{1.0, 0.0, 0.7071067811865476}));
    EXPECT_EQ(cyl.nurbs->control_points[4], (std::vector<double>{0.5, 1.0, 0.7071067811865476}));
    EXPECT_EQ(cyl.refine.elevate, (std::vector<int>{1, 1}));
    EXPECT_EQ(cyl.refine.spans, (std::vector<int>{32, 16}));
    EXPECT_EQ(cyl.refine.insert, (std::vector<std::vector<double>>{{0.05, 0.1}, {}}));

    const Body& floor = d.bodies[1];
    EXPECT_TRUE(floor.rigid);
    ASSERT_TRUE(floor.plane.has_value());
    EXPECT_EQ(floor.plane->point, (std::vector<double>{0.0, -0.5}));
    // [0, 2] normalized: exact, since 2 is a power of two.
    EXPECT_EQ(floor.plane->normal, (std::vector<double>{0.0, 1.0}));

    ASSERT_EQ(d.constraints.size(), 1u);
    EXPECT_EQ(d.constraints[0], (Constraint{"cylinder", Side::u0, {true, false}, {0.0, 0.0}, {}, {}}));
    ASSERT_EQ(d.loads.size(), 1u);
    EXPECT_EQ(d.loads[0].body, "cylinder");
    EXPECT_EQ(d.loads[0].side, Side::v1);
    EXPECT_EQ(d.loads[0].kind, LoadKind::force);
    EXPECT_EQ(d.loads[0].vector, (std::vector<double>{0.0, -5.0}));

    ASSERT_EQ(d.contact.size(), 1u);
    const ContactPair& pair = d.contact[0];
    EXPECT_EQ(pair.name, "cyl_floor");
    EXPECT_EQ(pair.first, (ContactSurface{"cylinder", Side::v0, {}, {}}));
    EXPECT_EQ(pair.second, (ContactSurface{"floor", std::nullopt, {}, {}}));
    EXPECT_EQ(pair.formulation, Formulation::two_half_pass);
    EXPECT_EQ(pair.penalty, 1.0e6);
    EXPECT_EQ(pair.quadrature, 4);

    EXPECT_EQ(d.steps, (Steps{10, true, 4}));
    EXPECT_EQ(d.newton, (Newton{1.0e-9, 30, false}));
    EXPECT_EQ(d.output.file, "inputs/results/hertz_run.h5");  // relative to the deck's folder
    EXPECT_FALSE(d.output.every_step);
    EXPECT_EQ(d.output.samples_per_span, 8);
    EXPECT_TRUE(d.output.paraview);
    ASSERT_TRUE(d.output.reference.has_value());
    EXPECT_EQ(*d.output.reference, (Reference{"cyl_floor", ReferenceType::hertz_cylinder_plane, 1.0, {}, 10.0}));

    EXPECT_EQ(d.source_file, "hertz.yaml");
    EXPECT_EQ(d.resolved_yaml, write_resolved_yaml(d));
}

TEST(DeckReader, Reads3dDeckWithEveryLoadAndConstraintKind)
{
    const Deck d = read(cube_deck_3d);
    EXPECT_EQ(d.analysis.dimension, 3);
    EXPECT_EQ(d.bodies[0].nurbs->control_points.size(), 8u);
    EXPECT_EQ(d.bodies[0].refine.spans, (std::vector<int>{2, 2, 2}));
    // Unit length up to round-off (0.36 + 0.64 in floating point): kept as written.
    EXPECT_EQ(d.bodies[1].plane->normal, (std::vector<double>{0.6, 0.0, 0.8}));
    EXPECT_EQ(d.constraints[0], (Constraint{"cube", Side::w1, {true, true, true}, {0.0, 0.0, -0.2}, {}, {}}));
    EXPECT_EQ(d.constraints[1], (Constraint{"cube", Side::u0, {true, false, true}, {0.0, 0.0, 0.0}, {}, {}}));
    EXPECT_EQ(d.loads[0].kind, LoadKind::gravity);
    EXPECT_FALSE(d.loads[0].side.has_value());
    EXPECT_EQ(d.loads[0].vector, (std::vector<double>{0.0, 0.0, -9.81}));
    EXPECT_EQ(d.loads[0].density, 7800.0);
    EXPECT_EQ(d.loads[1].kind, LoadKind::pressure);
    EXPECT_EQ(d.loads[1].side, Side::v1);
    EXPECT_EQ(d.loads[1].pressure, 2.5);
    EXPECT_EQ(d.contact[0].first, (ContactSurface{"table", std::nullopt, {}, {}}));
    EXPECT_EQ(d.contact[0].second, (ContactSurface{"cube", Side::w0, {}, {}}));
    EXPECT_EQ(d.contact[0].formulation, Formulation::single_pass);
}

TEST(DeckReader, Reads3dShapesAndAPointContactReference)
{
    const Deck d = read(shapes_deck_3d);
    ASSERT_EQ(d.bodies.size(), 3u);
    const Shape& ball = *d.bodies[0].shape;
    EXPECT_EQ(ball.type, ShapeType::sphere_octant);
    EXPECT_EQ(ball.center, (std::vector<double>{0, 0, 1}));
    EXPECT_EQ(ball.radius, 1.0);
    EXPECT_FALSE(ball.extrude.has_value());
    EXPECT_EQ(shape_degrees(ball), (std::vector<int>{2, 1, 2}));
    EXPECT_EQ(d.bodies[0].refine.insert, (std::vector<std::vector<double>>{{0.05}, {0.5}, {0.95}}));
    const Shape& block = *d.bodies[1].shape;
    EXPECT_EQ(block.type, ShapeType::box);
    EXPECT_EQ(block.corner, (std::vector<double>{0, 0, -1}));
    EXPECT_EQ(block.size, (std::vector<double>{2, 2, 1}));
    const Shape& slab = *d.bodies[2].shape;
    EXPECT_EQ(slab.type, ShapeType::quarter_disc);
    EXPECT_EQ(slab.center, (std::vector<double>{3, 1}));
    EXPECT_EQ(slab.extrude, std::optional<double>(0.2));
    EXPECT_EQ(shape_degrees(slab), (std::vector<int>{2, 1, 1}));
    ASSERT_TRUE(d.output.reference.has_value());
    EXPECT_EQ(d.output.reference->type, ReferenceType::hertz_two_spheres);
    EXPECT_EQ(d.output.reference->radii[0], 1.0);
    EXPECT_EQ(d.output.reference->radii[1], 2.0);
    EXPECT_EQ(d.output.reference->force, 1.5);
    // --set reaches the new keys; refine is checked against the shape's degrees (w of the octant: 2).
    const Deck thicker = read(shapes_deck_3d, {"bodies.slab.shape.extrude=0.5",
                                               "output.reference={pair: touch, type: hertz_sphere_plane, radius: 1, "
                                               "force: 2}"});
    EXPECT_EQ(thicker.bodies[2].shape->extrude, std::optional<double>(0.5));
    EXPECT_EQ(thicker.output.reference->type, ReferenceType::hertz_sphere_plane);
    EXPECT_EQ(thicker.output.reference->radius, 1.0);
    EXPECT_NO_THROW(read(shapes_deck_3d, {"bodies.ball.refine.insert=[[], [], [0.9, 0.9]]"}));
    EXPECT_THROW(read(shapes_deck_3d, {"bodies.ball.refine.insert=[[], [], [0.9, 0.9, 0.9]]"}), DeckError);
}

TEST(DeckReader, NormalizesTheRigidPlaneNormal)
{
    const Deck d = read(replaced(minimal_deck, "normal: [0, 1]", "normal: [3, 4]"));
    // 3/5 and 4/5 are each one correctly rounded division.
    EXPECT_EQ(d.bodies[1].plane->normal, (std::vector<double>{3.0 / 5.0, 4.0 / 5.0}));
}

TEST(DeckReader, NormalizesHugeAndTinyNormals)
{
    // Any finite non-zero normal is valid, also where the sum of squares over- or
    // underflows (beyond ~1e154, below ~1e-154): it is scaled by its largest entry first.
    EXPECT_EQ(read(replaced(minimal_deck, "normal: [0, 1]", "normal: [0, 1e300]")).bodies[1].plane->normal,
              (std::vector<double>{0.0, 1.0}));
    constexpr double two_roundings = 4 * std::numeric_limits<double>::epsilon();  // x / scale, then / norm
    for (const char* normal : {"normal: [3e300, 4e300]", "normal: [3e-200, 4e-200]", "normal: [-3e-310, 4e-310]"}) {
        SCOPED_TRACE(normal);
        const std::vector<double> n = read(replaced(minimal_deck, "normal: [0, 1]", normal)).bodies[1].plane->normal;
        ASSERT_EQ(n.size(), 2u);
        EXPECT_NEAR(std::abs(n[0]), 0.6, two_roundings);
        EXPECT_NEAR(n[1], 0.8, two_roundings);
    }
}

TEST(DeckReader, OmittedOptionalSectionsTakeTheDocumentedDefaults)
{
    const Deck d = read(minimal_deck);
    // The values of the deck.md tables, written out (not taken from the structs).
    EXPECT_EQ(d.title, "");
    EXPECT_EQ(d.analysis.plane, PlaneMode::strain);
    EXPECT_EQ(d.analysis.kinematics, Kinematics::small);
    EXPECT_EQ(d.materials[0].model, MaterialModel::linear_elastic);
    EXPECT_EQ(d.contact[0].formulation, Formulation::two_half_pass);
    EXPECT_EQ(d.contact[0].quadrature, 0);  // 0 = degree + 2 of each side
    EXPECT_EQ(d.steps.count, 1);
    EXPECT_TRUE(d.steps.adaptive);
    EXPECT_EQ(d.steps.max_cutbacks, 8);
    EXPECT_EQ(d.newton.tolerance, 1e-10);
    EXPECT_EQ(d.newton.max_iterations, 25);
    EXPECT_TRUE(d.newton.line_search);
    EXPECT_EQ(d.output.file, "inputs/hertz.h5");  // deck name with .h5, in the deck's folder
    EXPECT_TRUE(d.output.every_step);
    EXPECT_EQ(d.output.samples_per_span, 16);
    EXPECT_FALSE(d.output.reference.has_value());
    EXPECT_FALSE(d.output.paraview);
    EXPECT_TRUE(d.bodies[0].refine == Refine{});

    // ... and they agree with the defaults of the structs in io/deck.hpp.
    EXPECT_EQ(d.steps, Steps{});
    EXPECT_EQ(d.newton, Newton{});
    EXPECT_EQ(d.analysis, Analysis{});

    // Empty or null optional sections mean the same as leaving them out.
    const Deck e = read(minimal_deck + "steps: {}\nnewton:\noutput: {}\n");
    EXPECT_EQ(e, d);
}

// deck.md, solver: suitesparse direct by default; only PETSc has iterative methods and
// options, so without a backend they choose petsc (as mpirun -np N > 1 does), and with
// backend suitesparse said outright they are an error (verification/bad_input).
TEST(DeckReader, AnIterativeMethodOrPetscOptionsChooseThePetscBackend)
{
    const Deck d = read(minimal_deck);
    EXPECT_EQ(d.solver.backend, SolverBackend::suitesparse);
    EXPECT_EQ(d.solver.type, SolverType::direct);
    const Deck iterative = read(minimal_deck, {"solver.type=iterative"});
    EXPECT_EQ(iterative.solver.backend, SolverBackend::petsc);
    EXPECT_EQ(iterative.solver.type, SolverType::iterative);
    const Deck options = read(minimal_deck + "solver: {options: \"-ksp_monitor\"}\n");
    EXPECT_EQ(options.solver.backend, SolverBackend::petsc);
    EXPECT_EQ(options.solver.type, SolverType::direct);
    EXPECT_THROW(read(minimal_deck, {"solver.backend=suitesparse", "solver.type=iterative"}), DeckError);
}

TEST(DeckReader, ReadsEnforcementAndAutoPenalty)
{
    const Deck d = read(minimal_deck);
    // deck.md: enforcement penalty; augmented_lagrangian {gap_tolerance automatic, max_updates 30}.
    EXPECT_EQ(d.contact[0].enforcement, Enforcement::penalty);
    EXPECT_FALSE(d.contact[0].penalty_auto);
    EXPECT_EQ(d.contact[0].augmented_lagrangian.gap_tolerance, 0.0);  // 0 = automatic
    EXPECT_EQ(d.contact[0].augmented_lagrangian.max_updates, 30);
    EXPECT_EQ(d.contact[0].augmented_lagrangian, AugmentedLagrangian{});

    const Deck a = read(replaced(minimal_deck, "penalty: 1.0e4",
                                       "penalty: auto\n    enforcement: augmented_lagrangian\n"
                                       "    augmented_lagrangian: {gap_tolerance: 1.0e-9, max_updates: 12}"));
    EXPECT_TRUE(a.contact[0].penalty_auto);
    EXPECT_EQ(a.contact[0].enforcement, Enforcement::augmented_lagrangian);
    EXPECT_EQ(a.contact[0].augmented_lagrangian.gap_tolerance, 1e-9);
    EXPECT_EQ(a.contact[0].augmented_lagrangian.max_updates, 12);
    // Without the map, the defaults.
    const Deck b = read(replaced(minimal_deck, "penalty: 1.0e4",
                                       "penalty: 2.0e4\n    enforcement: augmented_lagrangian"));
    EXPECT_EQ(b.contact[0].penalty, 2e4);
    EXPECT_EQ(b.contact[0].augmented_lagrangian, AugmentedLagrangian{});
    // --set may switch both on.
    const Deck c = read(minimal_deck, {"contact.block_floor.penalty=auto",
                                       "contact.block_floor.enforcement=augmented_lagrangian",
                                       "contact.block_floor.augmented_lagrangian.max_updates=7"});
    EXPECT_TRUE(c.contact[0].penalty_auto);
    EXPECT_EQ(c.contact[0].augmented_lagrangian.max_updates, 7);
}

TEST(DeckReader, ReadsADeckFileAndResolvesPathsAgainstItsFolder)
{
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(::testing::TempDir()) / "igacontact_deck_reader_test";
    fs::create_directories(dir);
    const fs::path deck_path = dir / "contact.case.yaml";
    std::ofstream(deck_path) << minimal_deck;

    const Deck d = read_deck(deck_path.string(), {});
    EXPECT_EQ(d.source_file, deck_path.string());
    EXPECT_EQ(d.output.file, (dir / "contact.case.h5").string());  // only the last extension is replaced

    const Deck relative = read_deck(deck_path.string(), {"output.file=out/run.h5"});
    EXPECT_EQ(relative.output.file, (dir / "out" / "run.h5").string());
    const Deck absolute = read_deck(deck_path.string(), {"output.file=/tmp/run.h5"});
    EXPECT_EQ(absolute.output.file, "/tmp/run.h5");
    fs::remove_all(dir);
}

// ---------------------------------------------------------------------------
// Resolved deck

void expect_round_trip(const std::string& text)
{
    const Deck first = read(text);
    const std::string yaml = write_resolved_yaml(first);
    Deck second;
    ASSERT_NO_THROW(second = read_deck_text(yaml, "resolved.yaml", "")) << yaml;
    EXPECT_EQ(second.resolved_yaml, yaml) << "writing is not idempotent";
    second.source_file = first.source_file;
    EXPECT_TRUE(second == first) << yaml;
}

TEST(ResolvedDeck, RoundTripGivesAnEqualDeck)
{
    expect_round_trip(hertz_deck);
    expect_round_trip(cube_deck_3d);
    expect_round_trip(two_cylinders_deck);
    expect_round_trip(minimal_deck);
    expect_round_trip(shapes_deck_3d);
}

TEST(ResolvedDeck, RoundTripKeepsEnforcementAndAutoPenalty)
{
    expect_round_trip(replaced(minimal_deck, "penalty: 1.0e4",
                                     "penalty: auto\n    enforcement: augmented_lagrangian\n"
                                     "    augmented_lagrangian: {gap_tolerance: 1.0e-9, max_updates: 12}"));
    expect_round_trip(replaced(minimal_deck, "penalty: 1.0e4",
                                     "penalty: 3.0e5\n    enforcement: augmented_lagrangian"));
    const std::string yaml =
        read(replaced(minimal_deck, "penalty: 1.0e4", "penalty: auto")).resolved_yaml;
    EXPECT_NE(yaml.find("\n    penalty: auto\n"), std::string::npos) << yaml;
    EXPECT_NE(yaml.find("\n    enforcement: penalty\n"), std::string::npos) << yaml;
}

TEST(ResolvedDeck, MakesDefaultsExplicit)
{
    const std::string yaml = read(minimal_deck).resolved_yaml;
    for (const char* line : {"title: \"\"", "  plane: strain", "  kinematics: small", "    model: linear_elastic",
                             "    formulation: two_half_pass", "  count: 1", "  adaptive: true", "  max_cutbacks: 8",
                             "  tolerance: 1.0e-10", "  max_iterations: 25", "  line_search: true",
                             "  file: inputs/hertz.h5", "  every_step: true", "  samples_per_span: 16",
                             "  paraview: false"})
        EXPECT_NE(yaml.find(std::string("\n") + line + "\n"), std::string::npos) << line << "\n" << yaml;
    EXPECT_EQ(yaml.find("quadrature"), std::string::npos) << "the degree-dependent default is left out";
}

TEST(ResolvedDeck, NumbersAreShortestExactFloats)
{
    EXPECT_EQ(format_number(1000.0), "1000.0");
    EXPECT_EQ(format_number(0.3), "0.3");
    EXPECT_EQ(format_number(1e-10), "1.0e-10");
    EXPECT_EQ(format_number(-2.5e20), "-2.5e+20");
    EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");
    for (double x : {0.1 + 0.2, 1.0 / 3.0, 6.02214076e23, -1e-300, 0.7071067811865476})
        EXPECT_EQ(parse_number(format_number(x)), x) << format_number(x);
}

TEST(ResolvedDeck, NumbersBeyondADoubleOverflowToInfinityNotZero)
{
    // from_chars leaves its output untouched when out of range; 1e400 was once read as 0.
    EXPECT_EQ(parse_number("1e400"), std::numeric_limits<double>::infinity());
    EXPECT_EQ(parse_number("-1e400"), -std::numeric_limits<double>::infinity());
    EXPECT_EQ(parse_number("1e-400"), 0.0);  // underflow is zero (to_number then judges the range)
    EXPECT_EQ(parse_number("5e-324"), 5e-324);
}

// ---------------------------------------------------------------------------
// Did you mean

TEST(DidYouMean, EditDistanceAndThreshold)
{
    EXPECT_EQ(edit_distance("penalti", "penalty"), 1u);
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
    EXPECT_EQ(edit_distance("", "abc"), 3u);
    EXPECT_EQ(did_you_mean("penalti", {"name", "penalty", "quadrature"}), " (did you mean 'penalty'?)");
    EXPECT_EQ(did_you_mean("samples", {"samples_per_span", "every_step"}), "");  // 9 edits: not a typo
    EXPECT_EQ(did_you_mean("max_iteration", {"tolerance", "max_iterations"}), " (did you mean 'max_iterations'?)");
}

}  // namespace
}  // namespace iga::io
