#pragma once
// Reading the `bodies` entries of a deck (deformable NURBS patches, built-in
// shapes, refinement, rigid obstacles: docs/deck.md "bodies"), and the name
// bookkeeping that the later sections check their references against.
//
// Part of the deck reader (deck_reader.cpp); internal to io/. Checks made here:
// knot vectors open, non-decreasing, interior multiplicity <= degree;
// control-point count = prod(n_knots - degree - 1) with rows [x, y, (z,) w],
// w > 0; refine lists with one entry per parametric direction; inserted knots
// strictly inside the parameter interval; rigid plane normals of non-zero
// length (normalized here); `transform:` lists (io/transform_reader.hpp).

#include "io/deck.hpp"
#include "io/yaml_cursor.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace iga::io {

/// The patch and surface names of a deformable body, what side references are checked against.
struct BodyParts {
    bool multi_patch = false;
    bool unknown = false;  ///< its geometry file could not be read: side references are not checked
    std::vector<std::string> patches;
    std::vector<std::string> surfaces;
};

/// Names defined by the sections read so far.
struct KnownNames {
    int dim = 0;  ///< analysis.dimension once valid, else 0
    std::string deck_dir;  ///< folder of the deck: relative file names are relative to it
    std::vector<std::string> materials;
    std::vector<std::pair<std::string, bool>> bodies;  ///< name, is rigid
    std::vector<std::pair<std::string, BodyParts>> parts;  ///< deformable bodies only
    std::vector<std::string> pairs;

    const std::pair<std::string, bool>* find_body(const std::string& name) const;
    const BodyParts* find_parts(const std::string& name) const;
    std::vector<std::string> body_names() const;
};

/// A side reference of a deformable body as read: a side, patch.side or a named surface.
struct SideReference {
    std::string patch;
    Side side = Side::u0;
    std::string surface;
};

/// Parses `text` as a side of deformable body `body`: a named surface of it, else
/// `patch.side` (multi-patch bodies) or `side` (single-patch bodies). Records an
/// issue at `at` (unknown patch, unknown surface, ...) and returns nullopt when it is none.
std::optional<SideReference> side_reference(const Cursor& at, const std::string& text, const std::string& body,
                                            const KnownNames& known);

/// Keeps the item names of one list unique.
class NameRegistry {
public:
    explicit NameRegistry(std::string what) : what_(std::move(what)) {}
    /// Records "duplicate <what> name" at `at` and returns false when `name` is taken.
    bool add(const std::string& name, const Cursor& at);

private:
    std::string what_;
    std::vector<std::pair<std::string, SourceLocation>> seen_;
};

/// The required `name` of a list item: a non-empty word without '.' (the
/// separator of key paths and of `body.side`).
std::optional<std::string> read_name(const Cursor& item);

/// Side names of a dim-D patch: u0, u1, v0, v1 (, w0, w1).
std::vector<std::string> side_names(int dim);
/// `text` as a side of a dim-D patch; records an issue at `at` if it is not one.
std::optional<Side> side_from_text(const Cursor& at, const std::string& text, int dim);

/// Reads the patches of a G+Smo XML geometry file (io/gismo_xml.hpp) of a dim-D
/// deck into `body.patches`, named p<id>; records an issue at `at` (with the
/// file's own located messages) when it cannot.
void read_geometry_file(const Cursor& at, const std::string& path, int dim, Body& body);

/// One entry of `bodies` (known.dim must be valid); registers its name in `known`.
Body read_body(const Cursor& c, KnownNames& known, NameRegistry& names);

}  // namespace iga::io
