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

/// E and nu of surface k of a pair (a rigid one: E infinite).
void elastic_constants(const Scene& scene, const PairModel& model, int k, double& E, double& nu)
{
    const int b = model.body[static_cast<std::size_t>(k)];
    E = b < 0 ? std::numeric_limits<double>::infinity() : scene.bodies[static_cast<std::size_t>(b)].material.E;
    nu = b < 0 ? 0.0 : scene.bodies[static_cast<std::size_t>(b)].material.nu;
}

/// A 3D Hertz solution placed on the pair: the first-touch point and the normal there.
struct PlacedPointContact {
    analytic::HertzPointContact hertz{};
    VecN center = VecN::Zero(3);
    VecN normal = VecN::Zero(3);
};

PlacedPointContact sphere_on_plane(const Scene& scene, const PairModel& model, const io::Reference& ref,
                                   io::ReferenceData& data)
{
    constexpr int samples_per_span = 16;
    PlacedPointContact out;
    data.type = "hertz_sphere_plane";
    const int k_body = deformable(model.pair, 0) ? 0 : 1;
    double E, nu;
    elastic_constants(scene, model, k_body, E, nu);
    out.hertz = analytic::hertz_sphere_plane(E, nu, ref.radius, ref.force);
    const auto& obstacle = std::get<contact::RigidObstacle>(model.pair.surface(1 - k_body));
    out.normal = std::get<contact::RigidPlane>(obstacle.shape).normal;
    double lowest = std::numeric_limits<double>::infinity();
    for (const contact::SidePiece& piece : deformable(model.pair, k_body)->pieces)
        for (const VecN& x : face_samples(piece.side.patch, samples_per_span))
            if (x.dot(out.normal) < lowest) {
                lowest = x.dot(out.normal);
                out.center = x;
            }
    data.inputs["radius"] = ref.radius;
    data.inputs["E"] = E;
    data.inputs["nu"] = nu;
    return out;
}

PlacedPointContact two_spheres(const Scene& scene, const PairModel& model, const io::Reference& ref,
                               io::ReferenceData& data)
{
    PlacedPointContact out;
    data.type = "hertz_two_spheres";
    double E1, nu1, E2, nu2;
    elastic_constants(scene, model, 0, E1, nu1);
    elastic_constants(scene, model, 1, E2, nu2);
    out.hertz = analytic::hertz_two_spheres(E1, nu1, ref.radii[0], E2, nu2, ref.radii[1], ref.force);
    const contact::DeformableSide* a = deformable(model.pair, 0);
    const contact::DeformableSide* b = deformable(model.pair, 1);
    IGA_CHECK(a && b, "hertz_two_spheres needs two deformable sides");
    double best = std::numeric_limits<double>::infinity();
    for (const contact::SidePiece& pa : a->pieces)
        for (const VecN& x : face_samples(pa.side.patch, 4))
            for (const contact::SidePiece& pb : b->pieces) {
                const contact::Projection p = contact::project_to_surface(pb.side.patch, pb.outward_sign, x);
                if (p.status == contact::Projection::Status::failed ||
                    p.status == contact::Projection::Status::unsettled || !(p.distance < best))
                    continue;
                best = p.distance;
                out.center = 0.5 * (x + p.point);
                out.normal = p.normal;
            }
    data.inputs["radius_first"] = ref.radii[0];
    data.inputs["radius_second"] = ref.radii[1];
    return out;
}

/// The stored curve: along one in-plane direction through the centre.
void sample_curve(const PlacedPointContact& placed, io::ReferenceData& data)
{
    const Eigen::Vector3d n3 = placed.normal;
    const Eigen::Vector3d axis = std::abs(n3(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const VecN tangent = n3.cross(axis).normalized();
    data.tangent = to_std(tangent);
    data.normal = to_std(placed.normal);
    constexpr int n_curve = 601;
    data.x.resize(n_curve);
    data.pressure.resize(n_curve);
    data.coordinates.resize(n_curve, 3);
    for (int i = 0; i < n_curve; ++i) {
        const double x = -1.5 * placed.hertz.a + 3.0 * placed.hertz.a * i / (n_curve - 1);
        data.x(i) = x;
        data.pressure(i) = placed.hertz.pressure(std::abs(x));
        data.coordinates.row(i) = (placed.center + x * tangent).transpose();
    }
}

/// Peak, contact radius and L2 errors of pressures p at reference coordinates X.
void add_radial_errors(const PlacedPointContact& placed, const RowMatrix& X, const Vector& p, const std::string& tag,
                       io::ReferenceData& data)
{
    if (X.rows() == 0)
        return;
    const std::vector<double> r = analytic::in_plane_distances(X, placed.center, placed.normal);
    const std::vector<double> ps(p.data(), p.data() + p.size());
    const analytic::RadialPressureErrors e = analytic::radial_pressure_errors(placed.hertz, r, ps);
    data.errors[tag + "peak"] = e.peak;
    data.errors[tag + "contact_radius"] = e.radius;
    data.errors[tag + "l2"] = e.l2;
}

}  // namespace

io::ReferenceData point_contact_reference(const Scene& scene, const PairModel& model,
                                          const io::StepData* step)
{
    const io::Reference& ref = *scene.settings.output.reference;
    io::ReferenceData data;
    data.pair = ref.pair;
    const PlacedPointContact placed = ref.type == io::ReferenceType::hertz_sphere_plane
                                          ? sphere_on_plane(scene, model, ref, data)
                                          : two_spheres(scene, model, ref, data);
    data.inputs["force"] = ref.force;
    data.inputs["E_star"] = placed.hertz.E_star;
    data.inputs["R_star"] = placed.hertz.R_star;
    data.a = placed.hertz.a;
    data.p0 = placed.hertz.p0;
    data.center = to_std(placed.center);
    sample_curve(placed, data);
    if (!step)
        return data;
    for (const io::ContactPairResult& pair : step->contact) {
        if (pair.name != ref.pair)
            continue;
        for (std::size_t s = 0; s < pair.sides.size(); ++s) {
            const io::ContactSideResult& side = pair.sides[s];
            const std::string prefix = s == 0 ? "" : side.side_name + ".";
            add_radial_errors(placed, side.postprocessed.reference_coordinates, side.postprocessed.pressure, prefix,
                              data);
            add_radial_errors(placed, side.gauss_points.reference_coordinates, side.gauss_points.pressure,
                              prefix + "gauss_", data);
            if (s == 0)
                data.errors["normal_force"] = side.normal_force;
        }
    }
    return data;
}

}  // namespace iga::analysis
