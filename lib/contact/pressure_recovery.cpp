#include "contact/pressure_recovery.hpp"

#include "core/error.hpp"

namespace iga::contact {

Vector control_point_pressure(const nurbs::Patch& side, const std::vector<double>& eta, const Vector& pressure,
                              const Vector& weight)
{
    IGA_CHECK(side.n_par() == 1, "contact: pressure recovery needs a curve side (n_par = 1)");
    const Index n_g = static_cast<Index>(eta.size());
    IGA_CHECK(pressure.size() == n_g && weight.size() == n_g,
              "contact: pressure recovery needs one pressure and one weight per Gauss point");
    Vector numerator = Vector::Zero(side.n_control_points());
    Vector denominator = Vector::Zero(side.n_control_points());
    for (Index g = 0; g < n_g; ++g) {
        VecN xi(1);
        xi(0) = eta[g];
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

    const std::vector<double> breaks = side_reference.knots(0).breakpoints();
    const Index n_spans = static_cast<Index>(breaks.size()) - 1;
    const Index n_s = n_spans * samples_per_span + 1;
    const int d = side_reference.dim();
    const RowMatrix current = side_reference.control_points() + side_displacement;
    out.parameter.resize(n_s);
    out.coordinates.resize(n_s, d);
    out.reference_coordinates.resize(n_s, d);
    out.pressure.resize(n_s);
    for (Index k = 0; k < n_spans; ++k)
        for (int j = 0; j < samples_per_span; ++j)
            out.parameter(k * samples_per_span + j) =
                breaks[k] + (breaks[k + 1] - breaks[k]) * static_cast<double>(j) / samples_per_span;
    out.parameter(n_s - 1) = breaks.back();
    for (Index s = 0; s < n_s; ++s) {
        VecN xi(1);
        xi(0) = out.parameter(s);
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
