// The user's key reference agrees with the deck format: the key tables of
// docs/deck.md are what the deck schema (lib/io/deck_schema.cpp) generates, and
// every key of the schema is in one of them. A key added to the schema without
// regenerating the docs fails here, with the command that regenerates them.

#include "io/deck_key_tables.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace iga::io {
namespace {

std::string read_text(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The 1-based number of the first line where `a` and `b` differ, with both lines.
std::string first_difference(const std::string& a, const std::string& b)
{
    std::istringstream in_a(a), in_b(b);
    std::string line_a, line_b;
    for (int line = 1;; ++line) {
        const bool more_a = static_cast<bool>(std::getline(in_a, line_a));
        const bool more_b = static_cast<bool>(std::getline(in_b, line_b));
        if (!more_a && !more_b)
            return "(they differ only in the final line break)";
        if (!more_a || !more_b || line_a != line_b)
            return "line " + std::to_string(line) + ":\n  docs/deck.md: " + (more_a ? line_a : "(end of file)") +
                   "\n  generated:    " + (more_b ? line_b : "(end of file)");
    }
}

TEST(DeckDocs, KeyTablesAreGeneratedFromTheSchema)
{
    const std::string docs = read_text(std::string(IGA_SOURCE_DIR) + "/docs/deck.md");
    ASSERT_FALSE(docs.empty()) << "docs/deck.md not found";
    const KeyTables tables = generate_key_tables(docs);
    EXPECT_GE(tables.tables.size(), 15u);
    EXPECT_TRUE(tables.markdown == docs)
        << "the key tables of docs/deck.md differ from what the deck schema (lib/io/deck_schema.cpp) generates, "
           "first at "
        << first_difference(docs, tables.markdown)
        << "\nRegenerate them (after building): /usr/bin/python3 scripts/update_deck_tables.py";
    std::string missing;
    for (const std::string& path : tables.undocumented)
        missing += "\n  " + path;
    EXPECT_TRUE(tables.undocumented.empty())
        << "keys of the deck schema that no table of docs/deck.md shows (add a '<!-- keys: MAP -->' table):"
        << missing;
}

TEST(DeckDocs, ATableShowsTheKeysOfMapsThatHaveNoTableOfTheirOwn)
{
    const std::string one = "# Steps\n<!-- keys: steps -->\nold text\n<!-- /keys -->\nprose\n";
    const KeyTables t = generate_key_tables(one);
    const std::string head = "# Steps\n<!-- keys: steps -->\n\n| key | type | default | meaning |\n|---|---|---|---|\n"
                             "| `count` | integer ≥ 1 | `1` | initial number of increments.";
    EXPECT_EQ(t.markdown.rfind(head, 0), 0u) << t.markdown;
    EXPECT_NE(t.markdown.find("| `max_cutbacks` | integer ≥ 0 | `8` |"), std::string::npos);
    EXPECT_NE(t.markdown.find("\n<!-- /keys -->\nprose\n"), std::string::npos);
    EXPECT_EQ(t.tables, std::vector<std::string>{"steps"});

    // contact.* alone shows friction.coefficient; with a table of its own, friction is one row.
    const std::string contact = "<!-- keys: contact.* -->\n<!-- /keys -->\n";
    EXPECT_NE(generate_key_tables(contact).markdown.find("| `friction.coefficient` |"), std::string::npos);
    const std::string both = contact + "<!-- keys: contact.*.friction -->\n<!-- /keys -->\n";
    const std::string generated = generate_key_tables(both).markdown;
    EXPECT_EQ(generated.find("| `friction.coefficient` |"), std::string::npos);
    EXPECT_NE(generated.find("| `friction` |"), std::string::npos);
    EXPECT_NE(generated.find("| `coefficient` |"), std::string::npos);
    // A group is documented once for all its places.
    const std::string patches = "<!-- keys: bodies.*.patches.* -->\n<!-- /keys -->\n";
    EXPECT_NE(generate_key_tables(patches).markdown.find("| `nurbs.degrees` |"), std::string::npos);
    const std::string with_nurbs = patches + "<!-- keys: bodies.*.nurbs -->\n<!-- /keys -->\n";
    EXPECT_EQ(generate_key_tables(with_nurbs).markdown.find("| `nurbs.degrees` |"), std::string::npos);
}

TEST(DeckDocs, BadMarkersAreReportedWithTheirLine)
{
    const auto error_of = [](const std::string& markdown) {
        try {
            generate_key_tables(markdown);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    EXPECT_EQ(error_of("text\n<!-- keys: stepz -->\n<!-- /keys -->\n"),
              "line 2: 'stepz' names no map of the deck schema (io/deck_schema.hpp)");
    EXPECT_EQ(error_of("<!-- keys: steps.count -->\n<!-- /keys -->\n"),
              "line 1: 'steps.count' names no map of the deck schema (io/deck_schema.hpp)");
    EXPECT_EQ(error_of("<!-- keys: contact -->\n<!-- /keys -->\n"),
              "line 1: 'contact' names no map of the deck schema (io/deck_schema.hpp)");  // a list: contact.*
    EXPECT_EQ(error_of("<!-- keys: steps -->\nno end\n"), "line 1: no '<!-- /keys -->' after the table");
    EXPECT_EQ(error_of("<!-- keys: steps -->\n<!-- keys: newton -->\n"),
              "line 2: a table opens inside the table opened at line 1");
    EXPECT_EQ(error_of("<!-- /keys -->\n"), "line 1: '<!-- /keys -->' without a '<!-- keys: MAP -->' before it");
    EXPECT_EQ(error_of("no tables\n"), "accepted");
}

}  // namespace
}  // namespace iga::io
