// `igacontact keys [--markdown FILE]`: the keys of the deck format, from the deck
// schema (io/deck_schema.hpp). A tool of the documentation, not listed in --help:
//
//   igacontact keys                   every key path with its type and default
//   igacontact keys --markdown FILE   FILE with its marked key tables generated, on
//                                     stdout (io/deck_key_tables.hpp); what
//                                     scripts/update_deck_tables.py writes to docs/deck.md

#include "commands.hpp"

#include "io/deck_key_tables.hpp"
#include "io/deck_schema.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace iga::app {

int keys_command(int argc, char** argv)
{
    CLI::App cli{"List the keys of the deck format, or print a markdown file with its key tables generated.",
                 "igacontact keys"};
    std::string markdown;
    cli.add_option("--markdown", markdown, "a markdown file with <!-- keys: MAP --> tables (docs/deck.md)");
    if (const int code = parse_command_line(cli, argc, argv); code >= 0)
        return code;

    if (markdown.empty()) {
        for (const io::DeckKey& key : io::deck_keys())
            std::cout << fmt::format("{}  [{}]  default: {}\n", key.path, key.type_text, key.default_text);
        return exit_ok;
    }
    std::ifstream in(markdown, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in)
        throw UsageError("cannot read " + markdown);
    io::KeyTables tables;
    try {
        tables = io::generate_key_tables(text.str());
    } catch (const std::invalid_argument& e) {
        throw UsageError(markdown + ": " + e.what());
    }
    std::cout << tables.markdown;
    for (const std::string& path : tables.undocumented)
        std::cerr << "warning: no table of " << markdown << " shows the key " << path << '\n';
    return exit_ok;
}

}  // namespace iga::app
