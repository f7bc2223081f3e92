#include "analysis/term.hpp"

namespace iga::analysis {

Matrix local_displacement(const Vector& u_full, const std::vector<int>& dofs, int d)
{
    const int n = static_cast<int>(dofs.size()) / d;
    Matrix u(n, d);
    for (int a = 0; a < n; ++a)
        for (int i = 0; i < d; ++i)
            u(a, i) = u_full(dofs[static_cast<std::size_t>(a * d + i)]);
    return u;
}

}  // namespace iga::analysis
