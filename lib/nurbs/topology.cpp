#include "nurbs/topology.hpp"

#include "nurbs/refine.hpp"
#include "nurbs/side_patch.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <tuple>
#include <unordered_map>

namespace iga::nurbs {
namespace {

/// Two normalized knots closer than this are the same knot: far above the
/// round-off of t = (u - front) / range, far below any sensible span.
constexpr double knot_tolerance = 1e-10;
/// Weights of glued sides must be proportional to this relative accuracy.
constexpr double weight_tolerance = 1e-10;
/// Conforming refinement stops after this many sweeps over the interfaces (a
/// knot crosses at most one interface per sweep; more would mean a cycle that
/// keeps adding knots, which cannot happen with matched knot sets).
constexpr int max_sweeps = 64;

/// Parent directions of a side's own directions, in order.
std::vector<int> side_dirs(int n_par, Side side)
{
    std::vector<int> dirs;
    for (int d = 0; d < n_par; ++d)
        if (d != side_direction(side))
            dirs.push_back(d);
    return dirs;
}

/// Side grid sizes per own direction (a curve: {n, 1}).
std::array<int, 2> grid_size(const Patch& patch, Side side)
{
    const std::vector<int> dirs = side_dirs(patch.n_par(), side);
    std::array<int, 2> n{1, 1};
    for (std::size_t k = 0; k < dirs.size(); ++k)
        n[k] = patch.n_basis(dirs[k]);
    return n;
}

std::vector<SideOrientation> orientations(int q)
{
    std::vector<SideOrientation> out;
    if (q == 1) {
        out.push_back({{0, 1}, {false, false}});
        out.push_back({{0, 1}, {true, false}});
        return out;
    }
    for (const std::array<int, 2> dir : {std::array<int, 2>{0, 1}, std::array<int, 2>{1, 0}})
        for (int f = 0; f < 4; ++f)
            out.push_back({dir, {(f & 1) != 0, (f & 2) != 0}});
    return out;
}

/// Index in side b's grid of side a's grid point (i0, i1).
int mapped_index(const std::array<int, 2>& i, const SideOrientation& o, const std::array<int, 2>& nb, int q)
{
    std::array<int, 2> j{0, 0};
    for (int k = 0; k < q; ++k)
        j[o.dir[k]] = o.flip[k] ? nb[o.dir[k]] - 1 - i[k] : i[k];
    return j[0] + nb[0] * j[1];
}

bool corners_match(const SidePatch& a, const SidePatch& b, const std::array<int, 2>& na,
                   const std::array<int, 2>& nb, const SideOrientation& o, int q, double tol)
{
    for (int c = 0; c < (q == 1 ? 2 : 4); ++c) {
        // Corners by their flags: the grids may differ in size before conforming.
        const std::array<bool, 2> at_end{(c & 1) != 0, (c & 2) != 0};
        const int ia = (at_end[0] ? na[0] - 1 : 0) + na[0] * (at_end[1] ? na[1] - 1 : 0);
        std::array<int, 2> j{0, 0};
        for (int k = 0; k < q; ++k)
            j[o.dir[k]] = (at_end[k] != o.flip[k]) ? nb[o.dir[k]] - 1 : 0;
        const int ib = j[0] + nb[0] * j[1];
        if (!((a.patch.control_points().row(ia) - b.patch.control_points().row(ib)).norm() <= tol))
            return false;
    }
    return true;
}

/// Empty when every control point coincides and the weights are proportional, else why not.
std::string grids_differ(const SidePatch& a, const SidePatch& b, const std::array<int, 2>& na,
                         const std::array<int, 2>& nb, const SideOrientation& o, int q, double tol)
{
    for (int k = 0; k < q; ++k)
        if (na[k] != nb[o.dir[k]])
            return "they carry different numbers of control points (" + std::to_string(na[k]) + " and " +
                   std::to_string(nb[o.dir[k]]) + " along one direction)";
    double ratio = 0.0;
    for (int i1 = 0; i1 < na[1]; ++i1)
        for (int i0 = 0; i0 < na[0]; ++i0) {
            const int ia = i0 + na[0] * i1;
            const int ib = mapped_index({i0, i1}, o, nb, q);
            const double gap = (a.patch.control_points().row(ia) - b.patch.control_points().row(ib)).norm();
            if (!(gap <= tol))
                return "their control points do not coincide (" + std::to_string(gap) +
                       " apart after making the knots match): the sides are different curves or surfaces";
            const double wa = a.patch.weights()(ia), wb = b.patch.weights()(ib);
            if (ratio == 0.0)
                ratio = wb / wa;
            if (!(std::abs(wb - ratio * wa) <= weight_tolerance * wb))
                return "their weights are not proportional (the rational parametrizations differ)";
        }
    return {};
}

struct Knot {
    double t;
    int multiplicity;
};

/// Distinct interior knots of direction dir in normalized parameters.
std::vector<Knot> interior_knots(const Patch& patch, int dir, bool reversed)
{
    const KnotVector& kv = patch.knots(dir);
    const double front = kv.front(), range = kv.back() - kv.front();
    std::vector<Knot> out;
    const std::vector<double> breaks = kv.breakpoints();
    for (std::size_t k = 1; k + 1 < breaks.size(); ++k) {
        const double t = (breaks[k] - front) / range;
        out.push_back({reversed ? 1.0 - t : t, kv.multiplicity(breaks[k])});
    }
    return out;
}

/// Inserts into `patch` (direction dir) the knots of `wanted` it lacks or has
/// with a lower multiplicity. True when it changed.
bool insert_missing(Patch& patch, int dir, const std::vector<Knot>& wanted)
{
    const std::vector<Knot> have = interior_knots(patch, dir, false);
    const KnotVector& kv = patch.knots(dir);
    const double front = kv.front(), range = kv.back() - kv.front();
    std::vector<double> values;
    for (const Knot& w : wanted) {
        const auto it = std::find_if(have.begin(), have.end(),
                                     [&](const Knot& h) { return std::abs(h.t - w.t) <= knot_tolerance; });
        const int present = it == have.end() ? 0 : it->multiplicity;
        const double u = it == have.end() ? front + w.t * range : front + it->t * range;
        // An existing knot is inserted at its own value (breakpoints are exact).
        const double value = it == have.end() ? u : kv.breakpoints()[static_cast<std::size_t>(it - have.begin()) + 1];
        for (int m = present; m < w.multiplicity; ++m)
            values.push_back(value);
    }
    if (values.empty())
        return false;
    patch = insert_knots(patch, dir, values);
    return true;
}

/// One conforming pass over an interface candidate; true when a patch changed.
bool conform(Patch& a, Side sa, Patch& b, Side sb, const SideOrientation& o)
{
    bool changed = false;
    const std::vector<int> da = side_dirs(a.n_par(), sa), db = side_dirs(b.n_par(), sb);
    for (std::size_t k = 0; k < da.size(); ++k) {
        const int dir_a = da[k], dir_b = db[static_cast<std::size_t>(o.dir[k])];
        const int pa = a.degree(dir_a), pb = b.degree(dir_b);
        if (pa < pb) {
            a = elevate_degree(a, dir_a, pb - pa);
            changed = true;
        } else if (pb < pa) {
            b = elevate_degree(b, dir_b, pa - pb);
            changed = true;
        }
        const bool reversed = o.flip[k];
        changed = insert_missing(a, dir_a, interior_knots(b, dir_b, reversed)) || changed;
        changed = insert_missing(b, dir_b, interior_knots(a, dir_a, reversed)) || changed;
    }
    return changed;
}

struct Candidate {
    int pa;
    Side sa;
    int pb;
    Side sb;
    std::vector<SideOrientation> fits;  ///< orientations whose corners coincide
};

/// A non-collapsed side of a patch, extracted once.
struct SideRecord {
    int patch;
    Side name;
    std::array<int, 2> grid;
    SidePatch side;
};

/// Corner control points of a side grid (2 for a curve, 4 for a surface).
std::vector<int> corner_indices(const std::array<int, 2>& n, int q)
{
    if (q == 1)
        return {0, n[0] - 1};
    return {0, n[0] - 1, n[0] * (n[1] - 1), n[0] * n[1] - 1};
}

/// Cell size of the corner hash, as a fraction of the largest coordinate, when no
/// tolerance is given (exact coincidence): any size works, a small one keeps cells sparse.
constexpr double coincidence_cell = 1e-9;

using CellKey = std::array<long long, 3>;

struct CellKeyHash {
    std::size_t operator()(const CellKey& k) const
    {
        std::size_t h = 0;
        for (const long long v : k)
            h = h * 1000003u ^ std::hash<long long>()(v);
        return h;
    }
};

/// Cells of size h >= the coincidence tolerance: two points within h of each
/// other lie in the same cell or in neighbouring ones (3^d cells around a point).
class PointHash {
public:
    explicit PointHash(double h) : h_(h) {}
    CellKey key(const Eigen::Ref<const Eigen::RowVectorXd>& x) const
    {
        CellKey k{0, 0, 0};
        for (Index i = 0; i < x.size() && i < 3; ++i)  // clamped far inside the range of long long
            k[static_cast<std::size_t>(i)] = static_cast<long long>(std::clamp(std::floor(x(i) / h_), -1e18, 1e18));
        return k;
    }
    template <class Visit>
    void for_each_neighbour(const Eigen::Ref<const Eigen::RowVectorXd>& x, const Visit& visit) const
    {
        const CellKey centre = key(x);
        const int d = static_cast<int>(std::min<Index>(x.size(), 3));
        int n_cells = 1;
        for (int i = 0; i < d; ++i)
            n_cells *= 3;
        for (int c = 0; c < n_cells; ++c) {
            CellKey k = centre;
            for (int i = 0, r = c; i < d; ++i, r /= 3)
                k[static_cast<std::size_t>(i)] += r % 3 - 1;
            visit(k);
        }
    }

private:
    double h_;
};

int find_root(std::vector<int>& parent, int i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

}  // namespace

NonMatchingInterface::NonMatchingInterface(int pa, Side sa, int pb, Side sb, const std::string& reason)
    : Error(reason), patch_a(pa), patch_b(pb), side_a(sa), side_b(sb)
{
}

bool Topology::is_interface(int p, Side side) const
{
    return std::any_of(interfaces.begin(), interfaces.end(), [&](const Interface& i) {
        return (i.patch_a == p && i.side_a == side) || (i.patch_b == p && i.side_b == side);
    });
}

Topology glue_patches(std::vector<Patch>& patches, double tolerance, const StopRequest& stop)
{
    const int n_patches = static_cast<int>(patches.size());
    Topology topo;
    if (n_patches == 0)
        return topo;
    const int n_par = patches.front().n_par();
    const int q = n_par - 1;
    IGA_CHECK(n_par >= 2, "glue_patches: patches need at least 2 parametric directions");

    // Candidates from the corners (refinement keeps the corner control points):
    // every side's corners go into a hash of cells of size >= tolerance, and side a
    // meets only the sides with a corner in the cells around its first corner
    // (every orientation maps that corner onto a corner of the other side).
    std::vector<SideRecord> sides;
    for (int p = 0; p < n_patches; ++p) {
        stop.check();
        for (int s = 0; s < 2 * n_par; ++s) {
            SidePatch side = extract_side(patches[p], static_cast<Side>(s));
            if (is_collapsed(side, tolerance))
                continue;
            sides.push_back({p, static_cast<Side>(s), grid_size(patches[p], static_cast<Side>(s)), std::move(side)});
        }
    }
    double extent = 0.0;
    for (const Patch& patch : patches)
        extent = std::max(extent, patch.control_points().cwiseAbs().maxCoeff());
    const PointHash hash(tolerance > 0.0 ? tolerance : coincidence_cell * std::max(extent, 1.0));
    std::unordered_map<CellKey, std::vector<int>, CellKeyHash> corners;  // cell -> sides with a corner there
    for (std::size_t k = 0; k < sides.size(); ++k)
        for (const int c : corner_indices(sides[k].grid, q))
            corners[hash.key(sides[k].side.patch.control_points().row(c))].push_back(static_cast<int>(k));
    std::vector<Candidate> candidates;
    std::vector<int> near;
    for (std::size_t ka = 0; ka < sides.size(); ++ka) {
        stop.check();
        const SideRecord& a = sides[ka];
        near.clear();
        hash.for_each_neighbour(a.side.patch.control_points().row(0), [&](const CellKey& cell) {
            if (const auto it = corners.find(cell); it != corners.end())
                for (const int kb : it->second)
                    if (sides[static_cast<std::size_t>(kb)].patch > a.patch)
                        near.push_back(kb);
        });
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
        for (const int kb : near) {
            const SideRecord& b = sides[static_cast<std::size_t>(kb)];
            Candidate c{a.patch, a.name, b.patch, b.name, {}};
            for (const SideOrientation& o : orientations(q))
                if (corners_match(a.side, b.side, a.grid, b.grid, o, q, tolerance))
                    c.fits.push_back(o);
            if (!c.fits.empty())
                candidates.push_back(std::move(c));
        }
    }
    // Patch order, then side order: the order the pairwise search gave.
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
        return std::tuple(x.pa, x.sa, x.pb, x.sb) < std::tuple(y.pa, y.sa, y.pb, y.sb);
    });

    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        bool changed = false;
        for (const Candidate& c : candidates) {
            stop.check();
            changed = conform(patches[c.pa], c.sa, patches[c.pb], c.sb, c.fits.front()) || changed;
        }
        if (!changed)
            break;
    }

    for (const Candidate& c : candidates) {
        stop.check();
        const SidePatch a = extract_side(patches[c.pa], c.sa), b = extract_side(patches[c.pb], c.sb);
        const auto na = grid_size(patches[c.pa], c.sa), nb = grid_size(patches[c.pb], c.sb);
        std::string why;
        std::optional<SideOrientation> found;
        for (const SideOrientation& o : c.fits) {
            const std::string differ = grids_differ(a, b, na, nb, o, q, tolerance);
            if (differ.empty()) {
                found = o;
                break;
            }
            if (why.empty())
                why = differ;
        }
        if (!found)
            throw NonMatchingInterface(c.pa, c.sa, c.pb, c.sb, why);
        topo.interfaces.push_back({c.pa, c.sa, c.pb, c.sb, *found});
    }

    // Nodes: union of paired control points, numbered by first appearance.
    std::vector<int> offset(static_cast<std::size_t>(n_patches) + 1, 0);
    for (int p = 0; p < n_patches; ++p)
        offset[p + 1] = offset[p] + patches[p].n_control_points();
    std::vector<int> parent(static_cast<std::size_t>(offset.back()));
    std::iota(parent.begin(), parent.end(), 0);
    for (const Interface& i : topo.interfaces) {
        const SidePatch a = extract_side(patches[i.patch_a], i.side_a), b = extract_side(patches[i.patch_b], i.side_b);
        const auto na = grid_size(patches[i.patch_a], i.side_a), nb = grid_size(patches[i.patch_b], i.side_b);
        for (int i1 = 0; i1 < na[1]; ++i1)
            for (int i0 = 0; i0 < na[0]; ++i0) {
                const int ga = offset[i.patch_a] + a.parent_index[i0 + na[0] * i1];
                const int gb = offset[i.patch_b] + b.parent_index[mapped_index({i0, i1}, i.orientation, nb, q)];
                const int ra = find_root(parent, ga), rb = find_root(parent, gb);
                if (ra != rb)
                    parent[std::max(ra, rb)] = std::min(ra, rb);  // the earliest control point represents
            }
    }
    std::vector<int> node_of_root(parent.size(), -1);
    topo.node.resize(static_cast<std::size_t>(n_patches));
    for (int p = 0; p < n_patches; ++p) {
        topo.node[p].resize(static_cast<std::size_t>(patches[p].n_control_points()));
        for (int a = 0; a < patches[p].n_control_points(); ++a) {
            const int root = find_root(parent, offset[p] + a);
            if (node_of_root[root] < 0)
                node_of_root[root] = topo.n_nodes++;
            topo.node[p][a] = node_of_root[root];
        }
    }
    return topo;
}

