#!/usr/bin/env bash
# Configure and build igacontact (Release) in build/ (or $IGACONTACT_BUILD_DIR).
# Usage: scripts/build.sh [cmake --build target...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"
jobs="${IGACONTACT_JOBS:-$(nproc 2>/dev/null || echo 2)}"

"$root/scripts/setup.sh"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release ${IGACONTACT_CMAKE_ARGS:-} >&2
fi
if [ $# -gt 0 ]; then
  targets=()
  for t in "$@"; do targets+=(--target "$t"); done
  cmake --build "$build" -j "$jobs" "${targets[@]}" >&2
else
  cmake --build "$build" -j "$jobs" >&2
fi
