#pragma once
// Open knot vectors and the univariate B-spline basis on them.
//
// Notation follows Piegl & Tiller, "The NURBS Book", 2nd ed.: degree p,
// basis functions N_0..N_n, knots u_0..u_m with m = n + p + 1.
//
// Invariants, checked on construction (throws iga::Error): p >= 1; knots
// non-decreasing and finite; open (first and last knot repeated p+1 times);
// no interior multiplicity above p; at least one span of positive length.
// A span ("element") is [u_i, u_{i+1}) with u_i < u_{i+1}; the last span is
// closed on the right so that u = back() belongs to it.

#include <Eigen/Core>
#include <span>
#include <vector>

namespace iga::nurbs {

class KnotVector {
public:
    KnotVector(int degree, std::vector<double> knots);

    int degree() const { return degree_; }
    int n_basis() const { return static_cast<int>(knots_.size()) - degree_ - 1; }  ///< n + 1 = m - p
    int n_spans() const { return static_cast<int>(span_starts_.size()); }          ///< spans of positive length
    double front() const { return knots_[degree_]; }                                ///< start of the domain
    double back() const { return knots_[knots_.size() - degree_ - 1]; }             ///< end of the domain

    /// Knot index i with u in [u_i, u_{i+1}) (A2.1); u is clamped to [front, back].
    /// NaN gives the first span, so the basis evaluated there is NaN (a visible numerical failure).
    int find_span(double u) const;
    /// Knot index i of the k-th span of positive length, k in [0, n_spans()).
    int span_start(int k) const { return span_starts_[k]; }
    /// Position k of knot span i (inverse of span_start).
    int span_number(int knot_index) const;
    /// Distinct knot values front() = b_0 < b_1 < ... < b_{n_spans} = back().
    std::vector<double> breakpoints() const;
    /// Multiplicity of the value u among the knots (0 if absent).
    int multiplicity(double u) const;

    std::span<const double> knots() const { return knots_; }
    const std::vector<double>& knot_values() const { return knots_; }

private:
    int degree_;
    std::vector<double> knots_;
    std::vector<int> span_starts_;
};

/// Values and derivatives up to order n_derivs of the p+1 basis functions that
/// are non-zero on knot span `span`, at parameter u (A2.3).
/// Returns a (n_derivs+1) x (p+1) matrix: entry (k, j) is the k-th derivative of
/// N_{span-p+j}(u). Derivatives above p are zero.
Eigen::MatrixXd basis_derivatives(const KnotVector& knots, int span, double u, int n_derivs);

/// Same as basis_derivatives, writing into `ders` (resized; no allocation once it
/// has the size): the out-parameter form for hot loops.
void basis_derivatives_into(const KnotVector& knots, int span, double u, int n_derivs, Eigen::MatrixXd& ders);

}  // namespace iga::nurbs
