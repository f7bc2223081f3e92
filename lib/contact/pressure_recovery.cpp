#include "contact/pressure_recovery.hpp"

#include "core/error.hpp"

namespace iga::contact {

namespace {

/// Samples of p^h = sum_A R_A p_A on one side patch (see the header for the
/// sample set), written into out's parameter, grid, coordinates,
/// reference_coordinates and pressure. current: n_cp x d; p_A: n_cp.
void sample_pressure(const nurbs::Patch& side_reference, const RowMatrix& current, const Vector& p_A,
                     int samples_per_span, RecoveredPressure& out)
{
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
            p += R * p_A(A);
        }
        out.coordinates.row(s) = x.transpose();
        out.reference_coordinates.row(s) = X.transpose();
        out.pressure(s) = p;
    }
}

}  // namespace

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

    sample_pressure(side_reference, side_reference.control_points() + side_displacement, out.control_point_pressure,
                    samples_per_span, out);
    return out;
}

}  // namespace iga::contact

namespace iga::contact {

RecoveredPressure recover_pressure(const DeformableSide& surface, const RowMatrix& surface_displacement,
                                   const CarrierResult& carrier, int samples_per_span)
{
    if (surface.pieces.size() == 1) {
        const SidePiece& piece = surface.pieces.front();
        RowMatrix disp(static_cast<Index>(piece.surface_index.size()), surface_displacement.cols());
        for (std::size_t a = 0; a < piece.surface_index.size(); ++a)
            disp.row(static_cast<Index>(a)) = surface_displacement.row(piece.surface_index[a]);
        RecoveredPressure out = recover_pressure(piece.side.patch, disp, carrier, samples_per_span);
        Vector p_A = Vector::Zero(surface.n_control_points);
        for (std::size_t a = 0; a < piece.surface_index.size(); ++a)
            p_A(piece.surface_index[a]) = out.control_point_pressure(static_cast<Index>(a));
        out.control_point_pressure = std::move(p_A);
        return out;
    }
    IGA_CHECK(samples_per_span >= 1, "contact: samples_per_span must be >= 1");
    IGA_CHECK(surface_displacement.rows() == surface.n_control_points,
              "contact: surface displacement must be n_cp x d");
    IGA_CHECK(carrier.piece.size() == static_cast<std::size_t>(carrier.parameter.rows()),
              "contact: a multi-piece surface needs the piece of every Gauss point");
    // p_A over the whole surface: an interface control point collects the Gauss
    // points of both pieces, once.
    Vector numerator = Vector::Zero(surface.n_control_points);
    Vector denominator = Vector::Zero(surface.n_control_points);
    for (Index g = 0; g < carrier.parameter.rows(); ++g) {
        const SidePiece& piece = surface.pieces[static_cast<std::size_t>(carrier.piece[static_cast<std::size_t>(g)])];
        const nurbs::BasisValues basis = nurbs::rational_basis(piece.side.patch, VecN(carrier.parameter.row(g).transpose()), 0);
        for (std::size_t a = 0; a < basis.indices.size(); ++a) {
            const int A = piece.surface_index[static_cast<std::size_t>(basis.indices[a])];
            const double rw = basis.R(static_cast<Index>(a)) * carrier.weight(g);
            numerator(A) += rw * carrier.pressure(g);
            denominator(A) += rw;
        }
    }
    RecoveredPressure out;
    out.control_point_pressure = Vector::Zero(surface.n_control_points);
    for (Index A = 0; A < numerator.size(); ++A)
        if (denominator(A) > 0.0)
            out.control_point_pressure(A) = numerator(A) / denominator(A);
    out.normal_force = carrier.pressure.dot(carrier.weight);

    // Samples: every piece's own sample set, pieces in order (a point on an
    // interface appears once per piece, with the same value).
    const RowMatrix current = surface.control_points() + surface_displacement;
    std::vector<RecoveredPressure> parts;
    Index n_s = 0;
    for (const SidePiece& piece : surface.pieces) {
        Vector p_A(static_cast<Index>(piece.surface_index.size()));
        RowMatrix x(static_cast<Index>(piece.surface_index.size()), current.cols());
        for (std::size_t a = 0; a < piece.surface_index.size(); ++a) {
            p_A(static_cast<Index>(a)) = out.control_point_pressure(piece.surface_index[a]);
            x.row(static_cast<Index>(a)) = current.row(piece.surface_index[a]);
        }
        RecoveredPressure part;
        sample_pressure(piece.side.patch, x, p_A, samples_per_span, part);
        n_s += part.pressure.size();
        parts.push_back(std::move(part));
    }
    const Index q = parts.front().parameter.cols(), d = current.cols();
    out.parameter.resize(n_s, q);
    out.coordinates.resize(n_s, d);
    out.reference_coordinates.resize(n_s, d);
    out.pressure.resize(n_s);
    Index row = 0;
    for (const RecoveredPressure& part : parts) {
        const Index n = part.pressure.size();
        out.parameter.middleRows(row, n) = part.parameter;
        out.coordinates.middleRows(row, n) = part.coordinates;
        out.reference_coordinates.middleRows(row, n) = part.reference_coordinates;
        out.pressure.segment(row, n) = part.pressure;
        out.grids.push_back(part.grid);
        row += n;
    }
    out.grid = {n_s, 1};
    return out;
}

}  // namespace iga::contact
