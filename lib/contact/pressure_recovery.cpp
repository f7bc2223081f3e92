#include "contact/pressure_recovery.hpp"

#include "core/error.hpp"

namespace iga::contact {

Vector control_point_pressure(const nurbs::Patch& side, const std::vector<double>& eta, const Vector& pressure,
                              const Vector& weight)
{
    RowMatrix parameter(static_cast<Index>(eta.size()), 1);
    for (std::size_t g = 0; g < eta.size(); ++g)
        parameter(static_cast<Index>(g), 0) = eta[g];
    return control_point_pressure(side, parameter, pressure, weight);
}

Vector control_point_pressure(const nurbs::Patch& side, const RowMatrix& parameter, const Vector& pressure,
                              const Vector& weight)
{
    IGA_CHECK(side.n_par() == 1 || side.n_par() == 2, "contact: pressure recovery needs a curve or surface side");
    IGA_CHECK(parameter.cols() == side.n_par(), "contact: one parameter per side direction and Gauss point");
    const Index n_g = parameter.rows();
    IGA_CHECK(pressure.size() == n_g && weight.size() == n_g,
              "contact: pressure recovery needs one pressure and one weight per Gauss point");
    Vector numerator = Vector::Zero(side.n_control_points());
    Vector denominator = Vector::Zero(side.n_control_points());
    for (Index g = 0; g < n_g; ++g) {
        const VecN xi = parameter.row(g).transpose();
        const nurbs::BasisValues basis = nurbs::rational_basis(side, xi, 0);
        for (std::size_t a = 0; a < basis.indices.size(); ++a) {
            const double rw = basis.R(static_cast<Index>(a)) * weight(g);
            numerator(basis.indices[a]) += rw * pressure(g);
            denominator(basis.indices[a]) += rw;
        }
    }
    Vector p_A = Vector::Zero(side.n_control_points());
    for (Index A = 0; A < p_A.size(); ++A)
        if (denominator(A) > 0.0)
            p_A(A) = numerator(A) / denominator(A);
    return p_A;
}

RecoveredPressure recover_pressure(const nurbs::Patch& side_reference, const RowMatrix& side_displacement,
                                   const CarrierResult& carrier, int samples_per_span)
{
    IGA_CHECK(samples_per_span >= 1, "contact: samples_per_span must be >= 1");
    IGA_CHECK(side_displacement.rows() == side_reference.n_control_points() &&
                  side_displacement.cols() == side_reference.dim(),
              "contact: side displacement must be n_cp x d");
    RecoveredPressure out;
    out.control_point_pressure = control_point_pressure(side_reference, carrier.parameter, carrier.pressure,
                                                        carrier.weight);
    out.normal_force = carrier.pressure.dot(carrier.weight);

    // Samples: in each direction every span divided into samples_per_span equal
    // intervals, span ends taken once; on a surface the tensor grid of both.
    const int q = side_reference.n_par();
    std::vector<std::vector<double>> axis(static_cast<std::size_t>(q));
    for (int dir = 0; dir < q; ++dir) {
        const std::vector<double> breaks = side_reference.knots(dir).breakpoints();
        const std::size_t n_spans = breaks.size() - 1;
        for (std::size_t k = 0; k < n_spans; ++k)
            for (int j = 0; j < samples_per_span; ++j)
                axis[dir].push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * static_cast<double>(j) / samples_per_span);
        axis[dir].push_back(breaks.back());
    }
    const Index n_u = static_cast<Index>(axis[0].size());
    const Index n_v = q == 2 ? static_cast<Index>(axis[1].size()) : 1;
    const Index n_s = n_u * n_v;
    out.grid = {n_u, n_v};
    const int d = side_reference.dim();
    const RowMatrix current = side_reference.control_points() + side_displacement;
    out.parameter.resize(n_s, q);
    out.coordinates.resize(n_s, d);
    out.reference_coordinates.resize(n_s, d);
    out.pressure.resize(n_s);
    for (Index j = 0; j < n_v; ++j)  // u runs fastest
        for (Index i = 0; i < n_u; ++i) {
            out.parameter(j * n_u + i, 0) = axis[0][static_cast<std::size_t>(i)];
            if (q == 2)
                out.parameter(j * n_u + i, 1) = axis[1][static_cast<std::size_t>(j)];
        }
    for (Index s = 0; s < n_s; ++s) {
        const VecN xi = out.parameter.row(s).transpose();
        const nurbs::BasisValues basis = nurbs::rational_basis(side_reference, xi, 0);
        VecN x = VecN::Zero(d), X = VecN::Zero(d);
        double p = 0.0;
        for (std::size_t a = 0; a < basis.indices.size(); ++a) {
            const double R = basis.R(static_cast<Index>(a));
            const int A = basis.indices[a];
            X += R * side_reference.control_points().row(A).transpose();
            x += R * current.row(A).transpose();
            p += R * out.control_point_pressure(A);
        }
        out.coordinates.row(s) = x.transpose();
        out.reference_coordinates.row(s) = X.transpose();
        out.pressure(s) = p;
    }
    return out;
}

}  // namespace iga::contact
