#pragma once
// DofMap: numbering of the degrees of freedom of all deformable bodies.
//
// Nodes are control points, numbered consecutively body by body (body b owns
// nodes node_offset(b) .. node_offset(b) + n_nodes(b) - 1). "Full" numbering:
// dof(node, component) = node * d + component, component in [0, d). Constrained
// dofs carry a prescribed full value and an amplitude (core/amplitude.hpp): at
// pseudo-time t the dof is held at a(t) * value (the default ramp: the load
// factor times the value); the free dofs are numbered 0 .. n_free - 1 in
// increasing full order. The nonlinear solver works on free vectors (n_free); residual terms
// are evaluated on full vectors (n_full = n_nodes * d) from expand().
// Immutable after construction.

#include "core/amplitude.hpp"
#include "core/types.hpp"

#include <vector>

namespace iga::assembly {

/// A prescribed dof: full index, full value and the amplitude that scales it.
struct PrescribedDof {
    int dof = 0;
    double value = 0;
    Amplitude amplitude{};
};

class DofMap {
public:
    /// nodes_per_body: control points of each deformable body, in body order.
    /// A dof listed twice must carry the same value both times, and the same
    /// amplitude unless the value is 0 (else iga::Error).
    DofMap(int dimension, std::vector<int> nodes_per_body, const std::vector<PrescribedDof>& constraints);

    int dimension() const { return dimension_; }
    int n_bodies() const { return static_cast<int>(node_offsets_.size()) - 1; }
    int n_nodes() const { return node_offsets_.back(); }
    int n_nodes(int body) const { return node_offsets_[body + 1] - node_offsets_[body]; }
    int node_offset(int body) const { return node_offsets_[body]; }
    int n_full() const { return n_nodes() * dimension_; }
    int n_free() const { return static_cast<int>(full_of_free_.size()); }
    int n_constrained() const { return n_full() - n_free(); }

    int dof(int node, int component) const { return node * dimension_ + component; }
    bool is_constrained(int full_dof) const { return free_of_full_[full_dof] < 0; }
    /// Free index of a full dof, -1 if constrained.
    int free_index(int full_dof) const { return free_of_full_[full_dof]; }
    int full_index(int free_dof) const { return full_of_free_[free_dof]; }
    /// Prescribed full value (0 for a free dof).
    double prescribed(int full_dof) const { return prescribed_[full_dof]; }

    /// Full vector: free entries from u_free, constrained ones = a(t) * value.
    Vector expand(const Vector& u_free, double t) const;
    /// The free part of a full vector.
    Vector restrict(const Vector& full) const;

    /// n_full entries: free index or -1 (the table the assembler scatters with).
    const std::vector<int>& free_of_full() const { return free_of_full_; }

private:
    int dimension_;
    std::vector<int> node_offsets_;   // n_bodies + 1, prefix sums of nodes_per_body
    std::vector<int> free_of_full_;   // n_full
    std::vector<int> full_of_free_;   // n_free
    std::vector<double> prescribed_;  // n_full
    std::vector<Amplitude> amplitudes_;  // the distinct amplitudes of the prescribed dofs
    std::vector<int> amplitude_of_;      // n_full: index into amplitudes_ (0 for a free dof)
};

}  // namespace iga::assembly
