#include "io/gismo_xml.hpp"

#include "io/knot_checks.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string_view>

namespace iga::io {

namespace {

using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

/// The issues found in one XML file, all located in it.
class Issues {
public:
    explicit Issues(std::string file) : file_(std::move(file)) {}
    void add(int line, std::string path, std::string value, std::string reason)
    {
        issues_.push_back({{file_, line, 0}, std::move(path), std::move(value), std::move(reason)});
    }
    void throw_if_any() const
    {
        if (!issues_.empty())
            throw DeckError(issues_);
    }
    std::size_t count() const { return issues_.size(); }

private:
    std::string file_;
    std::vector<DeckIssue> issues_;
};

/// One whitespace-separated word of an element's text, with the line it sits on.
struct Word {
    std::string_view text;
    int line = 0;
};

/// The words of the text directly inside `e` (comments and child elements are skipped).
std::vector<Word> words(const XMLElement* e)
{
    std::vector<Word> out;
    for (const XMLNode* node = e->FirstChild(); node; node = node->NextSibling()) {
        if (!node->ToText())
            continue;
        const std::string_view text = node->Value();
        // tinyxml2 gives a text node the line of its first non-blank character
        // (XMLDocument::Identify); count from the text's first character instead.
        const std::size_t first = text.find_first_not_of(" \t\r\n");
        int line = node->GetLineNum() -
                   static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(
                                                                 first == std::string_view::npos ? 0 : first),
                                               '\n'));
        std::size_t i = 0;
        while (i < text.size()) {
            if (std::isspace(static_cast<unsigned char>(text[i]))) {
                line += text[i] == '\n';
                ++i;
                continue;
            }
            std::size_t j = i;
            while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j])))
                ++j;
            out.push_back({text.substr(i, j - i), line});
            i = j;
        }
    }
    return out;
}

std::optional<double> to_double(std::string_view text)
{
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

std::optional<int> to_int(std::string_view text)
{
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
        text.remove_prefix(1);
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.remove_suffix(1);
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty())
        return std::nullopt;
    return value;
}

/// A number read from an element's text, with its word (for messages) and line.
struct Number {
    double value = 0.0;
    Word word;
};

/// The numbers in the text of `e`, or nullopt after recording the first word that is not one.
std::optional<std::vector<Number>> numbers(const XMLElement* e, const std::string& path, Issues& issues)
{
    std::vector<Number> out;
    for (const Word& w : words(e)) {
        const auto value = to_double(w.text);
        if (!value) {
            issues.add(w.line, path, std::string(w.text), "not a finite number");
            return std::nullopt;
        }
        out.push_back({*value, w});
    }
    return out;
}

/// The integer attribute `name` of `e`: nullopt when absent (after recording it when
/// `required`) or not an integer (always recorded).
std::optional<int> int_attribute(const XMLElement* e, const char* name, const std::string& path, bool required,
                                 Issues& issues)
{
    const char* text = e->Attribute(name);
    if (!text) {
        if (required)
            issues.add(e->GetLineNum(), path, "", fmt::format("<{}> needs the attribute {}=\"...\"", e->Name(), name));
        return std::nullopt;
    }
    const auto value = to_int(text);
    if (!value)
        issues.add(e->GetLineNum(), path + "." + name, text, "not an integer");
    return value;
}

std::string join_words(const std::vector<std::string>& words)
{
    std::string out;
    for (const std::string& w : words)
        out += (out.empty() ? "" : ", ") + w;
    return out;
}

std::string element_type(const XMLElement* e)
{
    const char* type = e->Attribute("type");
    return type ? type : "";
}

/// The child <Basis> of `parent` whose type is `type`, or nullptr after recording that it is missing.
const XMLElement* basis_child(const XMLElement* parent, const std::string& type, const std::string& path,
                              Issues& issues)
{
    const XMLElement* basis = parent->FirstChildElement("Basis");
    if (!basis) {
        issues.add(parent->GetLineNum(), path, "", fmt::format("missing <Basis type=\"{}\">", type));
        return nullptr;
    }
    if (element_type(basis) != type) {
        issues.add(basis->GetLineNum(), path + ".Basis.type", element_type(basis),
                   fmt::format("expected <Basis type=\"{}\"> here", type));
        return nullptr;
    }
    return basis;
}

/// One supported <Geometry type=...>.
struct GeometryType {
    const char* name;
    int n_par;
    bool rational;
};
constexpr GeometryType geometry_types[] = {
    {"TensorBSpline2", 2, false}, {"TensorNurbs2", 2, true}, {"TensorBSpline3", 3, false}, {"TensorNurbs3", 3, true}};
