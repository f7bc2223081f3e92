#!/usr/bin/python3
"""Regenerate the key tables of docs/deck.md from the deck schema.

Usage:  /usr/bin/python3 scripts/update_deck_tables.py [--exe PATH] [--check]

Every table between `<!-- keys: MAP -->` and `<!-- /keys -->` in docs/deck.md is
generated from the deck schema (lib/io/deck_schema.cpp) by
`igacontact keys --markdown docs/deck.md`, so build igacontact first; the prose around
the tables is left as it is. The executable is --exe, else $IGACONTACT_EXE, else
build/bin/igacontact. Prints which tables changed.

--check writes nothing and exits 1 when a table is out of date (what
tests/io/deck_docs_test.cpp checks). Standard library only.
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = os.path.join(ROOT, "docs", "deck.md")
MARKER = re.compile(r"^<!-- keys: (.+) -->$")


def tables(text):
    """The marked tables of `text`: {map: the lines between its markers}."""
    found, current = {}, None
    for line in text.split("\n"):
        if line == "<!-- /keys -->":
            current = None
        elif MARKER.match(line):
            current = MARKER.match(line).group(1)
            found[current] = []
        elif current is not None:
            found[current].append(line)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--exe", default=os.environ.get("IGACONTACT_EXE",
                                                        os.path.join(ROOT, "build", "bin", "igacontact")))
    parser.add_argument("--check", action="store_true", help="write nothing; exit 1 if a table is out of date")
    args = parser.parse_args()
    if not os.access(args.exe, os.X_OK):
        sys.exit(f"update_deck_tables: no executable {args.exe}: build igacontact first (scripts/build.sh)")

    with open(DOCS, encoding="utf-8") as f:
        old = f.read()
    run = subprocess.run([args.exe, "keys", "--markdown", DOCS], capture_output=True, text=True)
    sys.stderr.write(run.stderr)
    if run.returncode != 0:
        sys.exit(f"update_deck_tables: {args.exe} keys --markdown failed (exit {run.returncode})")
    new = run.stdout

    before, after = tables(old), tables(new)
    changed = [name for name in after if before.get(name) != after[name]]
    if new == old:
        print("docs/deck.md: the key tables are up to date")
        return 0
    if args.check:
        print("docs/deck.md: out of date: " + (", ".join(changed) or "(outside the tables)"))
        return 1
    with open(DOCS, "w", encoding="utf-8") as f:
        f.write(new)
    print("docs/deck.md: regenerated " + ", ".join(changed))
    return 0


if __name__ == "__main__":
    sys.exit(main())
