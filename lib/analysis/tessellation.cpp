#include "analysis/tessellation.hpp"

namespace iga::analysis {

namespace {

void tessellate_patch(const PatchModel& model, int patch_index, int per_span, TessellatedBody& out)
{
    const nurbs::Patch& patch = model.patch;
    const int n_par = patch.n_par();
    std::array<std::vector<double>, 3> params;
    for (int dir = 0; dir < n_par; ++dir) {
        const std::vector<double> breaks = patch.knots(dir).breakpoints();
        for (std::size_t s = 0; s + 1 < breaks.size(); ++s)
            for (int k = 0; k < per_span; ++k)
                params[static_cast<std::size_t>(dir)].push_back(breaks[s] + (breaks[s + 1] - breaks[s]) * k / per_span);
        params[static_cast<std::size_t>(dir)].push_back(breaks.back());
    }
    const int nu = static_cast<int>(params[0].size());
    const int nv = n_par > 1 ? static_cast<int>(params[1].size()) : 1;
    const int nw = n_par > 2 ? static_cast<int>(params[2].size()) : 1;

    const int first = static_cast<int>(out.mesh.points.rows());
    out.mesh.points.conservativeResize(first + static_cast<Index>(nu) * nv * nw, 3);
    out.mesh.points.bottomRows(static_cast<Index>(nu) * nv * nw).setZero();
    auto id = [&](int i, int j, int k) { return first + i + nu * (j + nv * k); };
    for (int k = 0; k < nw; ++k)
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                VecN xi(n_par);
                xi(0) = params[0][static_cast<std::size_t>(i)];
                if (n_par > 1)
                    xi(1) = params[1][static_cast<std::size_t>(j)];
                if (n_par > 2)
                    xi(2) = params[2][static_cast<std::size_t>(k)];
                const nurbs::BasisValues basis = nurbs::rational_basis(patch, xi, 0);
                VecN x = VecN::Zero(patch.dim());
                for (std::size_t a = 0; a < basis.indices.size(); ++a)
                    x += basis.R(static_cast<Index>(a)) * patch.control_points().row(basis.indices[a]).transpose();
                out.mesh.points.row(id(i, j, k)).head(patch.dim()) = x.transpose();
                std::vector<int> nodes = basis.indices;
                for (int& a : nodes)
                    a = model.node[static_cast<std::size_t>(a)];
                out.indices.push_back(std::move(nodes));
                out.R.push_back(basis.R);
                out.parameters.push_back(xi);
                out.patch.push_back(patch_index);
            }
    if (n_par == 2) {
        out.mesh.nodes_per_cell = 4;
        for (int j = 0; j + 1 < nv; ++j)
            for (int i = 0; i + 1 < nu; ++i)
                out.mesh.cells.insert(out.mesh.cells.end(),
                                      {id(i, j, 0), id(i + 1, j, 0), id(i + 1, j + 1, 0), id(i, j + 1, 0)});
    } else if (n_par == 3) {
        out.mesh.nodes_per_cell = 8;
        for (int k = 0; k + 1 < nw; ++k)
            for (int j = 0; j + 1 < nv; ++j)
                for (int i = 0; i + 1 < nu; ++i)
                    out.mesh.cells.insert(out.mesh.cells.end(),
                                          {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                           id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                                           id(i, j + 1, k + 1)});
    }
}

}  // namespace

TessellatedBody tessellate(const BodyModel& body, int per_span)
{
    TessellatedBody out;
    out.mesh.body = body.name;
    out.mesh.points = RowMatrix::Zero(0, 3);
    for (std::size_t p = 0; p < body.patches.size(); ++p)
        tessellate_patch(body.patches[p], static_cast<int>(p), per_span, out);
    return out;
}

RowMatrix tessellation_displacement(const TessellatedBody& t, const RowMatrix& u)
{
    RowMatrix out = RowMatrix::Zero(t.mesh.points.rows(), 3);
    for (std::size_t p = 0; p < t.indices.size(); ++p)
        for (std::size_t a = 0; a < t.indices[p].size(); ++a)
            out.row(static_cast<Index>(p)).head(u.cols()) +=
                t.R[p](static_cast<Index>(a)) * u.row(t.indices[p][a]);
    return out;
}

}  // namespace iga::analysis