constexpr const char* supported_types = "TensorBSpline2, TensorNurbs2, TensorBSpline3, TensorNurbs3";

/// Degree and knots of each direction of a tensor B-spline basis, or nullopt after recording why not.
std::optional<std::vector<std::pair<int, std::vector<double>>>> read_knot_vectors(const XMLElement* tensor, int n_par,
                                                                                 const std::string& path,
                                                                                 Issues& issues)
{
    const std::size_t before = issues.count();
    std::vector<const XMLElement*> directions(static_cast<std::size_t>(n_par), nullptr);
    int position = 0;
    for (const XMLElement* b = tensor->FirstChildElement("Basis"); b; b = b->NextSiblingElement("Basis"), ++position) {
        if (element_type(b) != "BSplineBasis") {
            issues.add(b->GetLineNum(), path + ".Basis.type", element_type(b),
                       "expected <Basis type=\"BSplineBasis\"> (one per parametric direction)");
            continue;
        }
        int index = position;
        if (b->Attribute("index")) {
            const auto i = int_attribute(b, "index", path + ".Basis", false, issues);
            if (!i)
                continue;
            index = *i;
        }
        if (index < 0 || index >= n_par) {
            issues.add(b->GetLineNum(), path + ".Basis.index", std::to_string(index),
                       fmt::format("a {}-parameter basis has directions 0 to {}", n_par, n_par - 1));
            continue;
        }
        if (directions[static_cast<std::size_t>(index)]) {
            issues.add(b->GetLineNum(), path + ".Basis.index", std::to_string(index),
                       fmt::format("direction {} given twice (first at line {})", index,
                                   directions[static_cast<std::size_t>(index)]->GetLineNum()));
            continue;
        }
        directions[static_cast<std::size_t>(index)] = b;
    }
    std::vector<std::pair<int, std::vector<double>>> out;
    for (int dir = 0; dir < n_par; ++dir) {
        const XMLElement* b = directions[static_cast<std::size_t>(dir)];
        const std::string kv_path = fmt::format("{}.KnotVector(index={})", path, dir);
        if (!b) {
            issues.add(tensor->GetLineNum(), kv_path, "",
                       fmt::format("missing the knot vector of direction {} (<Basis type=\"BSplineBasis\" "
                                   "index=\"{}\"><KnotVector degree=\"p\">...)",
                                   dir, dir));
            continue;
        }
        const XMLElement* kv = b->FirstChildElement("KnotVector");
        if (!kv) {
            issues.add(b->GetLineNum(), kv_path, "", "missing <KnotVector degree=\"p\">knots</KnotVector>");
            continue;
        }
        const auto degree = int_attribute(kv, "degree", kv_path, true, issues);
        if (!degree)
            continue;
        if (*degree < 1) {
            issues.add(kv->GetLineNum(), kv_path + ".degree", std::to_string(*degree), "must be >= 1");
            continue;
        }
        const auto knots = numbers(kv, kv_path, issues);
        if (!knots)
            continue;
        std::vector<double> u;
        for (const Number& n : *knots)
            u.push_back(n.value);
        for (const KnotProblem& problem : knot_vector_problems(u, *degree)) {
            if (problem.knot) {
                const Word& w = (*knots)[*problem.knot].word;
                issues.add(w.line, kv_path, std::string(w.text), problem.reason);
            } else {
                issues.add(kv->GetLineNum(), kv_path, "", problem.reason);
            }
        }
        out.emplace_back(*degree, std::move(u));
    }
    if (issues.count() != before)
        return std::nullopt;
    return out;
}

