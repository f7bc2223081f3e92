#include "analysis/free_modes.hpp"
#include "core/text.hpp"

#include "core/error.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace iga::analysis {

namespace {

/// A point for a message: round-off below 1e-12 shown as 0.
VecN tidy(VecN p)
{
    for (Index i = 0; i < p.size(); ++i)
        if (std::abs(p(i)) < 1e-12)
            p(i) = 0.0;
    return p;
}

constexpr const char* axis_name[] = {"x", "y", "z"};

/// Deformable bodies joined by a contact pair of two deformable surfaces share a group.
std::vector<std::vector<int>> body_groups(const Scene& scene)
{
    std::vector<int> root(scene.bodies.size());
    std::iota(root.begin(), root.end(), 0);
    auto find = [&](int b) {
        while (root[static_cast<std::size_t>(b)] != b)
            b = root[static_cast<std::size_t>(b)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(b)])];
        return b;
    };
    for (const PairModel& pair : scene.pairs)
        if (pair.body[0] >= 0 && pair.body[1] >= 0)
            root[static_cast<std::size_t>(find(pair.body[0]))] = find(pair.body[1]);
    std::vector<std::vector<int>> groups;
    std::vector<int> group_of(scene.bodies.size(), -1);
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
        int& g = group_of[static_cast<std::size_t>(find(b))];
        if (g < 0) {
            g = static_cast<int>(groups.size());
            groups.emplace_back();
        }
        groups[static_cast<std::size_t>(g)].push_back(b);
    }
    return groups;
}

/// The rotation axes of dimension d: z in 2D; x, y, z in 3D.
std::vector<int> rotation_axes(int d) { return d == 2 ? std::vector<int>{2} : std::vector<int>{0, 1, 2}; }

/// omega x (X - c) for the unit vector omega along `axis`, in d components.
VecN rotation_motion(int axis, const VecN& X, const VecN& c)
{
    const int d = static_cast<int>(X.size());
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    r.head(d) = X - c;
    const Eigen::Vector3d v = Eigen::Vector3d::Unit(axis).cross(r);
    return v.head(d);
}

/// The group's nodes: full dofs (n_nodes x d) and reference positions.
struct GroupNodes {
    std::vector<std::vector<int>> dofs;
    std::vector<VecN> X;
    VecN centroid;
    double size = 1.0;  ///< bounding-box diagonal
};

GroupNodes group_nodes(const Scene& scene, const std::vector<int>& bodies)
{
    const assembly::DofMap& map = *scene.dofs;
    const int d = scene.dim;
    GroupNodes out;
    VecN lo = VecN::Constant(d, std::numeric_limits<double>::infinity()), hi = -lo;
    out.centroid = VecN::Zero(d);
    for (int b : bodies) {
        const BodyModel& body = scene.bodies[static_cast<std::size_t>(b)];
        for (int a = 0; a < body.n_nodes; ++a) {
            std::vector<int> dofs(static_cast<std::size_t>(d));
            for (int i = 0; i < d; ++i)
                dofs[static_cast<std::size_t>(i)] = map.dof(map.node_offset(b) + a, i);
            const VecN X = body.node_points.row(a).transpose();
            out.dofs.push_back(std::move(dofs));
            out.X.push_back(X);
            out.centroid += X;
            lo = lo.cwiseMin(X);
            hi = hi.cwiseMax(X);
        }
    }
    out.centroid /= static_cast<double>(std::max<std::size_t>(out.X.size(), 1));
    out.size = std::max((hi - lo).norm(), std::numeric_limits<double>::min());
    return out;
}

/// Rigid motion q of the group at node a: translations q_0..q_{d-1}, then unit
/// rotations about the centroid scaled by 1 / size (node motion <= 1).
VecN rigid_motion(const GroupNodes& nodes, int a, const Vector& q, int d)
{
    VecN u = q.head(d);
    const std::vector<int> axes = rotation_axes(d);
    for (std::size_t r = 0; r < axes.size(); ++r)
        u += q(d + static_cast<Index>(r)) / nodes.size *
             rotation_motion(axes[r], nodes.X[static_cast<std::size_t>(a)], nodes.centroid);
    return u;
}

