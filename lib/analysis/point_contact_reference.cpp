#include "analysis/point_contact_reference.hpp"

#include "analytic/radial_pressure_errors.hpp"
#include "contact/projection.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

namespace iga::analysis {

namespace {

/// Points of a face on a grid: `per_span` intervals per knot span and direction, span ends included.
std::vector<VecN> face_samples(const nurbs::Patch& face, int per_span)
{
    std::vector<std::vector<double>> axis(static_cast<std::size_t>(face.n_par()));
    for (int dir = 0; dir < face.n_par(); ++dir) {
        const std::vector<double> breaks = face.knots(dir).breakpoints();
        for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
            for (int k = 0; k < per_span; ++k)
                axis[dir].push_back(breaks[s] + (breaks[s + 1] - breaks[s]) * k / per_span);
        axis[dir].push_back(breaks.back());
    }
    std::vector<VecN> out;
    for (double v : axis.size() > 1 ? axis[1] : std::vector<double>{0.0})
        for (double u : axis[0]) {
            VecN xi(face.n_par());
            xi(0) = u;
            if (face.n_par() > 1)
                xi(1) = v;
            out.push_back(nurbs::evaluate(face, xi, 0).x);
        }
    return out;
}

const contact::DeformableSide* deformable(const contact::ContactPair& pair, int k)
{
    return std::get_if<contact::DeformableSide>(&pair.surface(k));
}

std::vector<double> to_std(const VecN& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace

io::ReferenceData point_contact_reference(const io::Deck& deck, const Scene& scene, const PairModel& model,
                                          const io::StepData* step)
{
    const io::Reference& ref = *deck.output.reference;
    auto elastic = [&](int k, double& E, double& nu) {
        const int b = model.body[static_cast<std::size_t>(k)];
        E = b < 0 ? std::numeric_limits<double>::infinity() : scene.bodies[static_cast<std::size_t>(b)].material.E;
        nu = b < 0 ? 0.0 : scene.bodies[static_cast<std::size_t>(b)].material.nu;
    };
    io::ReferenceData data;
    data.pair = ref.pair;
    analytic::HertzPointContact hertz{};
    VecN center(3), normal(3);
    constexpr int samples_per_span = 16;
    if (ref.type == io::ReferenceType::hertz_sphere_plane) {
        data.type = "hertz_sphere_plane";
        const int k_body = deformable(model.pair, 0) ? 0 : 1;
        double E, nu;
        elastic(k_body, E, nu);
        hertz = analytic::hertz_sphere_plane(E, nu, ref.radius, ref.force);
        const auto& obstacle = std::get<contact::RigidObstacle>(model.pair.surface(1 - k_body));
        normal = std::get<contact::RigidPlane>(obstacle.shape).normal;
        double lowest = std::numeric_limits<double>::infinity();
        for (const contact::SidePiece& piece : deformable(model.pair, k_body)->pieces)
            for (const VecN& x : face_samples(piece.side.patch, samples_per_span))
                if (x.dot(normal) < lowest) {
                    lowest = x.dot(normal);
                    center = x;
                }
        data.inputs["radius"] = ref.radius;
        data.inputs["E"] = E;
        data.inputs["nu"] = nu;
    } else {
        data.type = "hertz_two_spheres";
        double E1, nu1, E2, nu2;
        elastic(0, E1, nu1);
        elastic(1, E2, nu2);
        hertz = analytic::hertz_two_spheres(E1, nu1, ref.radii[0], E2, nu2, ref.radii[1], ref.force);
        const contact::DeformableSide* a = deformable(model.pair, 0);
        const contact::DeformableSide* b = deformable(model.pair, 1);
        IGA_CHECK(a && b, "hertz_two_spheres needs two deformable sides");
        double best = std::numeric_limits<double>::infinity();
        for (const contact::SidePiece& pa : a->pieces)
            for (const VecN& x : face_samples(pa.side.patch, 4))
                for (const contact::SidePiece& pb : b->pieces) {
                    const contact::Projection p = contact::project_to_surface(pb.side.patch, pb.outward_sign, x);
                    if (p.status == contact::Projection::Status::failed || !(p.distance < best))
                        continue;
                    best = p.distance;
                    center = 0.5 * (x + p.point);
                    normal = p.normal;
                }
        data.inputs["radius_first"] = ref.radii[0];
        data.inputs["radius_second"] = ref.radii[1];
    }
    data.inputs["force"] = ref.force;
    data.inputs["E_star"] = hertz.E_star;
    data.inputs["R_star"] = hertz.R_star;
    data.a = hertz.a;
    data.p0 = hertz.p0;
    data.center = to_std(center);
    // The stored curve runs along one in-plane direction through the centre.
    const Eigen::Vector3d n3 = normal;
    const Eigen::Vector3d axis = std::abs(n3(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const VecN tangent = n3.cross(axis).normalized();
    data.tangent = to_std(tangent);
    data.normal = to_std(normal);
    constexpr int n_curve = 601;
    data.x.resize(n_curve);
    data.pressure.resize(n_curve);
    data.coordinates.resize(n_curve, 3);
    for (int i = 0; i < n_curve; ++i) {
        const double x = -1.5 * hertz.a + 3.0 * hertz.a * i / (n_curve - 1);
        data.x(i) = x;
        data.pressure(i) = hertz.pressure(std::abs(x));
        data.coordinates.row(i) = (center + x * tangent).transpose();
    }

    if (!step)
        return data;
    for (const io::ContactPairResult& pair : step->contact) {
        if (pair.name != ref.pair)
            continue;
        for (std::size_t s = 0; s < pair.sides.size(); ++s) {
            const io::ContactSideResult& side = pair.sides[s];
            auto measure = [&](const RowMatrix& X, const Vector& p, const std::string& prefix) {
                if (X.rows() == 0)
                    return;
                const std::vector<double> r = analytic::in_plane_distances(X, center, normal);
                const std::vector<double> ps(p.data(), p.data() + p.size());
                const analytic::RadialPressureErrors e = analytic::radial_pressure_errors(hertz, r, ps);
                const std::string tag = s == 0 ? prefix : side.side_name + "." + prefix;
                data.errors[tag + "peak"] = e.peak;
                data.errors[tag + "contact_radius"] = e.radius;
                data.errors[tag + "l2"] = e.l2;
            };
            measure(side.postprocessed.reference_coordinates, side.postprocessed.pressure, "");
            measure(side.gauss_points.reference_coordinates, side.gauss_points.pressure, "gauss_");
            if (s == 0)
                data.errors["normal_force"] = side.normal_force;
        }
    }
    return data;
}

}  // namespace iga::analysis