/// The patch of one <Geometry>, or nullopt after recording its problems.
std::optional<NurbsData> read_geometry(const XMLElement* g, const std::string& path, int dim, Issues& issues)
{
    const std::string type = element_type(g);
    const GeometryType* kind = nullptr;
    for (const GeometryType& t : geometry_types)
        if (type == t.name)
            kind = &t;
    if (!kind) {
        issues.add(g->GetLineNum(), path + ".type", type,
                   fmt::format("{} geometry type (supported: {})", type.empty() ? "missing" : "unsupported",
                               supported_types));
        return std::nullopt;
    }
    if (kind->n_par != dim) {
        issues.add(g->GetLineNum(), path + ".type", type,
                   fmt::format("a {}-parameter patch, but analysis.dimension is {} (a {}D deck takes {})", kind->n_par,
                               dim, dim, dim == 2 ? "TensorBSpline2, TensorNurbs2" : "TensorBSpline3, TensorNurbs3"));
        return std::nullopt;
    }
    const int n = kind->n_par;
    const std::string tensor_type = fmt::format("TensorBSplineBasis{}", n);
    const XMLElement* tensor = nullptr;
    const XMLElement* weights = nullptr;
    if (kind->rational) {
        const XMLElement* nurbs = basis_child(g, fmt::format("TensorNurbsBasis{}", n), path, issues);
        if (!nurbs)
            return std::nullopt;
        tensor = basis_child(nurbs, tensor_type, path + ".Basis", issues);
        weights = nurbs->FirstChildElement("weights");
        if (!weights)
            issues.add(nurbs->GetLineNum(), path + ".weights", "",
                       "missing <weights> (one per control point) beside the tensor B-spline basis");
        if (!tensor || !weights)
            return std::nullopt;
    } else {
        tensor = basis_child(g, tensor_type, path, issues);
        if (!tensor)
            return std::nullopt;
    }
    const auto knot_vectors = read_knot_vectors(tensor, n, path, issues);
    if (!knot_vectors)
        return std::nullopt;

    // The knot vectors imply the control point count; the file must hold that many
    // numbers. Nothing of that size is allocated before the count is checked against
    // what <coefs> actually holds (a few knots can imply billions of control points).
    NurbsData nurbs;
    std::size_t n_cp = 1;
    bool n_cp_overflows = false;
    std::string product;
    for (const auto& [degree, knots] : *knot_vectors) {
        const std::size_t n_basis = knots.size() - static_cast<std::size_t>(degree) - 1;  // >= p + 1: checked
        if (n_cp > std::numeric_limits<std::size_t>::max() / n_basis)
            n_cp_overflows = true;
        else
            n_cp *= n_basis;
        product += (product.empty() ? "" : " x ") + std::to_string(n_basis);
        nurbs.degrees.push_back(degree);
        nurbs.knots.push_back(knots);
    }

    const XMLElement* coefs = g->FirstChildElement("coefs");
    if (!coefs) {
        issues.add(g->GetLineNum(), path + ".coefs", "",
                   "missing <coefs geoDim=\"d\"> (the control points, first parameter fastest)");
        return std::nullopt;
    }
    const auto geo_dim = int_attribute(coefs, "geoDim", path + ".coefs", true, issues);
    if (!geo_dim)
        return std::nullopt;
    if (*geo_dim < dim || *geo_dim > 3) {
        issues.add(coefs->GetLineNum(), path + ".coefs.geoDim", std::to_string(*geo_dim),
                   *geo_dim < dim ? fmt::format("the control points have {} coordinates, but analysis.dimension is {}",
                                                *geo_dim, dim)
                                  : std::string("must be 2 or 3"));
        return std::nullopt;
    }
    const auto values = numbers(coefs, path + ".coefs", issues);
    if (!values)
        return std::nullopt;
    const std::size_t d = static_cast<std::size_t>(*geo_dim);
    if (n_cp_overflows || n_cp > values->size() / d || values->size() != n_cp * d) {
        issues.add(coefs->GetLineNum(), path + ".coefs", "",
                   n_cp_overflows
                       ? fmt::format("the knot vectors give {} control points, more than any file holds; got {} "
                                     "numbers",
                                     product, values->size())
                       : fmt::format("expected {} numbers ({} control points from the knot vectors, {} coordinates "
                                     "each), got {}",
                                     n_cp * d, product, d, values->size()));
        return std::nullopt;
    }

    const std::size_t before = issues.count();
    std::vector<double> w(n_cp, 1.0);  // n_cp <= the numbers in the file: checked above
    if (weights) {
        const auto weight_values = numbers(weights, path + ".weights", issues);
        if (weight_values && weight_values->size() != n_cp)
            issues.add(weights->GetLineNum(), path + ".weights", "",
                       fmt::format("expected {} weights ({} control points from the knot vectors), got {}", n_cp,
                                   product, weight_values->size()));
        else if (weight_values)
            for (std::size_t i = 0; i < n_cp; ++i) {
                const Number& v = (*weight_values)[i];
                if (!(v.value > 0))
                    issues.add(v.word.line, path + ".weights", std::string(v.word.text),
                               fmt::format("weight {} (control point {}) must be > 0", i + 1, i + 1));
                w[i] = v.value;
            }
    }
    static constexpr const char* axis = "xyz";
    for (std::size_t i = 0; i < n_cp; ++i) {
        std::vector<double> row;
        for (std::size_t k = 0; k < d; ++k) {
            const Number& c = (*values)[i * d + k];
            if (k < static_cast<std::size_t>(dim)) {
                row.push_back(c.value);
            } else if (c.value != 0.0) {
                issues.add(c.word.line, path + ".coefs", std::string(c.word.text),
                           fmt::format("control point {} has {} = {}: a geoDim {} geometry fits a {}D deck only "
                                       "when its extra coordinates are zero",
                                       i + 1, axis[k], c.value, d, dim));
                break;
            }
        }
        row.push_back(w[i]);
        nurbs.control_points.push_back(std::move(row));
    }
    if (issues.count() != before)
        return std::nullopt;
    return nurbs;
}

