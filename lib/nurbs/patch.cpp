#include "nurbs/patch.hpp"

#include "core/error.hpp"

#include <cmath>
#include <string>

namespace iga::nurbs {

namespace {

/// Column of the pair (k, l), k <= l, in the second-derivative order uu, uv, uw, vv, vw, ww.
}  // namespace

Patch::Patch(std::vector<KnotVector> knots, RowMatrix control_points, Vector weights)
    : knots_(std::move(knots)), control_points_(std::move(control_points)), weights_(std::move(weights))
{
    const int n = n_par();
    if (n < 1 || n > 3)
        throw Error("patch: number of parametric directions must be 1, 2 or 3, got " + std::to_string(n));
    if (dim() < 1 || dim() > 3)
        throw Error("patch: spatial dimension must be 1, 2 or 3, got " + std::to_string(dim()));
    int expected = 1;
    for (const auto& kv : knots_)
        expected *= kv.n_basis();
    if (control_points_.rows() != expected)
        throw Error("patch: " + std::to_string(control_points_.rows()) +
                    " control points, but the knot vectors define " + std::to_string(expected));
    if (weights_.size() != expected)
        throw Error("patch: " + std::to_string(weights_.size()) + " weights for " + std::to_string(expected) +
                    " control points");
    for (Index a = 0; a < weights_.size(); ++a)
        if (!(std::isfinite(weights_(a)) && weights_(a) > 0))
            throw Error("patch: weight " + std::to_string(a) + " = " + std::to_string(weights_(a)) +
                        " must be finite and > 0");
}

int Patch::control_point_index(const std::array<int, 3>& ijk) const
{
    int index = 0;
    int stride = 1;
    for (int d = 0; d < n_par(); ++d) {
        IGA_ASSERT(ijk[d] >= 0 && ijk[d] < n_basis(d), "control point index out of range");
        index += ijk[d] * stride;
        stride *= n_basis(d);
    }
    return index;
}

std::array<int, 3> Patch::control_point_ijk(int index) const
{
    IGA_ASSERT(index >= 0 && index < n_control_points(), "control point index out of range");
    std::array<int, 3> ijk{0, 0, 0};
    for (int d = 0; d < n_par(); ++d) {
        ijk[d] = index % n_basis(d);
        index /= n_basis(d);
    }
    return ijk;
}

std::vector<Element> Patch::elements() const
{
    const int n = n_par();
    std::array<int, 3> n_spans{1, 1, 1};
    for (int d = 0; d < n; ++d)
        n_spans[d] = knots_[d].n_spans();
    std::vector<Element> out;
    out.reserve(static_cast<std::size_t>(n_spans[0]) * n_spans[1] * n_spans[2]);
    for (int k = 0; k < n_spans[2]; ++k)
        for (int j = 0; j < n_spans[1]; ++j)
            for (int i = 0; i < n_spans[0]; ++i) {
                const std::array<int, 3> number{i, j, k};
                Element e;
                for (int d = 0; d < n; ++d) {
                    const KnotVector& kv = knots_[d];
                    e.span[d] = kv.span_start(number[d]);
                    e.lower[d] = kv.knot_values()[e.span[d]];
                    e.upper[d] = kv.knot_values()[e.span[d] + 1];
                }
                out.push_back(e);
            }
    return out;
}

Patch Patch::with_control_points(RowMatrix points) const
{
    IGA_CHECK(points.rows() == control_points_.rows() && points.cols() == control_points_.cols(),
              "with_control_points: expected " + std::to_string(control_points_.rows()) + " x " +
                  std::to_string(control_points_.cols()) + " points");
    Patch out = *this;
    out.control_points_ = std::move(points);
    return out;
}

BasisValues rational_basis(const Patch& patch, const VecN& xi, int n_derivs)
{
    IGA_CHECK(xi.size() == patch.n_par(), "rational_basis: xi must have n_par entries");
    std::array<int, 3> span{0, 0, 0};
    for (int d = 0; d < patch.n_par(); ++d)
        span[d] = patch.knots(d).find_span(xi(d));
    return rational_basis(patch, span, xi, n_derivs);
}

BasisValues rational_basis(const Patch& patch, const std::array<int, 3>& span, const VecN& xi, int n_derivs)
{
    const int n = patch.n_par();
    IGA_CHECK(xi.size() == n, "rational_basis: xi must have n_par entries");
    IGA_CHECK(n_derivs >= 0 && n_derivs <= 2, "rational_basis: n_derivs must be 0, 1 or 2");

    // Univariate values and derivatives per direction; unused directions are
    // the constant 1 so that the tensor loops below need no special cases.
    std::array<Eigen::MatrixXd, 3> ders;
    std::array<int, 3> n_local_dir{1, 1, 1};
    for (int d = 0; d < 3; ++d) {
        if (d < n) {
            basis_derivatives_into(patch.knots(d), span[d], xi(d), n_derivs, ders[d]);
            n_local_dir[d] = patch.degree(d) + 1;
        } else {
            ders[d].setZero(n_derivs + 1, 1);
            ders[d](0, 0) = 1.0;
        }
    }
    const int n_local = n_local_dir[0] * n_local_dir[1] * n_local_dir[2];
    const int n_second = n * (n + 1) / 2;

    BasisValues out;
    out.indices.resize(n_local);
    out.R.resize(n_local);
    if (n_derivs >= 1)
        out.dR.resize(n_local, n);
    if (n_derivs >= 2)
        out.d2R.resize(n_local, n_second);

    // Weighted products w_a N_a and their derivatives (the numerators), and the
    // sums W, dW, d2W (the denominator of the rational basis).
    const Vector& weights = patch.weights();
    double W = 0.0;
    std::array<double, 3> dW{0, 0, 0};
    std::array<double, 6> d2W{0, 0, 0, 0, 0, 0};
    std::array<int, 3> first{0, 0, 0};
    for (int d = 0; d < n; ++d)
        first[d] = span[d] - patch.degree(d);

    int a = 0;
    for (int k = 0; k < n_local_dir[2]; ++k)
        for (int j = 0; j < n_local_dir[1]; ++j)
            for (int i = 0; i < n_local_dir[0]; ++i, ++a) {
                const std::array<int, 3> local{i, j, k};
                const int global = patch.control_point_index({first[0] + i, first[1] + j, first[2] + k});
                out.indices[a] = global;
                const double w = weights(global);
                // value(d, order): order-th derivative of the 1D factor in direction d
                auto value = [&](int d, int order) { return ders[d](order, local[d]); };
                const double N = value(0, 0) * value(1, 0) * value(2, 0);
                out.R(a) = w * N;
                W += w * N;
                if (n_derivs >= 1) {
                    for (int p = 0; p < n; ++p) {
                        double dN = 1.0;
                        for (int d = 0; d < 3; ++d)
                            dN *= value(d, d == p ? 1 : 0);
                        out.dR(a, p) = w * dN;
                        dW[p] += w * dN;
                    }
                }
                if (n_derivs >= 2) {
                    for (int p = 0; p < n; ++p)
                        for (int q = p; q < n; ++q) {
                            double d2N = 1.0;
                            for (int d = 0; d < 3; ++d)
                                d2N *= value(d, (d == p ? 1 : 0) + (d == q ? 1 : 0));
                            const int c = second_column(n, p, q);
                            out.d2R(a, c) = w * d2N;
                            d2W[c] += w * d2N;
                        }
                }
            }

    // Quotient rule (A4.2 generalized to the tensor product): from R W = w N,
    //   dR_p = (w N_p - R W_p) / W,
    //   d2R_pq = (w N_pq - dR_p W_q - dR_q W_p - R W_pq) / W.
    const double inv_W = 1.0 / W;
    out.R *= inv_W;
    if (n_derivs >= 1)
        for (int p = 0; p < n; ++p)
            out.dR.col(p) = (out.dR.col(p) - out.R * dW[p]) * inv_W;
    if (n_derivs >= 2)
        for (int p = 0; p < n; ++p)
            for (int q = p; q < n; ++q) {
                const int c = second_column(n, p, q);
                out.d2R.col(c) =
                    (out.d2R.col(c) - out.dR.col(p) * dW[q] - out.dR.col(q) * dW[p] - out.R * d2W[c]) * inv_W;
            }
    return out;
}

PointDerivatives combine(const BasisValues& basis, const RowMatrix& points)
{
    const int d = static_cast<int>(points.cols());
    const int n_local = static_cast<int>(basis.indices.size());
    PointDerivatives out;
    out.x = VecN::Zero(d);
    if (basis.dR.size() > 0)
        out.dx = Matrix::Zero(d, basis.dR.cols());
    if (basis.d2R.size() > 0)
        out.d2x = Matrix::Zero(d, basis.d2R.cols());
    for (int a = 0; a < n_local; ++a) {
        const auto P = points.row(basis.indices[a]).transpose();
        out.x += basis.R(a) * P;
        if (basis.dR.size() > 0)
            out.dx += P * basis.dR.row(a);
        if (basis.d2R.size() > 0)
            out.d2x += P * basis.d2R.row(a);
    }
    return out;
}

PointDerivatives evaluate(const Patch& patch, const VecN& xi, int n_derivs)
{
    return combine(rational_basis(patch, xi, n_derivs), patch.control_points());
}

}  // namespace iga::nurbs