/// The rows that hold rigid motions: one per prescribed dof, one per contact-side
/// node against a rigid obstacle (with_contact). Row . q = the held motion of mode q.
Matrix holding_rows(const Scene& scene, const std::vector<int>& bodies, const GroupNodes& nodes,
                    bool with_contact = true)
{
    const assembly::DofMap& map = *scene.dofs;
    const int d = scene.dim;
    const int n_rigid = d + static_cast<int>(rotation_axes(d).size());
    std::vector<Vector> rows;
    // A's row for "direction n at node a": n . (R q)(X_a), linear in q.
    auto add_row = [&](int a, const VecN& n) {
        Vector row(n_rigid);
        for (int j = 0; j < n_rigid; ++j)
            row(j) = n.dot(rigid_motion(nodes, a, Vector::Unit(n_rigid, j), d));
        rows.push_back(row);
    };
    for (std::size_t a = 0; a < nodes.dofs.size(); ++a)
        for (int i = 0; i < d; ++i)
            if (map.is_constrained(nodes.dofs[a][static_cast<std::size_t>(i)]))
                add_row(static_cast<int>(a), VecN::Unit(d, i));

    // Group node of (body b, body node a).
    std::vector<int> first_node;
    int count = 0;
    for (int b : bodies) {
        first_node.push_back(count);
        count += scene.bodies[static_cast<std::size_t>(b)].n_nodes;
    }
    for (const PairModel& pair : scene.pairs) {
        if (pair.obstacle < 0 || !with_contact)
            continue;
        const int k = 1 - pair.obstacle;
        const auto member = std::find(bodies.begin(), bodies.end(), pair.body[static_cast<std::size_t>(k)]);
        if (member == bodies.end())
            continue;
        const int offset = first_node[static_cast<std::size_t>(member - bodies.begin())];
        const auto& obstacle = std::get<contact::RigidObstacle>(pair.pair.surface(pair.obstacle));
        for (int parent : pair.parent_index[static_cast<std::size_t>(k)]) {
            const int a = offset + parent;
            const VecN& X = nodes.X[static_cast<std::size_t>(a)];
            if (pair.pair.settings().friction.active()) {  // a sticking point is held in every direction
                for (int i = 0; i < d; ++i)
                    add_row(a, VecN::Unit(d, i));
                continue;
            }
            if (const auto* plane = std::get_if<contact::RigidPlane>(&obstacle.shape)) {
                add_row(a, plane->normal);
            } else {
                const VecN r = X - std::get<contact::RigidSphere>(obstacle.shape).center;
                if (r.norm() > 0.0)  // at the centre every direction is normal: no contact is defined there
                    add_row(a, r.normalized());
            }
        }
    }
    Matrix A(static_cast<Index>(rows.size()), n_rigid);
    for (std::size_t r = 0; r < rows.size(); ++r)
        A.row(static_cast<Index>(r)) = rows[r].transpose();
    return A;
}

/// The n_full displacement of rigid motion q of the group, zero on prescribed dofs
/// (where a free mode is zero up to free_mode_tolerance anyway).
Vector full_motion(const Scene& scene, const GroupNodes& nodes, const Vector& q)
{
    const assembly::DofMap& map = *scene.dofs;
    const int d = scene.dim;
    Vector u = Vector::Zero(map.n_full());
    for (std::size_t a = 0; a < nodes.dofs.size(); ++a) {
        const VecN m = rigid_motion(nodes, static_cast<int>(a), q, d);
        for (int i = 0; i < d; ++i) {
            const int k = nodes.dofs[a][static_cast<std::size_t>(i)];
            u(k) = map.is_constrained(k) ? 0.0 : m(i);
        }
    }
    return u;
}

/// Dimension of the null space of A's first `columns` columns (the rigid modes q
/// restricted to them that no row holds), by the tolerance of find_free_modes.
int nullity(const Matrix& A, int columns)
{
    if (A.rows() == 0)
        return columns;
    const Eigen::JacobiSVD<Matrix> svd(A.leftCols(columns));
    const Vector& sigma = svd.singularValues();
    int n = 0;
    for (int j = 0; j < columns; ++j)
        if (j >= sigma.size() || sigma(j) <= free_mode_tolerance)
            ++n;
    return n;
}

std::string group_label(const Scene& scene, const std::vector<int>& bodies)
{
    if (bodies.size() == 1)
        return "body " + scene.bodies[static_cast<std::size_t>(bodies[0])].name;
    std::string out = "bodies ";
    for (std::size_t k = 0; k < bodies.size(); ++k)
        out += (k == 0 ? "" : k + 1 == bodies.size() ? " and " : ", ") +
               scene.bodies[static_cast<std::size_t>(bodies[k])].name;
    return out;
}

}  // namespace

