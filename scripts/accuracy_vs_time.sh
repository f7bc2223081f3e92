#!/usr/bin/env bash
# What accuracy costs in time: sweep the Hertz benchmark over degree, mesh and
# penalty, and write docs/accuracy/ (accuracy.csv, accuracy.md, PNG plots).
# Usage: scripts/accuracy_vs_time.sh [--quick] [--jobs N] [--repeat N] [--out DIR]
# Builds igacontact first (scripts/build.sh), unless IGACONTACT_EXE names a binary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"
exe="${IGACONTACT_EXE:-}"
if [ -z "$exe" ]; then
  "$root/scripts/build.sh" igacontact
  exe="$build/bin/igacontact"
fi
exec /usr/bin/python3 "$root/scripts/accuracy_vs_time.py" --exe "$exe" "$@"
