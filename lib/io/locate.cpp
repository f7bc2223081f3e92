#include "io/locate.hpp"

#include <yaml-cpp/yaml.h>

#include <sstream>

namespace iga::io {

namespace {

std::vector<std::string> split(const std::string& path)
{
    std::vector<std::string> parts;
    std::stringstream in(path);
    std::string part;
    while (std::getline(in, part, '.'))
        if (!part.empty())
            parts.push_back(part);
    return parts;
}

SourceLocation at(const std::string& file, const YAML::Node& node)
{
    const YAML::Mark mark = node.Mark();
    if (mark.line < 0)
        return {file, 0, 0};
    return {file, mark.line + 1, mark.column + 1};  // yaml-cpp marks are 0-based
}

}  // namespace

SourceLocation locate(const std::string& deck_file, const std::string& path)
{
    YAML::Node node;
    try {
        node = YAML::LoadFile(deck_file);
    } catch (const std::exception&) {
        return {deck_file, 0, 0};
    }
    SourceLocation best = {deck_file, 0, 0};
    for (const std::string& part : split(path)) {
        // Read through a const view: non-const operator[] may insert into the tree.
        const YAML::Node& view = node;
        YAML::Node next;
        bool found = false;
        if (view.IsMap()) {
            const YAML::Node child = view[part];  // invalid (not throwing) when absent
            if (child.IsDefined()) {
                next.reset(child);
                found = true;
            }
        } else if (view.IsSequence()) {
            for (const YAML::Node& item : view)
                if (item.IsMap() && item["name"] && item["name"].IsScalar() && item["name"].Scalar() == part) {
                    next.reset(item);
                    found = true;
                    break;
                }
            if (!found) {
                try {
                    const std::size_t index = std::stoul(part);
                    if (index < view.size()) {
                        next.reset(view[index]);
                        found = true;
                    }
                } catch (const std::exception&) {
                }
            }
        }
        if (!found)
            break;
        node.reset(next);  // Node::operator= would assign into the tree (yaml-cpp reference semantics)
        best = at(deck_file, node);
    }
    return best;
}

DeckIssue located_issue(const std::string& deck_file, const std::string& path, const std::string& value,
                        const std::string& reason)
{
    return DeckIssue{locate(deck_file, path), path, value, reason};
}

}  // namespace iga::io
