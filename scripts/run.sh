#!/usr/bin/env bash
# Set up, build and run one deck, then say where the results (and, for contact
# runs, the pressure plot) are.
# Usage: scripts/run.sh [DECK] [igacontact options...]   (default deck: inputs/hertz.yaml)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"

deck="$root/inputs/hertz.yaml"
if [ $# -gt 0 ] && [[ "$1" != -* ]]; then
  deck="$1"
  shift
fi

"$root/scripts/build.sh" igacontact

set +e
summary="$("$build/bin/igacontact" "$deck" --summary json "$@")"
status=$?
set -e

results="$(printf '%s\n' "$summary" | /usr/bin/python3 -c 'import json,sys
for line in sys.stdin:
    line = line.strip()
    if line.startswith("{"):
        print(json.loads(line).get("results", ""))' 2>/dev/null || true)"

if [ -n "$results" ] && [ -f "$results" ]; then
  :  # the app itself printed "results: <file>"
  has_contact="$(/usr/bin/python3 -c 'import h5py,sys
f = h5py.File(sys.argv[1], "r")
print("yes" if "results" in f and "contact" in f["results"] else "no")' "$results" 2>/dev/null || echo no)"
  if [ "$has_contact" = yes ]; then
    png="${results%.h5}_pressure.png"
    if /usr/bin/python3 "$root/scripts/plot_pressure.py" "$results" -o "$png" >/dev/null; then
      echo "pressure plot: $png"
    else
      echo "pressure plot: failed (see scripts/plot_pressure.py)" >&2
    fi
  fi
fi
exit $status
