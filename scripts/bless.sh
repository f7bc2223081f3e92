#!/usr/bin/env bash
# Regenerate the stored reference of one verification case,
# verification/CASE/reference.h5, by running verification/CASE/deck.yaml with the
# current build. Deliberate: run by hand when a change of the results is intended,
# never by CI; commit the new reference with a message that says why it changed.
# Usage: scripts/bless.sh CASE            e.g. scripts/bless.sh hertz
# Environment: IGACONTACT_BUILD_DIR (default build/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"

if [ $# -ne 1 ] || [[ "$1" == -* ]]; then
  echo "usage: scripts/bless.sh CASE   (a folder of verification/ with a deck.yaml)" >&2
  exit 2
fi
case_dir="$root/verification/$1"
if [ ! -f "$case_dir/deck.yaml" ]; then
  echo "bless: no verification case '$1' ($case_dir/deck.yaml not found)" >&2
  exit 2
fi

"$root/scripts/build.sh" igacontact
app="$build/bin/igacontact"

tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$app" "$case_dir/deck.yaml" -q -o "$tmp/reference.h5"   # a failed run stops here (exit code 1)

# Reference files stay small (house style: well under 2 MiB).
max_bytes=$((2 * 1024 * 1024))
size=$(stat -c %s "$tmp/reference.h5")
if [ "$size" -ge "$max_bytes" ]; then
  echo "bless: the new reference is $size bytes (limit $max_bytes): make the deck smaller" >&2
  exit 1
fi

if [ -f "$case_dir/reference.h5" ]; then
  echo "bless: differences from the previous reference (exact comparison):"
  "$app" compare "$case_dir/reference.h5" "$tmp/reference.h5" --rtol 0 --atol 0 || true
fi
mv "$tmp/reference.h5" "$case_dir/reference.h5"
echo "bless: wrote $case_dir/reference.h5 ($size bytes); review and commit it with the reason"
