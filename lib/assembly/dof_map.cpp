#include "assembly/dof_map.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace iga::assembly {

DofMap::DofMap(int dimension, std::vector<int> nodes_per_body, const std::vector<PrescribedDof>& constraints)
    : dimension_(dimension)
{
    IGA_CHECK(dimension >= 1 && dimension <= 3, "DofMap: dimension must be 1, 2 or 3");
    node_offsets_.assign(1, 0);
    for (int n : nodes_per_body) {
        IGA_CHECK(n >= 0, "DofMap: negative node count for a body");
        node_offsets_.push_back(node_offsets_.back() + n);
    }
    const int n_full_dofs = n_full();
    prescribed_.assign(n_full_dofs, 0.0);
    amplitudes_.assign(1, Amplitude());  // index 0: the default ramp
    amplitude_of_.assign(n_full_dofs, 0);
    std::vector<char> constrained(n_full_dofs, 0);
    for (const PrescribedDof& c : constraints) {
        IGA_CHECK(c.dof >= 0 && c.dof < n_full_dofs,
                  "DofMap: constrained dof " + std::to_string(c.dof) + " out of range [0, " +
                      std::to_string(n_full_dofs) + ")");
        IGA_CHECK(std::isfinite(c.value), "DofMap: prescribed value of dof " + std::to_string(c.dof) +
                                              " is not finite");
        IGA_CHECK(!constrained[c.dof] || prescribed_[c.dof] == c.value,
                  "DofMap: dof " + std::to_string(c.dof) + " is prescribed twice with different values");
        const auto known = std::find(amplitudes_.begin(), amplitudes_.end(), c.amplitude);
        const int amplitude = static_cast<int>(known - amplitudes_.begin());
        if (known == amplitudes_.end())
            amplitudes_.push_back(c.amplitude);
        // A zero value is zero under any amplitude.
        IGA_CHECK(!constrained[c.dof] || c.value == 0.0 || amplitude_of_[c.dof] == amplitude,
                  "DofMap: dof " + std::to_string(c.dof) + " is prescribed twice with different amplitudes");
        constrained[c.dof] = 1;
        prescribed_[c.dof] = c.value;
        amplitude_of_[c.dof] = amplitude;
    }
    free_of_full_.assign(n_full_dofs, -1);
    for (int i = 0; i < n_full_dofs; ++i) {
        if (!constrained[i]) {
            free_of_full_[i] = static_cast<int>(full_of_free_.size());
            full_of_free_.push_back(i);
        }
    }
}

Vector DofMap::expand(const Vector& u_free, double t) const
{
    IGA_CHECK(u_free.size() == n_free(), "DofMap::expand: vector size differs from n_free");
    std::vector<double> a(amplitudes_.size());
    for (std::size_t k = 0; k < a.size(); ++k)
        a[k] = amplitudes_[k](t);
    Vector full(n_full());
    for (int i = 0; i < n_full(); ++i) {
        const int f = free_of_full_[i];
        full(i) = f >= 0 ? u_free(f) : a[static_cast<std::size_t>(amplitude_of_[i])] * prescribed_[i];
    }
    return full;
}

Vector DofMap::restrict(const Vector& full) const
{
    IGA_CHECK(full.size() == n_full(), "DofMap::restrict: vector size differs from n_full");
    Vector free(n_free());
    for (int f = 0; f < n_free(); ++f)
        free(f) = full(full_of_free_[f]);
    return free;
}

}  // namespace iga::assembly
