#pragma once
// Where a key path of a deck sits in its file, for errors found after reading
// (in analysis/: a patch that cannot be refined, a non-positive Jacobian,
// conflicting constraints): the same path syntax as --set (list items by name,
// else by index). Returns the deepest node of the path that exists, or the
// file alone (line 0) when the file cannot be read.

#include "core/error.hpp"

#include <string>

namespace iga::io {

SourceLocation locate(const std::string& deck_file, const std::string& path);

/// A DeckIssue located with locate().
DeckIssue located_issue(const std::string& deck_file, const std::string& path, const std::string& value,
                        const std::string& reason);

}  // namespace iga::io