/// A <Geometry> at the top level of the file.
struct GeometryEntry {
    const XMLElement* element = nullptr;
    std::string name;  ///< p<id>
    std::string path;  ///< Geometry(id=...) for messages
};

/// The patch ids the <MultiPatch> lists (`file_ids`: the Geometry ids of the file), in its
/// order, each with the line that names it,
/// or nullopt after recording why not.
std::optional<std::vector<std::pair<int, int>>> multipatch_ids(const XMLElement* mp, int dim,
                                                               const std::map<int, std::size_t>& file_ids,
                                                               Issues& issues)
{
    const std::size_t before = issues.count();
    if (mp->Attribute("parDim"))
        if (const auto par_dim = int_attribute(mp, "parDim", "MultiPatch", false, issues); par_dim && *par_dim != dim)
            issues.add(mp->GetLineNum(), "MultiPatch.parDim", std::to_string(*par_dim),
                       fmt::format("a multi-patch of {}-parameter patches, but analysis.dimension is {}", *par_dim,
                                   dim));
    const XMLElement* patches = mp->FirstChildElement("patches");
    if (!patches) {
        issues.add(mp->GetLineNum(), "MultiPatch", "",
                   "missing <patches type=\"id_range\">first last</patches> (or type=\"id_index\" with a list of "
                   "ids)");
        return std::nullopt;
    }
    const std::string type = element_type(patches);
    if (type != "id_range" && type != "id_index") {
        issues.add(patches->GetLineNum(), "MultiPatch.patches.type", type,
                   "expected id_range (first last) or id_index (a list of Geometry ids)");
        return std::nullopt;
    }
    std::vector<std::pair<int, Word>> listed;
    for (const Word& w : words(patches)) {
        const auto id = to_int(w.text);
        if (!id) {
            issues.add(w.line, "MultiPatch.patches", std::string(w.text), "not an integer Geometry id");
            return std::nullopt;
        }
        listed.emplace_back(*id, w);
    }
    std::vector<std::pair<int, int>> ids;
    if (type == "id_range") {
        if (listed.size() != 2 || listed[0].first > listed[1].first) {
            issues.add(patches->GetLineNum(), "MultiPatch.patches", "",
                       "id_range takes two ids, first <= last (both included)");
            return std::nullopt;
        }
        // 64-bit: `last` may be INT_MAX, where an int counter would overflow. A range
        // longer than the file's list of ids stops at its first id not in the file
        // (reported by the caller): nothing of the range's size is built.
        const long long first = listed[0].first, last = listed[1].first;
        const bool too_long = last - first + 1 > static_cast<long long>(file_ids.size());
        for (long long id = first; id <= last; ++id) {
            ids.emplace_back(static_cast<int>(id), patches->GetLineNum());
            if (too_long && file_ids.count(static_cast<int>(id)) == 0)
                break;
        }
    } else {
        if (listed.empty())
            issues.add(patches->GetLineNum(), "MultiPatch.patches", "", "id_index lists no Geometry id");
        std::set<int> seen;  // a set: a long list must not take quadratic time
        for (const auto& [id, w] : listed) {
            if (!seen.insert(id).second)
                issues.add(w.line, "MultiPatch.patches", std::string(w.text), "Geometry id listed twice");
            ids.emplace_back(id, w.line);
        }
    }
    if (issues.count() != before)
        return std::nullopt;
    return ids;
}

/// Why `path` cannot be read as a file, checked before opening it (a FIFO would
/// block the reader); "" for a regular file.
std::string not_a_file(const std::string& path)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // follows symbolic links
    switch (status.type()) {
    case fs::file_type::regular: return {};
    case fs::file_type::not_found: return "no such file";
    case fs::file_type::directory: return "it is a folder, not a file";
    case fs::file_type::fifo: return "it is a FIFO (named pipe), not a file";
    case fs::file_type::character:
    case fs::file_type::block: return "it is a device, not a file";
    case fs::file_type::socket: return "it is a socket, not a file";
    default: return ec ? ec.message() : std::string("not a regular file");
    }
}

