#include "io/xdmf_writer.hpp"

#include "core/error.hpp"
#include "io/results_writer.hpp"

#include <fmt/format.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace iga::io {

namespace {

std::string item(const std::string& h5, const std::string& path, const std::string& dims, bool integer)
{
    return fmt::format("<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}</DataItem>",
                       dims, integer ? "Int" : "Float", integer ? 4 : 8, h5, path);
}

/// Column `k` of an n_rows x n_cols float dataset, as an XDMF HyperSlab (start, stride, count).
std::string column(const std::string& h5, const std::string& path, long long n_rows, int n_cols, int k)
{
    return fmt::format("<DataItem ItemType=\"HyperSlab\" Dimensions=\"{0} 1\" Type=\"HyperSlab\">\n"
                       "       <DataItem Dimensions=\"3 2\" NumberType=\"Int\" Format=\"XML\">0 {1} 1 1 {0} 1</DataItem>\n"
                       "       {2}\n      </DataItem>",
                       n_rows, k, item(h5, path, fmt::format("{} {}", n_rows, n_cols), false));
}

/// Rows [first, first + count) of an n_rows x n_cols float dataset (n_cols = 0: a
/// 1-D dataset of length n_rows), as an XDMF HyperSlab.
std::string rows(const std::string& h5, const std::string& path, long long n_rows, int n_cols, long long first,
                 long long count)
{
    if (n_cols == 0)
        return fmt::format("<DataItem ItemType=\"HyperSlab\" Dimensions=\"{0}\" Type=\"HyperSlab\">\n"
                           "       <DataItem Dimensions=\"3 1\" NumberType=\"Int\" Format=\"XML\">{1} 1 {0}</DataItem>\n"
                           "       {2}\n      </DataItem>",
                           count, first, item(h5, path, std::to_string(n_rows), false));
    return fmt::format("<DataItem ItemType=\"HyperSlab\" Dimensions=\"{0} {3}\" Type=\"HyperSlab\">\n"
                       "       <DataItem Dimensions=\"3 2\" NumberType=\"Int\" Format=\"XML\">{1} 0 1 1 {0} {3}</DataItem>\n"
                       "       {2}\n      </DataItem>",
                       count, first, item(h5, path, fmt::format("{} {}", n_rows, n_cols), false), n_cols);
}

/// The topology of a sample grid of n_v x n_u points: a structured surface, or a
/// polyline when n_v == 1 (a curve).
std::string sample_topology(long long n_v, long long n_u)
{
    if (n_v > 1 && n_u > 1)
        return fmt::format("     <Topology TopologyType=\"2DSMesh\" Dimensions=\"{} {}\"/>\n", n_v, n_u);
    return fmt::format("     <Topology TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"{}\"/>\n",
                       n_u * n_v);
}

/// The components of an n x d tangential traction dataset, one scalar attribute each.
std::string traction_components(const std::string& h5, const std::string& path, long long n, int d)
{
    std::string out;
    for (int k = 0; k < d; ++k)
        out += fmt::format("     <Attribute Name=\"tangential_traction_{}\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                           "      {}\n     </Attribute>\n",
                           "xyz"[k], column(h5, path, n, d, k));
    return out;
}

/// Column order of fields/<body>/stress (results.md).
constexpr std::array<const char*, 6> stress_components = {"xx", "yy", "zz", "xy", "yz", "xz"};

std::string escape(const std::string& s)
{
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

}  // namespace

std::string xdmf_text(const std::string& h5_name, const std::vector<XdmfMesh>& meshes,
                      const std::vector<XdmfStep>& steps)
{
    const std::string h5 = escape(h5_name);
    std::string out = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
                      "  <Grid Name=\"increments\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const XdmfStep& step : steps) {
        const std::string group = "/steps/" + step_group_name(step.index);
        out += fmt::format("   <Grid Name=\"increment {}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
                           "    <Time Value=\"{:.17g}\"/>\n",
                           step.index, step.load_factor);
        for (const XdmfMesh& mesh : meshes) {
            const std::string body = escape(mesh.body);
            out += fmt::format("    <Grid Name=\"{}\" GridType=\"Uniform\">\n", body);
            out += fmt::format("     <Topology TopologyType=\"{}\" NumberOfElements=\"{}\">\n      {}\n     </Topology>\n",
                               mesh.nodes_per_cell == 8 ? "Hexahedron" : "Quadrilateral", mesh.n_cells,
                               item(h5, "/paraview/" + body + "/cells",
                                    fmt::format("{} {}", mesh.n_cells, mesh.nodes_per_cell), true));
            out += fmt::format("     <Geometry GeometryType=\"XYZ\">\n      {}\n     </Geometry>\n",
                               item(h5, "/paraview/" + body + "/points", fmt::format("{} 3", mesh.n_points), false));
            out += fmt::format("     <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n"
                               "      {}\n     </Attribute>\n",
                               item(h5, group + "/paraview/" + body + "/displacement",
                                    fmt::format("{} 3", mesh.n_points), false));
            if (mesh.fields) {
                const std::string fields = group + "/fields/" + body;
                for (std::size_t k = 0; k < stress_components.size(); ++k)
                    out += fmt::format("     <Attribute Name=\"stress_{}\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                                       "      {}\n     </Attribute>\n",
                                       stress_components[k], column(h5, fields + "/stress", mesh.n_points, 6,
                                                                    static_cast<int>(k)));
                out += fmt::format("     <Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                                   "      {}\n     </Attribute>\n",
                                   item(h5, fields + "/von_mises", std::to_string(mesh.n_points), false));
            }
            out += "    </Grid>\n";
        }
        for (const XdmfContactSide& side : step.sides) {
            const std::string g = escape(side.group);
            const std::string geometry = side.dim == 3 ? "XYZ" : "XY";
            out += fmt::format("    <Grid Name=\"{} gauss points\" GridType=\"Uniform\">\n", escape(side.label));
            out += fmt::format("     <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\" NodesPerElement=\"1\"/>\n",
                               side.n_gauss);
            out += fmt::format("     <Geometry GeometryType=\"{}\">\n      {}\n     </Geometry>\n", geometry,
                               item(h5, g + "/gauss_points/coordinates", fmt::format("{} {}", side.n_gauss, side.dim),
                                    false));
            for (const char* name : {"pressure", "gap"})
                out += fmt::format("     <Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"Node\">\n      {}\n"
                                   "     </Attribute>\n",
                                   name, item(h5, g + "/gauss_points/" + name, std::to_string(side.n_gauss), false));
            if (side.friction) {
                out += fmt::format("     <Attribute Name=\"status\" AttributeType=\"Scalar\" Center=\"Node\">\n      {}\n"
                                   "     </Attribute>\n",
                                   item(h5, g + "/gauss_points/status", std::to_string(side.n_gauss), true));
                for (const char* name : {"slip", "slip_increment"})
                    out += fmt::format("     <Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"Node\">\n      {}\n"
                                       "     </Attribute>\n",
                                       name, item(h5, g + "/gauss_points/" + name, std::to_string(side.n_gauss), false));
                out += traction_components(h5, g + "/gauss_points/tangential_traction_vector", side.n_gauss, side.dim);
            }
            out += "    </Grid>\n";
            if (!side.patch_grids.empty()) {  // one sample grid per patch side, rows in storage order
                long long first = 0;
                for (std::size_t k = 0; k < side.patch_grids.size(); ++k) {
                    const auto [n_v, n_u] = side.patch_grids[k];
                    const std::string name = k < side.patch_sides.size() ? side.patch_sides[k] : std::to_string(k);
                    out += fmt::format("    <Grid Name=\"{} post-processed {}\" GridType=\"Uniform\">\n",
                                       escape(side.label), escape(name));
                    out += sample_topology(n_v, n_u);
                    out += fmt::format("     <Geometry GeometryType=\"{}\">\n      {}\n     </Geometry>\n", geometry,
                                       rows(h5, g + "/postprocessed/coordinates", side.n_samples, side.dim, first,
                                            n_v * n_u));
                    out += fmt::format("     <Attribute Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Node\">\n"
                                       "      {}\n     </Attribute>\n    </Grid>\n",
                                       rows(h5, g + "/postprocessed/pressure", side.n_samples, 0, first, n_v * n_u));
                    first += n_v * n_u;
                }
                continue;
            }
            out += fmt::format("    <Grid Name=\"{} post-processed\" GridType=\"Uniform\">\n", escape(side.label));
            if (side.n_u > 0 && side.n_v > 0 && side.n_u * side.n_v == side.n_samples)  // a face: structured surface
                out += fmt::format("     <Topology TopologyType=\"2DSMesh\" Dimensions=\"{} {}\"/>\n", side.n_v,
                                   side.n_u);
            else
                out += fmt::format(
                    "     <Topology TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"{}\"/>\n",
                    side.n_samples);
            out += fmt::format("     <Geometry GeometryType=\"{}\">\n      {}\n     </Geometry>\n", geometry,
                               item(h5, g + "/postprocessed/coordinates",
                                    fmt::format("{} {}", side.n_samples, side.dim), false));
            out += fmt::format("     <Attribute Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Node\">\n      {}\n"
                               "     </Attribute>\n",
                               item(h5, g + "/postprocessed/pressure", std::to_string(side.n_samples), false));
            if (side.friction)
                out += traction_components(h5, g + "/postprocessed/tangential_traction_vector", side.n_samples, side.dim);
            out += "    </Grid>\n";
        }
        out += "   </Grid>\n";
    }
    out += "  </Grid>\n </Domain>\n</Xdmf>\n";
    return out;
}

void write_xdmf(const std::string& path, const std::string& text)
{
    const std::string temp = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream file(temp, std::ios::binary | std::ios::trunc);
        if (!file)
            throw StorageError("cannot write the ParaView index " + path + ": " + std::strerror(errno) +
                               " (the results file beside it is complete)");
        file << text;
        file.close();
        if (!file) {
            const int error = errno;
            std::remove(temp.c_str());
            throw StorageError("cannot write the ParaView index " + path + ": " + std::strerror(error) +
                               " (the results file beside it is complete)");
        }
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        std::remove(temp.c_str());
        throw Error("cannot rename the ParaView file onto " + path);
    }
}

}  // namespace iga::io