namespace {

/// Element centre and four points near its corners (0.9 / 0.1 mixes): Newton's starts.
void nearest_sample(const Patch& patch, const Element& e, const VecN& x, VecN& best_xi, double& best)
{
    const int n = patch.n_par();
    for (int corner = 0; corner < (1 << n) + 1; ++corner) {
        VecN xi(n);
        for (int k = 0; k < n; ++k)
            xi(k) = corner == (1 << n) ? 0.5 * (e.lower[k] + e.upper[k])
                                       : ((corner >> k) & 1 ? 0.9 * e.upper[k] + 0.1 * e.lower[k]
                                                            : 0.9 * e.lower[k] + 0.1 * e.upper[k]);
        const double dist = (evaluate(patch, xi, 0).x - x).norm();
        if (dist < best) {
            best = dist;
            best_xi = xi;
        }
    }
}

/// Newton from xi for the parameter point whose image is x (see invert_point).
std::optional<VecN> invert_from(const Patch& patch, const VecN& x, double parameter_margin, VecN xi)
{
    const int n = patch.n_par();
    const RowMatrix& P = patch.control_points();
    const double size = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
    constexpr int max_iterations = 40;
    constexpr double relative_accuracy = 1e-11;  // of the patch size: converged far below any tolerance used
    for (int it = 0; it < max_iterations; ++it) {
        const PointDerivatives pd = evaluate(patch, xi, 1);
        const VecN r = x - pd.x;
        if (r.norm() <= relative_accuracy * size) {
            for (int k = 0; k < n; ++k) {
                const double lo = patch.knots(k).front(), hi = patch.knots(k).back();
                const double m = parameter_margin * (hi - lo);
                if (!(xi(k) > lo + m && xi(k) < hi - m))
                    return std::nullopt;
            }
            return xi;
        }
        const Eigen::FullPivLU<Matrix> lu(pd.dx);
        if (!lu.isInvertible())
            return std::nullopt;
        VecN step = lu.solve(r);
        for (int k = 0; k < n; ++k) {
            const double lo = patch.knots(k).front(), hi = patch.knots(k).back();
            step(k) = std::clamp(step(k), -0.5 * (hi - lo), 0.5 * (hi - lo));  // a trust region: half the range
            xi(k) = std::clamp(xi(k) + step(k), lo, hi);
        }
    }
    return std::nullopt;
}

}  // namespace

std::optional<VecN> invert_point(const Patch& patch, const VecN& x, double parameter_margin)
{
    IGA_CHECK(patch.n_par() == patch.dim(), "invert_point: the patch must be a solid (n_par = dim)");
    VecN best_xi(patch.n_par());
    double best = std::numeric_limits<double>::infinity();
    for (const Element& e : patch.elements())
        nearest_sample(patch, e, x, best_xi, best);
    return invert_from(patch, x, parameter_margin, best_xi);
}

std::optional<VecN> invert_point(const Patch& patch, const VecN& x, double parameter_margin, const Element& start)
{
    IGA_CHECK(patch.n_par() == patch.dim(), "invert_point: the patch must be a solid (n_par = dim)");
    VecN best_xi(patch.n_par());
    double best = std::numeric_limits<double>::infinity();
    nearest_sample(patch, start, x, best_xi, best);
    return invert_from(patch, x, parameter_margin, best_xi);
}

}  // namespace iga::nurbs
