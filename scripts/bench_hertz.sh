#!/usr/bin/env bash
# Whole-run timing of the Hertz benchmark (median of several runs, one core):
# DOFs, wall time, the /timings split and the errors against Hertz.
# Usage: scripts/bench_hertz.sh [--repeat N] [--quick]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"
"$root/scripts/build.sh" igacontact
exec /usr/bin/python3 "$root/scripts/bench_hertz.py" --exe "$build/bin/igacontact" "$@"
