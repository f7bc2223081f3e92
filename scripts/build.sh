#!/usr/bin/env bash
# Configure and build igacontact (Release) in build/ (or $IGACONTACT_BUILD_DIR).
# Usage: scripts/build.sh [cmake --build target...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"
jobs="${IGACONTACT_JOBS:-$(nproc 2>/dev/null || echo 2)}"

"$root/scripts/setup.sh"
# A build folder configured before the PETSc option existed has a serial HDF5 cached,
# which a PETSc build must not link (PETSc links the MPI one): configure it afresh.
if [ -f "$build/CMakeCache.txt" ] && ! grep -q "^IGACONTACT_PETSC:" "$build/CMakeCache.txt"; then
  echo "build: reconfiguring $build (the PETSc backend is new)" >&2
  rm -f "$build/CMakeCache.txt"
  rm -rf "$build/CMakeFiles"
fi
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