std::vector<FreeModeGroup> find_free_modes(const Scene& scene)
{
    const int d = scene.dim;
    const std::vector<int> axes = rotation_axes(d);
    const int n_rigid = d + static_cast<int>(axes.size());
    std::vector<FreeModeGroup> out;
    for (const std::vector<int>& bodies : body_groups(scene)) {
        const GroupNodes nodes = group_nodes(scene, bodies);
        const Matrix A = holding_rows(scene, bodies, nodes);
        auto held = [&](const Vector& q) { return A.rows() > 0 && (A * q).lpNorm<Eigen::Infinity>() > free_mode_tolerance; };

        // Null space of A: right singular vectors with sigma <= tolerance (and all
        // of them past the rank when A has fewer rows than columns).
        Matrix null_space(n_rigid, 0);
        if (A.rows() == 0) {
            null_space = Matrix::Identity(n_rigid, n_rigid);
        } else {
            const Eigen::JacobiSVD<Matrix> svd(A, Eigen::ComputeFullV);
            const Vector& sigma = svd.singularValues();
            std::vector<int> columns;
            for (int j = 0; j < n_rigid; ++j)
                if (j >= sigma.size() || sigma(j) <= free_mode_tolerance)
                    columns.push_back(j);
            null_space.resize(n_rigid, static_cast<Index>(columns.size()));
            for (std::size_t c = 0; c < columns.size(); ++c)
                null_space.col(static_cast<Index>(c)) = svd.matrixV().col(columns[c]);
        }
        if (null_space.cols() == 0)
            continue;

        FreeModeGroup group;
        group.bodies = bodies;
        group.label = group_label(scene, bodies);
        group.basis.resize(scene.dofs->n_full(), null_space.cols());
        for (Index c = 0; c < null_space.cols(); ++c) {
            Vector m = full_motion(scene, nodes, null_space.col(c));
            double largest = 0.0;  // node motion <= 1
            for (const auto& dofs : nodes.dofs) {
                double norm2 = 0.0;
                for (int k : dofs)
                    norm2 += m(k) * m(k);
                largest = std::max(largest, std::sqrt(norm2));
            }
            group.basis.col(c) = m / std::max(largest, std::numeric_limits<double>::min());
        }

        for (int i = 0; i < d; ++i)
            if (!held(Vector::Unit(n_rigid, i))) {
                FreeMode mode;
                mode.kind = FreeMode::Kind::translation;
                mode.axis = i;
                mode.displacement = full_motion(scene, nodes, Vector::Unit(n_rigid, i));
                mode.text = fmt::format("translate freely in {}", axis_name[i]);
                group.named.push_back(std::move(mode));
            }
        // A rotation about c = the rotation about the centroid plus a translation t:
        // the least-squares (minimum-norm) t that frees it, if any does.
        const Matrix A_t = A.leftCols(d);
        for (std::size_t r = 0; r < axes.size(); ++r) {
            Vector q = Vector::Unit(n_rigid, d + static_cast<Index>(r));
            if (A.rows() > 0)
                q.head(d) = Eigen::JacobiSVD<Matrix>(A_t, Eigen::ComputeThinU | Eigen::ComputeThinV)
                                .solve(-A.col(d + static_cast<Index>(r)));
            if (held(q))
                continue;
            // t = -omega x (c - g) / size  =>  c - g = size omega x t (t normal to omega).
            Eigen::Vector3d t = Eigen::Vector3d::Zero();
            t.head(d) = q.head(d);
            const Eigen::Vector3d shift = nodes.size * Eigen::Vector3d::Unit(axes[r]).cross(t);
            FreeMode mode;
            mode.kind = FreeMode::Kind::rotation;
            mode.axis = axes[r];
            mode.centre = nodes.centroid + shift.head(d);
            mode.displacement = nodes.size * full_motion(scene, nodes, q);  // unit angle
            mode.text = d == 2 ? fmt::format("rotate freely about {}", point_text(tidy(mode.centre), 4))
                               : fmt::format("rotate freely about the {} axis through {}", axis_name[axes[r]],
                                             point_text(tidy(mode.centre), 4));
            group.named.push_back(std::move(mode));
        }

        double E_min = std::numeric_limits<double>::infinity();
        for (int b : bodies)
            E_min = std::min(E_min, scene.bodies[static_cast<std::size_t>(b)].material.E);
        group.spring_stiffness = weak_spring_factor * E_min * std::pow(nodes.size, d - 2) /
                                 static_cast<double>(nodes.X.size());
        out.push_back(std::move(group));
    }
    return out;
}

