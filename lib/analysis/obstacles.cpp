#include "analysis/obstacles.hpp"

#include "analysis/geometry.hpp"
#include "io/locate.hpp"

#include <fmt/format.h>

namespace iga::analysis {

namespace {

/// Distance from the surface, relative to the body size, that still counts as on it.
constexpr double touching_tolerance = 1e-9;

}  // namespace

contact::RigidObstacle rigid_obstacle(const io::Body& body)
{
    const VecN motion = body.motion.empty() ? VecN() : to_vec(body.motion);
    const Amplitude amplitude = body.amplitude.value_or(Amplitude());
    if (body.sphere)
        return contact::RigidObstacle(contact::RigidSphere::make(to_vec(body.sphere->center), body.sphere->radius),
                                      motion, amplitude);
    IGA_CHECK(body.plane.has_value(), "the deck reader let a rigid body without a shape through");
    return contact::RigidObstacle(contact::RigidPlane::make(to_vec(body.plane->point), to_vec(body.plane->normal)),
                                  motion, amplitude);
}

void check_obstacle_side(const io::Deck& deck, const Scene& scene, const io::ContactPair& pair,
                         const PairModel& model)
{
    const int k = model.obstacle;
    const int b = model.body[static_cast<std::size_t>(1 - k)];
    if (k < 0 || b < 0)
        return;
    const auto& obstacle = std::get<contact::RigidObstacle>(model.pair.surface(k));
    const BodyModel& body = scene.bodies[static_cast<std::size_t>(b)];
    const RowMatrix& points = body.node_points;
    // Points on the surface count as inside: a body that touches a flipped plane at
    // its lowest point (the usual Hertz set-up) lies wholly behind it all the same.
    const double on_surface = touching_tolerance * body.size();
    for (Index a = 0; a < points.rows(); ++a)
        if (!(obstacle.foot(points.row(a).transpose(), 0.0).gap >= -on_surface))
            return;  // a control point outside the obstacle: the body is not all inside
    const std::string& rigid = model.label[static_cast<std::size_t>(k)];
    const io::Body* deck_body = deck.find_body(rigid);
    IGA_CHECK(deck_body != nullptr, "a contact obstacle without its deck body");
    if (deck_body->plane) {
        const auto& n = deck_body->plane->normal;
        std::string flipped = "[";
        for (std::size_t i = 0; i < n.size(); ++i)
            flipped += fmt::format("{}{:.6g}", i ? ", " : "", n[i] == 0.0 ? 0.0 : -n[i]);
        throw DeckError(io::located_issue(
            deck.source_file, "bodies." + rigid + ".rigid.plane.normal", "",
            fmt::format("the whole body '{}' lies behind the plane of '{}' at the start (inside the obstacle), so "
                        "contact pair '{}' would push it through: the normal points OUT of the obstacle, towards "
                        "the bodies it stops; did you mean normal: {}]?",
                        body.name, rigid, pair.name, flipped)));
    }
    throw DeckError(io::located_issue(
        deck.source_file, "bodies." + rigid + ".rigid", "",
        fmt::format("the whole body '{}' lies inside the obstacle '{}' at the start, so contact pair '{}' cannot "
                    "push it out: check the centre and radius",
                    body.name, rigid, pair.name)));
}

}  // namespace iga::analysis
