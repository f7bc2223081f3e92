#pragma once
// Shared pieces of the deck reader and --set tests: a small valid deck whose
// line numbers the tests quote, a realistic Hertz deck, and helpers that read
// a deck and return the formatted issues.

#include "io/deck_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace iga::io::test {

/// A minimal valid 2D deck. The tests replace one piece of it and quote the line
/// numbers below, so keep its lines where they are.
inline const std::string minimal_deck = R"(format: 1
analysis: {dimension: 2}
materials:
  - name: steel
    model: linear_elastic
    E: 1000
    nu: 0.3
bodies:
  - name: block
    material: steel
    shape: {type: rectangle, corner: [0, 0], size: [2, 1]}
  - name: floor
    rigid: {plane: {point: [0, 0], normal: [0, 1]}}
constraints:
  - {body: block, side: u0, fix: [x]}
loads:
  - {body: block, side: v1, traction: [0, -1]}
contact:
  - name: block_floor
    between: [block.v0, floor]
    penalty: 1.0e4
)";

/// A realistic Hertz deck (explicit NURBS quarter cylinder, refinement, every
/// section given), a 3D deck with every load and constraint kind, and a deck of
/// two built-in shapes in contact.
inline const std::string hertz_deck = R"(# Hertz: elastic quarter cylinder pressed on a rigid plane, plane strain.
format: 1
title: Hertz cylinder on a rigid plane
analysis:
  dimension: 2
  plane: strain
  kinematics: finite
materials:
  - name: rubber
    model: neo_hookean
    E: 1000
    nu: 0.3
bodies:
  - name: cylinder
    material: rubber
    nurbs:
      degrees: [2, 1]
      knots: [[0, 0, 0, 1, 1, 1], [0, 0, 1, 1]]
      control_points:
        - [0.0, 0.0, 1.0]
        - [1.0, 0.0, 0.7071067811865476]
        - [1.0, 1.0, 1.0]
        - [0.0, 1.0, 1.0]
        - [0.5, 1.0, 0.7071067811865476]
        - [1.0, 1.0, 1.0]
    refine:
      elevate: [1, 1]
      spans: [32, 16]
      insert: [[0.05, 0.1], []]
  - name: floor
    rigid: {plane: {point: [0, -0.5], normal: [0, 2]}}
constraints:
  - {body: cylinder, side: u0, fix: [x]}
loads:
  - {body: cylinder, side: v1, force: [0, -5]}
contact:
  - name: cyl_floor
    between: [cylinder.v0, floor]
    formulation: two_half_pass
    penalty: 1.0e6
    quadrature: 4
steps: {count: 10, adaptive: true, max_cutbacks: 4}
newton: {tolerance: 1.0e-9, max_iterations: 30, line_search: false}
output:
  file: results/hertz_run.h5
  every_step: false
  samples_per_span: 8
  reference: {pair: cyl_floor, type: hertz_cylinder_plane, radius: 1.0, force: 10.0}
  paraview: true
)";

inline const std::string cube_deck_3d = R"(format: 1
analysis: {dimension: 3, kinematics: small}
materials:
  - {name: steel, model: saint_venant_kirchhoff, E: 210000, nu: 0.29}
bodies:
  - name: cube
    material: steel
    nurbs:
      degrees: [1, 1, 1]
      knots: [[0, 0, 1, 1], [0, 0, 1, 1], [0, 0, 1, 1]]
      control_points:
        - [0, 0, 0, 1]
        - [1, 0, 0, 1]
        - [0, 1, 0, 1]
        - [1, 1, 0, 1]
        - [0, 0, 1, 1]
        - [1, 0, 1, 1]
        - [0, 1, 1, 1]
        - [1, 1, 1, 1]
    refine: {spans: [2, 2, 2]}
  - name: table
    rigid: {plane: {point: [0, 0, -0.1], normal: [0.6, 0, 0.8]}}
constraints:
  - {body: cube, side: w1, displacement: [0, 0, -0.2]}
  - {body: cube, side: u0, fix: [x, z]}
loads:
  - {body: cube, gravity: [0, 0, -9.81], density: 7800}
  - {body: cube, side: v1, pressure: 2.5}
contact:
  - {name: cube_table, between: [table, cube.w0], formulation: single_pass, penalty: 1.0e5}
)";

inline const std::string two_cylinders_deck = R"(format: 1
title: "two cylinders: 'mate'"
analysis: {dimension: 2, plane: stress}
materials:
  - {name: a, E: 1, nu: -0.5}
bodies:
  - {name: lower, material: a, shape: {type: half_disc, center: [0, 1], radius: 1}}
  - name: upper
    material: a
    shape: {type: quarter_disc, center: [0, 3], radius: 2}
    refine: {insert: [[0.5, 0.5], [0.25]]}
contact:
  - {name: mate, between: [lower.v0, upper.v0], penalty: 50}
output: {reference: {pair: mate, type: hertz_two_cylinders, radii: [1, 2], force: 3}}
)";


/// A 3D deck of the built-in 3D shapes: a sphere octant on a box, an extruded
/// quarter disc, and a point-contact reference.
inline const std::string shapes_deck_3d = R"(format: 1
analysis: {dimension: 3}
materials:
  - {name: m, E: 1000, nu: 0.3}
bodies:
  - name: ball
    material: m
    shape: {type: sphere_octant, center: [0, 0, 1], radius: 1}
    refine: {elevate: [0, 1, 0], insert: [[0.05], [0.5], [0.95]]}
  - {name: block, material: m, shape: {type: box, corner: [0, 0, -1], size: [2, 2, 1]}}
  - {name: slab, material: m, shape: {type: quarter_disc, center: [3, 1], radius: 1, extrude: 0.2}}
contact:
  - {name: touch, between: [ball.v0, block.w1], penalty: 1.0e5}
output:
  reference: {pair: touch, type: hertz_two_spheres, radii: [1, 2], force: 1.5}
)";

/// `text` with the single occurrence of `from` replaced by `to`.
inline std::string replaced(const std::string& text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' is not in the deck";
    EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "'" << from << "' occurs twice in the deck";
    if (at == std::string::npos)
        return text;
    return text.substr(0, at) + to + text.substr(at + from.size());
}

/// Reads `text` as inputs/hertz.yaml (deck folder "inputs").
inline Deck read(const std::string& text, const std::vector<std::string>& sets = {})
{
    return read_deck_text(text, "hertz.yaml", "inputs", sets);
}

/// The formatted issues of reading `text`; a test failure if it reads fine.
inline std::vector<std::string> issues_of(const std::string& text, const std::vector<std::string>& sets = {})
{
    try {
        read(text, sets);
    } catch (const DeckError& e) {
        std::vector<std::string> out;
        for (const auto& issue : e.issues())
            out.push_back(issue.format());
        return out;
    }
    ADD_FAILURE() << "the deck was accepted";
    return {};
}

/// The one formatted issue of reading `text` (a test failure if there are more or none).
inline std::string issue_of(const std::string& text, const std::vector<std::string>& sets = {})
{
    const auto issues = issues_of(text, sets);
    EXPECT_EQ(issues.size(), 1u) << ::testing::PrintToString(issues);
    return issues.empty() ? std::string() : issues.front();
}

}  // namespace iga::io::test
