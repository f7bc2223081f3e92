#include "nurbs/knot_vector.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace iga::nurbs {

namespace {

std::string describe(int degree, const std::vector<double>& knots)
{
    std::ostringstream out;
    out.precision(17);
    out << "knot vector of degree " << degree << " {";
    for (std::size_t i = 0; i < knots.size(); ++i)
        out << (i ? ", " : "") << knots[i];
    out << "}";
    return out.str();
}

[[noreturn]] void reject(int degree, const std::vector<double>& knots, const std::string& reason)
{
    throw Error("invalid " + describe(degree, knots) + ": " + reason);
}

}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots) : degree_(degree), knots_(std::move(knots))
{
    const int p = degree_;
    if (p < 1)
        reject(p, knots_, "degree must be >= 1");
    const int n_knots = static_cast<int>(knots_.size());
    if (n_knots < 2 * (p + 1))
        reject(p, knots_, "needs at least 2(p+1) = " + std::to_string(2 * (p + 1)) + " knots");
    for (int i = 0; i < n_knots; ++i)
        if (!std::isfinite(knots_[i]))
            reject(p, knots_, "knot " + std::to_string(i) + " is not finite");
    for (int i = 1; i < n_knots; ++i)
        if (knots_[i] < knots_[i - 1])
            reject(p, knots_, "knots must be non-decreasing (knot " + std::to_string(i) + " < knot " +
                                  std::to_string(i - 1) + ")");
    // Open: the end values repeat exactly p+1 times (more would make an end basis function vanish).
    const double first = knots_.front();
    const double last = knots_.back();
    if (!(first < last))
        reject(p, knots_, "needs at least one span of positive length");
    if (knots_[p] != first || knots_[p + 1] == first)
        reject(p, knots_, "must be open: the first knot must repeat exactly p+1 times");
    if (knots_[n_knots - 1 - p] != last || knots_[n_knots - 2 - p] == last)
        reject(p, knots_, "must be open: the last knot must repeat exactly p+1 times");
    for (int i = p + 1; i < n_knots - p - 1;) {
        int j = i;
        while (j + 1 < n_knots && knots_[j + 1] == knots_[i])
            ++j;
        const int multiplicity = j - i + 1;
        if (multiplicity > p) {
            std::ostringstream value;
            value.precision(17);
            value << knots_[i];
            reject(p, knots_,
                   "interior knot " + value.str() + " has multiplicity " + std::to_string(multiplicity) +
                       " > degree " + std::to_string(p));
        }
        i = j + 1;
    }
    for (int i = p; i < n_knots - p - 1; ++i)
        if (knots_[i] < knots_[i + 1])
            span_starts_.push_back(i);
}

int KnotVector::find_span(double u) const
{
    // A2.1 by bisection (std::upper_bound). Written so that NaN lands in the
    // first span: the basis is then NaN and the caller's residual shows it.
    if (!(u > front()))
        return span_starts_.front();
    if (u >= back())
        return span_starts_.back();
    const auto it = std::upper_bound(knots_.begin() + degree_, knots_.end() - degree_ - 1, u);
    return static_cast<int>(it - knots_.begin()) - 1;
}

int KnotVector::span_number(int knot_index) const
{
    const auto it = std::lower_bound(span_starts_.begin(), span_starts_.end(), knot_index);
    IGA_CHECK(it != span_starts_.end() && *it == knot_index,
              "knot index " + std::to_string(knot_index) + " does not start a span of positive length");
    return static_cast<int>(it - span_starts_.begin());
}

std::vector<double> KnotVector::breakpoints() const
{
    std::vector<double> out;
    out.reserve(span_starts_.size() + 1);
    out.push_back(front());
    for (const int i : span_starts_)
        out.push_back(knots_[i + 1]);
    return out;
}

int KnotVector::multiplicity(double u) const
{
    return static_cast<int>(std::count(knots_.begin(), knots_.end(), u));
}

namespace {

// A2.3 (Piegl & Tiller p. 72): ndu holds the basis functions (upper triangle)
// and the knot differences (lower triangle); a holds two rows of coefficients.
// Templated on the work arrays so that common degrees use stack storage.
template <class Square, class TwoRows, class Buffer>
void ders_basis_funs(const KnotVector& knots, int span, double u, int n_derivs, Eigen::MatrixXd& ders)
{
    const int p = knots.degree();
    const double* U = knots.knot_values().data();
    Buffer left(p + 1), right(p + 1);
    Square ndu(p + 1, p + 1);
    ndu(0, 0) = 1.0;
    for (int j = 1; j <= p; ++j) {
        left(j) = u - U[span + 1 - j];
        right(j) = U[span + j] - u;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            ndu(j, r) = right(r + 1) + left(j - r);
            const double temp = ndu(r, j - 1) / ndu(j, r);
            ndu(r, j) = saved + right(r + 1) * temp;
            saved = left(j - r) * temp;
        }
        ndu(j, j) = saved;
    }

    ders.setZero(n_derivs + 1, p + 1);
    for (int j = 0; j <= p; ++j)
        ders(0, j) = ndu(j, p);
    const int top = std::min(n_derivs, p);
    if (top < 1)
        return;

    TwoRows a(2, p + 1);
    for (int r = 0; r <= p; ++r) {
        int s1 = 0, s2 = 1;
        a(0, 0) = 1.0;
        for (int k = 1; k <= top; ++k) {
            double d = 0.0;
            const int rk = r - k;
            const int pk = p - k;
            if (r >= k) {
                a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
                d = a(s2, 0) * ndu(rk, pk);
            }
            const int j1 = rk >= -1 ? 1 : -rk;
            const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
            for (int j = j1; j <= j2; ++j) {
                a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
                d += a(s2, j) * ndu(rk + j, pk);
            }
            if (r <= pk) {
                a(s2, k) = -a(s1, k - 1) / ndu(pk + 1, r);
                d += a(s2, k) * ndu(r, pk);
            }
            ders(k, r) = d;
            std::swap(s1, s2);
        }
    }
    double factor = p;
    for (int k = 1; k <= top; ++k) {
        ders.row(k) *= factor;
        factor *= (p - k);
    }
}

constexpr int max_stack_degree = 9;  // degrees above this use heap work arrays
constexpr int stack_size = max_stack_degree + 1;

}  // namespace

void basis_derivatives_into(const KnotVector& knots, int span, double u, int n_derivs, Eigen::MatrixXd& ders)
{
    IGA_ASSERT(span >= knots.degree() && span < knots.n_basis(), "span index out of range");
    IGA_ASSERT(n_derivs >= 0, "negative derivative order");
    if (knots.degree() <= max_stack_degree) {
        using Square = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, stack_size, stack_size>;
        using TwoRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, stack_size>;
        using Buffer = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, stack_size, 1>;
        ders_basis_funs<Square, TwoRows, Buffer>(knots, span, u, n_derivs, ders);
    } else {
        ders_basis_funs<Eigen::MatrixXd, Eigen::MatrixXd, Eigen::VectorXd>(knots, span, u, n_derivs, ders);
    }
}

Eigen::MatrixXd basis_derivatives(const KnotVector& knots, int span, double u, int n_derivs)
{
    Eigen::MatrixXd ders;
    basis_derivatives_into(knots, span, u, n_derivs, ders);
    return ders;
}

}  // namespace iga::nurbs
