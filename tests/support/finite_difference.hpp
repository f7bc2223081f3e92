#pragma once
// Central finite-difference Jacobian of a vector function, for tangent checks.
//
// J_ij ~ (f_i(x + h e_j) - f_i(x - h e_j)) / (2h): truncation error O(h^2 |f'''|),
// round-off O(eps |f| / h). Callers choose h and state the resulting tolerance.

#include <Eigen/Dense>
#include <functional>

namespace iga::test {

inline Eigen::MatrixXd central_difference_jacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x, double h)
{
    const Eigen::VectorXd f0 = f(x);
    Eigen::MatrixXd J(f0.size(), x.size());
    for (Eigen::Index j = 0; j < x.size(); ++j) {
        Eigen::VectorXd xp = x, xm = x;
        xp(j) += h;
        xm(j) -= h;
        J.col(j) = (f(xp) - f(xm)) / (2.0 * h);
    }
    return J;
}

}  // namespace iga::test
