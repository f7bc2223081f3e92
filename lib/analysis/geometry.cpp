#include "analysis/geometry.hpp"

#include "io/deck_names.hpp"
#include "nurbs/refine.hpp"
#include "nurbs/shapes.hpp"

#include <fmt/format.h>

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

namespace {

/// Why points (rows) are out of the range of TransformOutOfRange; "" when in range.
std::string range_problem(const RowMatrix& points)
{
    if (!points.allFinite())
        return "a control point is no longer a finite number (beyond about 1.8e308)";
    const double largest = points.cwiseAbs().maxCoeff();
    // The largest extent along an axis: a norm would square 1e-300 to 0.
    const double size = (points.colwise().maxCoeff() - points.colwise().minCoeff()).maxCoeff();
    if (largest > max_placed_coordinate)
        return fmt::format("a control point reaches |x| = {:.3g}, beyond {:g} (the element geometry multiplies "
                           "such lengths and would overflow)",
                           largest, max_placed_coordinate);
    if (size < min_placed_size)
        return fmt::format("the patch shrinks to a size of {:.3g}, below {:g} (the element geometry multiplies "
                           "such lengths and would underflow to 0)",
                           size, min_placed_size);
    if (size < min_size_to_distance * largest)
        return fmt::format("the patch (size {:.3g}) lies {:.3g} from the origin, more than {:g} times its size: "
                           "round-off of the coordinates would blur its shape",
                           size, largest, 1.0 / min_size_to_distance);
    return {};
}

}  // namespace

nurbs::Patch placed(const nurbs::Patch& patch, const std::vector<io::TransformStep>& steps)
{
    if (steps.empty())
        return patch;
    // Each prefix of the steps applied to the control points: the first step that
    // leaves the range (and was not out of it before) is named. Cheap: a few
    // matrix products of the control points per step.
    const int d = patch.dim();
    const RowMatrix& raw = patch.control_points();
    bool in_range = range_problem(raw).empty();
    nurbs::Affine map = nurbs::identity(d);
    for (std::size_t k = 0; k < steps.size(); ++k) {
        map = map.then(placement({steps[k]}, d));
        if (!in_range)
            continue;
        RowMatrix points = raw * map.A.transpose();
        points.rowwise() += map.b.transpose();
        const std::string problem = map.A.allFinite() && map.b.allFinite()
                                        ? range_problem(points)
                                        : std::string("the transform is no longer a finite map (beyond about 1.8e308)");
        if (!problem.empty())
            throw TransformOutOfRange(k, io::transform_step_keys[steps[k].index()],
                                      "out of range: after this step " + problem);
    }
    return nurbs::transformed(patch, map);
}

std::string transform_path(const io::Body& body, const std::string& patch)
{
    const std::string prefix = "bodies." + body.name;
    if (!patch.empty())
        return body.geometry_file.empty() ? prefix + ".patches." + patch + ".nurbs.transform"
                                          : prefix + ".geometry.transform";
    return prefix + (body.shape ? ".shape.transform" : ".nurbs.transform");
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
