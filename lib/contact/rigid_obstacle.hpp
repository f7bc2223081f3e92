#pragma once
// Rigid obstacles: a plane (a line in 2D) or a sphere (a circle in 2D), each
// possibly moving by a rigid translation a(t) * motion, scaled by its amplitude
// at the pseudo-time t (core/amplitude.hpp; the default ramp: the load factor).
//
//  - plane: the points y with (y - point) . normal <= 0 are inside the obstacle;
//    `normal` is the unit normal pointing OUT of it;
//  - sphere: the solid ball |y - center| <= radius; its outward normal at the
//    foot point of x is n = (x - center) / |x - center| (analytic projection).
//
// An obstacle plays the master. The gap of a slave point x follows gap.hpp,
// g_N = -(x - foot) . n: negative (open) outside, positive (penetration) inside.
// The residual of the slave uses n, which depends on no unknown; for the sphere
// it turns with x, and the tangent needs the radius of curvature of the
// obstacle's surface at the foot point (`radius`, infinite for a plane).
// Everything is dimension-free (d = 2 or 3).

#include "contact/gap.hpp"
#include "core/amplitude.hpp"
#include "core/error.hpp"
#include "core/types.hpp"

#include <cmath>
#include <limits>
#include <variant>

namespace iga::contact {

struct RigidPlane {
    VecN point;   ///< a point on the plane, d
    VecN normal;  ///< unit normal out of the obstacle, d

    /// Normalizes `normal`; throws iga::Error for mismatched sizes, non-finite
    /// values or a zero normal (the deck reader rejects these first).
    static RigidPlane make(const VecN& point, const VecN& normal)
    {
        IGA_CHECK(point.size() == normal.size() && (point.size() == 2 || point.size() == 3),
                  "contact: rigid plane point and normal need the same dimension, 2 or 3");
        IGA_CHECK(point.allFinite() && normal.allFinite() && normal.norm() > 0.0,
                  "contact: rigid plane needs a finite point and a non-zero finite normal");
        return RigidPlane{point, normal.normalized()};
    }

    /// g_N of x: positive = penetration into the obstacle.
    double gap(const VecN& x) const { return normal_gap(x, point, normal); }
};

/// The solid ball (disc in 2D) of radius `radius` around `center`.
struct RigidSphere {
    VecN center;
    double radius = 0.0;

    static RigidSphere make(const VecN& center, double radius)
    {
        IGA_CHECK(center.size() == 2 || center.size() == 3, "contact: rigid sphere centre needs 2 or 3 coordinates");
        IGA_CHECK(center.allFinite() && std::isfinite(radius) && radius > 0.0,
                  "contact: rigid sphere needs a finite centre and a radius > 0");
        return RigidSphere{center, radius};
    }
};

/// What the slave point x sees of an obstacle: its gap, the outward normal at the
/// foot point and the radius of curvature there (infinite for a plane).
struct ObstacleFoot {
    bool ok = true;        ///< false: x sits at the centre of a sphere (no normal)
    double gap = 0.0;      ///< g_N, positive = penetration
    VecN normal;           ///< unit, out of the obstacle
    double radius = std::numeric_limits<double>::infinity();
};

struct RigidObstacle {
    std::variant<RigidPlane, RigidSphere> shape;
    VecN motion;  ///< full translation, d; empty or zero for a fixed obstacle
    Amplitude amplitude;  ///< of the motion

    // Implicit on purpose: a plane or a sphere is a (fixed) obstacle wherever a surface is expected.
    RigidObstacle(RigidPlane plane, VecN motion_ = {}, Amplitude amplitude_ = {})
        : shape(std::move(plane)), motion(std::move(motion_)), amplitude(std::move(amplitude_))
    {
    }
    RigidObstacle(RigidSphere sphere, VecN motion_ = {}, Amplitude amplitude_ = {})
        : shape(std::move(sphere)), motion(std::move(motion_)), amplitude(std::move(amplitude_))
    {
    }

    int dim() const
    {
        return static_cast<int>(std::holds_alternative<RigidPlane>(shape) ? std::get<RigidPlane>(shape).point.size()
                                                                         : std::get<RigidSphere>(shape).center.size());
    }

    /// The obstacle's translation at pseudo-time t: a(t) * motion.
    VecN shift(double t) const
    {
        return motion.size() == dim() ? VecN(amplitude(t) * motion) : VecN(VecN::Zero(dim()));
    }
    /// The foot point data of x with the obstacle translated by a(t) * motion.
    ObstacleFoot foot(const VecN& x, double t) const
    {
        const VecN shift = this->shift(t);
        ObstacleFoot out;
        if (const auto* plane = std::get_if<RigidPlane>(&shape)) {
            out.normal = plane->normal;
            out.gap = normal_gap(x, plane->point + shift, plane->normal);
            return out;
        }
        const RigidSphere& sphere = std::get<RigidSphere>(shape);
        const VecN r = x - (sphere.center + shift);
        const double distance = r.norm();
        // At the centre every direction is a normal: no contact force can be defined.
        constexpr double centre_tolerance = 1e-12;
        if (!(distance > centre_tolerance * sphere.radius)) {
            out.ok = false;
            out.normal = VecN::Zero(x.size());
            out.gap = sphere.radius;
            return out;
        }
        out.normal = r / distance;
        out.gap = sphere.radius - distance;
        out.radius = distance;  // the normal turns with x about the centre: d n / d x = (I - n n) / |x - c|
        return out;
    }
};

}  // namespace iga::contact
