#include "core/error.hpp"

namespace iga {

std::string DeckIssue::format() const
{
    std::string out = where.file.empty() ? std::string("<deck>") : where.file;
    // append() rather than operator+ on temporaries: GCC 12 warns falsely (-Wrestrict) on the latter.
    if (where.line > 0) {
        out.append(":").append(std::to_string(where.line));
        if (where.column > 0)
            out.append(":").append(std::to_string(where.column));
    }
    out.append(": error: ");
    if (!path.empty()) {
        out.append(path);
        if (!value.empty())
            out.append(" = ").append(value);
        out.append(": ");
    }
    out.append(reason);
    return out;
}

namespace {
std::string join(const std::vector<DeckIssue>& issues)
{
    std::string out;
    for (std::size_t i = 0; i < issues.size(); ++i) {
        if (i > 0)
            out += '\n';
        out += issues[i].format();
    }
    return out;
}
}  // namespace

DeckError::DeckError(std::vector<DeckIssue> issues) : std::runtime_error(join(issues)), issues_(std::move(issues)) {}

DeckError::DeckError(DeckIssue issue) : DeckError(std::vector<DeckIssue>{std::move(issue)}) {}

void raise_internal_error(const char* condition, const std::string& message, const char* file, int line)
{
    throw Error(std::string(file) + ":" + std::to_string(line) + ": internal error: " + message + " (" + condition +
                " failed)");
}

}  // namespace iga
