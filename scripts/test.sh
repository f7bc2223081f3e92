#!/usr/bin/env bash
# Set up, build and run all tests through CTest (the README's test command; .ci/run calls it).
# Usage: scripts/test.sh [ctest options...]     e.g. scripts/test.sh -R nurbs
# Environment: IGACONTACT_BUILD_DIR (default build/), IGACONTACT_JOBS (default nproc).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"
jobs="${IGACONTACT_JOBS:-$(nproc 2>/dev/null || echo 2)}"

"$root/scripts/build.sh"
cd "$build"
ctest --output-on-failure -j "$jobs" "$@"
