#pragma once
// The closed sets of modelling choices that a deck names and the modules act on,
// defined once: io/deck_names.hpp spells them for the deck, mechanics and contact use
// them as they are (no translation between a deck enum and a domain enum).

namespace iga {

/// Small strain (K0 assembled once) or finite strain (total Lagrangian).
enum class Kinematics { small, finite };
/// The material models of mechanics/material.hpp.
enum class MaterialModel { linear_elastic, saint_venant_kirchhoff, neo_hookean };
/// 2D: plane strain or plane stress; `none` in 3D (the deck names only the first two).
enum class PlaneMode { strain, stress, none };
/// Contact: both sides carry Gauss points (each half pass its own rows), or the first
/// side alone with slave and master rows (contact/contact_pair.hpp).
enum class Formulation { two_half_pass, single_pass };
/// The linear-solver backends a deck can choose (`solver.backend`; solver/backends.hpp
/// says what each can do).
enum class SolverBackend { suitesparse, petsc };
/// Direct factorization or a preconditioned Krylov method (`solver.type`).
enum class SolverType { direct, iterative };

}  // namespace iga
