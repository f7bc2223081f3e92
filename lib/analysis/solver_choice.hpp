#pragma once
// The linear solver a run gets (solver/linear.hpp): the deck's `solver:` section
// (backend, type, options) and what the scene says of its tangents (symmetric,
// semi-definite, changing in a few rows per iteration), in one place.
//
// On several MPI ranks the backend is petsc whatever the deck says: the embedded
// SuiteSparse path runs on one process (docs/deck.md, "Linear solver").

#include "analysis/scene.hpp"
#include "core/parallel.hpp"
#include "io/deck.hpp"
#include "solver/linear.hpp"
#include "solver/newton.hpp"

namespace iga::analysis {

solver::LinearSolverPolicy linear_solver_policy(const Scene& scene,
                                                const solver::NonlinearSystem& system, const Communicator& comm);

/// The rigid-body modes of every deformable body on the free dofs (n_free x 3 in
/// 2D, x 6 in 3D; translations, then rotations about the model's centroid): the
/// near-null space of elasticity that algebraic multigrid needs to coarsen it well.
Matrix rigid_body_modes(const Scene& scene);

/// d when the free dofs come in blocks of the d components of one control point
/// (no node partly constrained), else 1 (solver::LinearSolverPolicy::block_size).
int point_block_size(const Scene& scene);

}  // namespace iga::analysis
