#include "analysis/geometry.hpp"

#include "io/deck_names.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"

namespace iga::analysis {

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
    return nurbs::shape_side_names(std::string(io::deck_name(body.shape->type)), body.shape->extrude.has_value());
}

nurbs::Patch build_patch(const io::Body& body, int dimension, int halvings)
{
    IGA_CHECK(!body.rigid, "build_patch called for the rigid body '" + body.name + "'");
    IGA_CHECK(!body.multi_patch(), "build_patch called for the multi-patch body '" + body.name + "'");
    return nurbs::halve_spans(
        refined(body.nurbs ? raw_patch(*body.nurbs, dimension) : shape_patch(*body.shape), body.refine), halvings);
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
