// The user's key reference agrees with the deck format: every key that `--set`
// knows (the schema of io/overrides.cpp, which a test in overrides_test.cpp holds
// to the resolved-deck writer, and the reader's round trip to the reader) is
// documented in docs/deck.md, spelled as code (`key`). A key added to the format
// without its documentation fails here.

#include "io/overrides.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace iga::io {
namespace {

std::string read_text(const std::string& path)
{
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(DeckDocs, EveryKeyOfTheFormatIsDocumentedInDeckMd)
{
    const std::string docs = read_text(std::string(IGA_SOURCE_DIR) + "/docs/deck.md");
    ASSERT_FALSE(docs.empty()) << "docs/deck.md not found";
    const std::vector<std::string> paths = deck_key_paths();
    ASSERT_GT(paths.size(), 50u);
    std::set<std::string> missing;
    for (const std::string& path : paths) {
        const std::string key = path.substr(path.rfind('.') + 1);
        // As code: `key`, `key:` or `{key: ...}` inside a code span or block.
        const bool documented = docs.find("`" + key + "`") != std::string::npos ||
                                docs.find("`" + key + ":") != std::string::npos ||
                                docs.find(" " + key + ": ") != std::string::npos ||
                                docs.find("{" + key + ": ") != std::string::npos;
        if (!documented)
            missing.insert(path);
    }
    std::string list;
    for (const std::string& path : missing)
        list += "\n  " + path;
    EXPECT_TRUE(missing.empty()) << "keys of the deck format that docs/deck.md does not mention:" << list;
}

}  // namespace
}  // namespace iga::io
