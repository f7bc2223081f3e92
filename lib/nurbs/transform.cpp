#include "nurbs/transform.hpp"

#include "core/error.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace iga::nurbs {

namespace {

void check_vector(const VecN& v, Index n, const char* what)
{
    IGA_CHECK(v.size() == n, std::string(what) + " must have " + std::to_string(n) + " entries");
    IGA_CHECK(v.allFinite(), std::string(what) + " must be finite");
}

/// v / |v|; the reader has refused zero vectors. Scaled by its largest entry first,
/// so that |v| neither overflows ([0, 0, 1e300]) nor underflows ([0, 0, 5e-324]):
/// any finite non-zero vector has a direction.
VecN unit(const VecN& v, const char* what)
{
    const double largest = v.cwiseAbs().maxCoeff();
    IGA_CHECK(largest > 0 && std::isfinite(largest), std::string(what) + " must be finite and non-zero");
    const VecN scaled = v / largest;  // largest entry +-1: its norm lies in [1, sqrt(3)]
    return scaled / scaled.norm();
}

}  // namespace

Affine Affine::then(const Affine& next) const
{
    IGA_CHECK(next.dim() == dim(), "composing affine maps of different dimensions");
    return Affine{next.A * A, next.A * b + next.b};
}

Affine identity(int dim)
{
    IGA_CHECK(dim >= 1 && dim <= 3, "an affine map needs 1 to 3 dimensions");
    return Affine{MatN::Identity(dim, dim), VecN::Zero(dim)};
}

Affine translation(const VecN& offset)
{
    check_vector(offset, offset.size(), "translate");
    Affine map = identity(static_cast<int>(offset.size()));
    map.b = offset;
    return map;
}

std::pair<double, double> cos_sin_deg(double angle_deg)
{
    IGA_CHECK(std::isfinite(angle_deg), "the angle must be finite");
    // angle = 90 q + r with |r| <= 45, exactly (std::remainder is exact); then
    // rotate (cos r, sin r) by q quarter turns, which only swaps and negates.
    const double r = std::remainder(angle_deg, 90.0);
    const long q = std::lround((angle_deg - r) / 90.0);
    const double radians = r * (std::numbers::pi / 180.0);
    double c = r == 0.0 ? 1.0 : std::cos(radians);
    double s = r == 0.0 ? 0.0 : std::sin(radians);
    for (long k = 0; k < ((q % 4) + 4) % 4; ++k) {
        const double c_old = c;
        c = -s;
        s = c_old;
    }
    return {c, s};
}

Affine rotation(const VecN& axis, double angle_deg, const VecN& about)
{
    check_vector(axis, 3, "rotation axis");
    check_vector(about, 3, "rotation centre");
    const VecN k = unit(axis, "rotation axis");
    const auto [c, s] = cos_sin_deg(angle_deg);
    // Rodrigues: R = c I + s [k]x + (1 - c) k k^T.
    MatN K(3, 3);
    K << 0, -k(2), k(1), k(2), 0, -k(0), -k(1), k(0), 0;
    const MatN R = c * MatN::Identity(3, 3) + s * K + (1 - c) * (k * k.transpose());
    // About a point p: x -> R (x - p) + p.
    return Affine{R, about - R * about};
}

Affine rotation_2d(double angle_deg, const VecN& about)
{
    check_vector(about, 2, "rotation centre");
    const auto [c, s] = cos_sin_deg(angle_deg);
    MatN R(2, 2);
    R << c, -s, s, c;
    return Affine{R, about - R * about};
}

Affine mirror(const VecN& normal, const VecN& point)
{
    check_vector(normal, normal.size(), "mirror normal");
    check_vector(point, normal.size(), "mirror point");
    const VecN n = unit(normal, "mirror normal");
    const int d = static_cast<int>(n.size());
    // x -> x - 2 ((x - p) . n) n = (I - 2 n n^T) x + 2 (p . n) n.
    return Affine{MatN::Identity(d, d) - 2 * (n * n.transpose()), 2 * point.dot(n) * n};
}

Affine scaling(double factor, int dim)
{
    IGA_CHECK(std::isfinite(factor) && factor > 0, "the scale factor must be finite and > 0");
    Affine map = identity(dim);
    map.A *= factor;
    return map;
}

Patch reverse_direction(const Patch& patch, int dir)
{
    IGA_CHECK(dir >= 0 && dir < patch.n_par(), "reverse_direction: no parametric direction " + std::to_string(dir));
    std::vector<KnotVector> knots = patch.all_knots();
    const KnotVector& old = patch.knots(dir);
    const double sum = old.front() + old.back();
    std::vector<double> values(old.knot_values().rbegin(), old.knot_values().rend());
    for (double& u : values)
        u = sum - u;
    knots[static_cast<std::size_t>(dir)] = KnotVector(old.degree(), std::move(values));
    RowMatrix points(patch.n_control_points(), patch.dim());
    Vector weights(patch.n_control_points());
    const int n = patch.n_basis(dir);
    for (int a = 0; a < patch.n_control_points(); ++a) {
        std::array<int, 3> ijk = patch.control_point_ijk(a);
        ijk[static_cast<std::size_t>(dir)] = n - 1 - ijk[static_cast<std::size_t>(dir)];
        const int b = patch.control_point_index(ijk);
        points.row(b) = patch.control_points().row(a);
        weights(b) = patch.weights()(a);
    }
    return Patch(std::move(knots), std::move(points), std::move(weights));
}

Patch transformed(const Patch& patch, const Affine& map)
{
    IGA_CHECK(map.dim() == patch.dim(), "transform: a " + std::to_string(map.dim()) + "D map for a patch in " +
                                            std::to_string(patch.dim()) + "D");
    // Rows are points: P A^T + 1 b^T.
    RowMatrix points = patch.control_points() * map.A.transpose();
    points.rowwise() += map.b.transpose();
    Patch out = patch.with_control_points(std::move(points));
    return map.reverses_orientation() ? reverse_direction(out, 0) : out;
}

}  // namespace iga::nurbs