std::string free_mode_text(const FreeModeGroup& group)
{
    std::string out = group.label + " can ";
    for (std::size_t k = 0; k < group.named.size(); ++k) {
        const std::string text = group.named[k].text;
        out += (k == 0 ? "" : k + 1 == group.named.size() ? " and " : ", ") + text;
    }
    const int unnamed = group.n_modes() - static_cast<int>(group.named.size());
    if (unnamed > 0)
        out += fmt::format("{}move freely in {} further rigid motion(s)", group.named.empty() ? "" : " and ", unnamed);
    return out;
}

Vector reference_loads(const Scene& scene, double t)
{
    Vector f = scene.f_ext(t);
    const int d = scene.dim;
    for (const FollowerPressure& follower : scene.followers)
        for (std::size_t e = 0; e < follower.side.elements.size(); ++e) {
            const auto& element = follower.side.elements[e];
            const mechanics::LocalForceTangent local = mechanics::follower_pressure(
                element, d, follower.amplitude(t) * follower.pressure, scene.kinematics,
                Matrix::Zero(element.n_local(), d));
            const auto& dofs = follower.element_dofs[e];
            for (std::size_t k = 0; k < dofs.size(); ++k)
                f(dofs[k]) += local.f_ext(static_cast<Index>(k));
        }
    return f;
}

std::optional<std::string> driven_free_mode(const Scene& scene, const std::vector<FreeModeGroup>& groups,
                                            const Vector& loads)
{
    auto driven = [&](const Vector& m, double& work) {
        work = loads.dot(m);
        const double scale = loads.cwiseProduct(m).cwiseAbs().sum();
        return scale > 0.0 && std::abs(work) > driven_mode_tolerance * scale;
    };
    for (const FreeModeGroup& group : groups) {
        double work = 0.0;
        for (const FreeMode& mode : group.named)
            if (driven(mode.displacement, work)) {
                const std::string what =
                    mode.kind == FreeMode::Kind::translation
                        ? fmt::format("a resultant {:.4g} in {}", work, axis_name[mode.axis])
                    : scene.dim == 2
                        ? fmt::format("a moment {:.4g} about {}", work, point_text(tidy(mode.centre), 4))
                        : fmt::format("a moment {:.4g} about the {} axis through {}", work, axis_name[mode.axis],
                                      point_text(tidy(mode.centre), 4));
                return fmt::format("loads drive a free mode: {} can {} and the loads have {}", group.label, mode.text,
                                   what);
            }
        for (Index c = 0; c < group.basis.cols(); ++c)
            if (driven(group.basis.col(c), work))
                return fmt::format("loads drive a free mode: {} can move freely in a combined rigid motion and the "
                                   "loads do work {:.4g} along it (per unit node motion)",
                                   group.label, work);
    }
    return std::nullopt;
}

std::vector<NodeSpring> weak_springs(const Scene& scene, const FreeModeGroup& group)
{
    const assembly::DofMap& map = *scene.dofs;
    const int d = scene.dim;
    std::vector<NodeSpring> out;
    for (int b : group.bodies)
        for (int a = 0; a < map.n_nodes(b); ++a) {
            NodeSpring spring;
            for (int i = 0; i < d; ++i)
                spring.dofs.push_back(map.dof(map.node_offset(b) + a, i));
            spring.stiffness = MatN::Zero(d, d);
            for (Index c = 0; c < group.basis.cols(); ++c) {
                VecN m(d);
                for (int i = 0; i < d; ++i)
                    m(i) = group.basis(spring.dofs[static_cast<std::size_t>(i)], c);
                spring.stiffness += group.spring_stiffness * m * m.transpose();
            }
            if (spring.stiffness.cwiseAbs().maxCoeff() > 0.0)
                out.push_back(std::move(spring));
        }
    return out;
}

bool singular_without_contact(const Scene& scene, const std::vector<FreeModeGroup>& free_modes)
{
    const int d = scene.dim;
    // A stressed finite-strain tangent is singular along a free translation (r is
    // invariant under it) but not along a rotation, which turns the stress.
    const bool small = scene.kinematics == mechanics::Kinematics::small;
    const int columns = d + (small ? static_cast<int>(rotation_axes(d).size()) : 0);
    int constraint_free = 0;  // per body: its elastic stiffness alone is singular along these
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
        const GroupNodes nodes = group_nodes(scene, {b});
        constraint_free += nullity(holding_rows(scene, {b}, nodes, false), columns);
    }
    // The weak springs hold the free modes: at most that many of these directions.
    int spring_held = 0;
    for (const FreeModeGroup& group : free_modes)
        spring_held += group.n_modes();
    return constraint_free > spring_held;
}

}  // namespace iga::analysis
