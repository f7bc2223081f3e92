#include "analysis/geometry.hpp"

#include "io/deck_names.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"

#include <variant>

namespace iga::analysis {

nurbs::Affine placement(const std::vector<io::TransformStep>& steps, int dimension)
{
    nurbs::Affine map = nurbs::identity(dimension);
    for (const io::TransformStep& step : steps) {
        if (const auto* t = std::get_if<io::Translate>(&step))
            map = map.then(nurbs::translation(to_vec(t->offset)));
        else if (const auto* r = std::get_if<io::Rotate>(&step))
            map = map.then(dimension == 3 ? nurbs::rotation(to_vec(r->axis), r->angle_deg, to_vec(r->about))
                                          : nurbs::rotation_2d(r->angle_deg, to_vec(r->about)));
        else if (const auto* m = std::get_if<io::Mirror>(&step))
            map = map.then(nurbs::mirror(to_vec(m->normal), to_vec(m->point)));
        else
            map = map.then(nurbs::scaling(std::get<io::Scale>(step).factor, dimension));
    }
    return map;
}

nurbs::Patch raw_patch(const io::NurbsData& data, int dimension)
{
    std::vector<nurbs::KnotVector> knots;
    for (std::size_t dir = 0; dir < data.degrees.size(); ++dir)
        knots.emplace_back(data.degrees[dir], data.knots[dir]);
    const auto n = static_cast<Index>(data.control_points.size());
    RowMatrix points(n, dimension);
    Vector weights(n);
    for (Index a = 0; a < n; ++a) {
        const auto& row = data.control_points[static_cast<std::size_t>(a)];
        for (int i = 0; i < dimension; ++i)
            points(a, i) = row[static_cast<std::size_t>(i)];
        weights(a) = row[static_cast<std::size_t>(dimension)];
    }
    return nurbs::Patch(std::move(knots), std::move(points), std::move(weights));
}

nurbs::Patch placed(const nurbs::Patch& patch, const std::vector<io::TransformStep>& steps)
{
    return steps.empty() ? patch : nurbs::transformed(patch, placement(steps, patch.dim()));
}

namespace {

nurbs::Patch planar_or_solid_shape(const io::Shape& shape)
{
    switch (shape.type) {
    case io::ShapeType::half_disc: return nurbs::half_disc(to_vec(shape.center), shape.radius);
    case io::ShapeType::quarter_disc: return nurbs::quarter_disc(to_vec(shape.center), shape.radius);
    case io::ShapeType::rectangle: return nurbs::rectangle(to_vec(shape.corner), to_vec(shape.size));
    case io::ShapeType::sphere_octant: return nurbs::sphere_octant(to_vec(shape.center), shape.radius);
    case io::ShapeType::box: return nurbs::box(to_vec(shape.corner), to_vec(shape.size));
    }
    throw Error("unknown shape type");
}

/// The shape as built (extruded in 3D), before its transform.
nurbs::Patch shape_patch(const io::Shape& shape)
{
    nurbs::Patch patch = planar_or_solid_shape(shape);
    return shape.extrude ? nurbs::extrude(patch, *shape.extrude) : patch;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> side_meanings(const io::Body& body)
{
    if (!body.shape)
        return {};
    auto meanings =
        nurbs::shape_side_names(std::string(io::deck_name(body.shape->type)), body.shape->extrude.has_value());
    if (!body.shape->transform.empty())
        for (auto& [side, text] : meanings)
            text += " (as built; placed by the transform)";
    return meanings;
}

nurbs::Patch build_patch(const io::Body& body, int dimension, int halvings)
{
    IGA_CHECK(!body.rigid, "build_patch called for the rigid body '" + body.name + "'");
    IGA_CHECK(!body.multi_patch(), "build_patch called for the multi-patch body '" + body.name + "'");
    const nurbs::Patch built = body.nurbs ? raw_patch(*body.nurbs, dimension) : shape_patch(*body.shape);
    const std::vector<io::TransformStep>& steps = body.nurbs ? body.nurbs->transform : body.shape->transform;
    return nurbs::halve_spans(placed(refined(built, body.refine), steps), halvings);
}

nurbs::Patch refined(nurbs::Patch patch, const io::Refine& refine)
{
    for (std::size_t dir = 0; dir < refine.elevate.size(); ++dir)
        if (refine.elevate[dir] > 0)
            patch = nurbs::elevate_degree(patch, static_cast<int>(dir), refine.elevate[dir]);
    for (std::size_t dir = 0; dir < refine.spans.size(); ++dir)
        if (refine.spans[dir] > 1)
            patch = nurbs::refine_uniform(patch, static_cast<int>(dir), refine.spans[dir]);
    for (std::size_t dir = 0; dir < refine.insert.size(); ++dir)
        if (!refine.insert[dir].empty())
            patch = nurbs::insert_knots(patch, static_cast<int>(dir), refine.insert[dir]);
    return patch;
}

}  // namespace iga::analysis