std::string describe_parse_error(const XMLDocument& doc)
{
    // ErrorStr() reads "Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=14 (0xe) Line number=7: XMLElement name=coefs";
    // keep the error name and the detail after the line number.
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : "";
    const auto colon = detail.find(": ");
    detail = colon == std::string::npos ? std::string() : detail.substr(colon + 2);
    std::string name = XMLDocument::ErrorIDToName(doc.ErrorID());
    if (name.rfind("XML_ERROR_", 0) == 0)
        name = name.substr(10);
    for (char& c : name)
        c = c == '_' ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return "not well-formed XML (" + name + (detail.empty() ? "" : ": " + detail) + ")";
}

}  // namespace

std::vector<ImportedPatch> read_gismo_xml(const std::string& path, int dimension)
{
    Issues issues(path);
    if (const std::string problem = not_a_file(path); !problem.empty()) {
        issues.add(0, "", "", "cannot read the G+Smo XML file: " + problem);
        issues.throw_if_any();
    }
    XMLDocument doc;  // whitespace preserved: line numbers inside texts stay exact
    const auto status = doc.LoadFile(path.c_str());
    if (status == tinyxml2::XML_ERROR_FILE_NOT_FOUND || status == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED ||
        status == tinyxml2::XML_ERROR_FILE_READ_ERROR) {
        issues.add(0, "", "", "cannot read the G+Smo XML file");
        issues.throw_if_any();
    }
    if (status != tinyxml2::XML_SUCCESS) {
        issues.add(doc.ErrorLineNum(), "", "", describe_parse_error(doc));
        issues.throw_if_any();
    }
    const XMLElement* root = doc.RootElement();
    if (!root) {
        issues.add(1, "", "", "not a G+Smo XML file: no root element (expected <xml>)");
        issues.throw_if_any();
    }
    if (std::strcmp(root->Name(), "xml") != 0) {
        issues.add(root->GetLineNum(), "", "",
                   fmt::format("not a G+Smo XML file: the root element is <{}>, expected <xml>", root->Name()));
        issues.throw_if_any();
    }

    std::vector<GeometryEntry> geometries;
    std::map<int, std::size_t> by_id;
    for (const XMLElement* g = root->FirstChildElement("Geometry"); g; g = g->NextSiblingElement("Geometry")) {
        const std::size_t position = geometries.size();
        int id = static_cast<int>(position);
        if (g->Attribute("id")) {
            const auto value = int_attribute(g, "id", fmt::format("Geometry({})", position + 1), false, issues);
            if (!value)
                continue;
            id = *value;
        }
        const std::string path_here = fmt::format("Geometry(id={})", id);
        if (const auto it = by_id.find(id); it != by_id.end()) {
            issues.add(g->GetLineNum(), path_here, "",
                       fmt::format("duplicate Geometry id {} (first at line {})", id,
                                   geometries[it->second].element->GetLineNum()));
            continue;
        }
        by_id.emplace(id, position);
        geometries.push_back({g, fmt::format("p{}", id), path_here});
    }

    std::vector<std::size_t> selected;
    const XMLElement* mp = root->FirstChildElement("MultiPatch");
    if (mp) {
        if (const XMLElement* second = mp->NextSiblingElement("MultiPatch"))
            issues.add(second->GetLineNum(), "MultiPatch", "",
                       fmt::format("a second <MultiPatch> (the first is at line {}): a body reads one multi-patch",
                                   mp->GetLineNum()));
        if (const auto ids = multipatch_ids(mp, dimension, by_id, issues)) {
            std::vector<std::string> known;
            for (const auto& [id, position] : by_id)
                known.push_back(std::to_string(id));
            for (const auto& [id, line] : *ids) {
                const auto it = by_id.find(id);
                if (it == by_id.end())
                    issues.add(line, "MultiPatch.patches", std::to_string(id),
                               fmt::format("no <Geometry id=\"{}\"> in the file (Geometry ids: {})", id,
                                           known.empty() ? std::string("none") : join_words(known)));
                else
                    selected.push_back(it->second);
            }
        }
    } else {
        for (std::size_t i = 0; i < geometries.size(); ++i)
            selected.push_back(i);
        if (geometries.empty() && issues.count() == 0)
            issues.add(root->GetLineNum(), "", "", "no <Geometry> element in the file");
    }

    std::vector<ImportedPatch> patches;
    for (std::size_t i : selected) {
        const GeometryEntry& entry = geometries[i];
        if (auto nurbs = read_geometry(entry.element, entry.path, dimension, issues))
            patches.push_back({entry.name, std::move(*nurbs), entry.element->GetLineNum()});
    }
    issues.throw_if_any();
    return patches;
}

}  // namespace iga::io
