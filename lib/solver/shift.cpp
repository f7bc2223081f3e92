#include "solver/shift.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>

namespace iga::solver {

Vector shift_scale(const Vector& diagonal)
{
    Vector D = diagonal.cwiseAbs();
    double sum = 0;
    Index n_nonzero = 0;
    for (Index i = 0; i < D.size(); ++i)
        if (D(i) > 0) {
            sum += D(i);
            ++n_nonzero;
        }
    const double fill = n_nonzero > 0 ? sum / static_cast<double>(n_nonzero) : 1.0;
    for (Index i = 0; i < D.size(); ++i)
        if (!(D(i) > 0))
            D(i) = fill;
    return D;
}

bool complete_diagonal(SparseMatrix& A, std::vector<int>& diagonal_position)
{
    A.makeCompressed();
    const int n = static_cast<int>(A.rows());
    auto find_diagonal = [&]() {
        diagonal_position.assign(n, -1);
        for (int j = 0; j < n; ++j) {
            const int* first = A.innerIndexPtr() + A.outerIndexPtr()[j];
            const int* last = A.innerIndexPtr() + A.outerIndexPtr()[j + 1];
            const int* it = std::lower_bound(first, last, j);
            if (it != last && *it == j)
                diagonal_position[j] = static_cast<int>(it - A.innerIndexPtr());
        }
        return std::find(diagonal_position.begin(), diagonal_position.end(), -1) == diagonal_position.end();
    };
    if (find_diagonal())
        return false;  // the usual case: a stiffness couples every dof with itself
    SparseMatrix zero_diagonal(n, n);
    std::vector<Triplet> entries;
    entries.reserve(n);
    for (int j = 0; j < n; ++j)
        entries.emplace_back(j, j, 0.0);
    zero_diagonal.setFromTriplets(entries.begin(), entries.end());
    SparseMatrix sum = A + zero_diagonal;  // the union pattern, zeros included
    A.swap(sum);
    A.makeCompressed();
    const bool complete = find_diagonal();
    IGA_CHECK(complete, "complete_diagonal: diagonal entries missing after adding them");
    return true;
}

}  // namespace iga::solver
