#!/usr/bin/env bash
# Fuzz the deck reader with libFuzzer + ASan/UBSan (optional; needs clang).
#
# Usage: scripts/fuzz_deck_reader.sh [SECONDS]     (default 120)
#
# Builds fuzz/deck_reader_fuzzer.cpp in build-fuzz/ (a separate CMake project,
# CC=clang CXX=clang++, -DIGACONTACT_FUZZ=ON), seeds the corpus from inputs/*.yaml,
# verification/bad_input/*.yaml and verification/hard/*.yaml, and runs for SECONDS.
# iga::DeckError is the expected outcome of bad input; anything else (another
# exception, a crash, a sanitizer report) stops the run and leaves crash-* /
# leak-* / timeout-* files in build-fuzz/findings/. Exit code: the fuzzer's (0 =
# nothing found).
set -euo pipefail
seconds="${1:-120}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${FUZZ_BUILD_DIR:-$root/build-fuzz}"

command -v clang++ > /dev/null || { echo "clang++ not found (apt-get install -y clang)" >&2; exit 2; }
CC=clang CXX=clang++ cmake -S "$root/fuzz" -B "$build" -DIGACONTACT_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build "$build" -j2

corpus="$build/corpus" findings="$build/findings"
mkdir -p "$corpus" "$findings"
cp "$root"/inputs/*.yaml "$root"/verification/bad_input/*.yaml "$root"/verification/hard/*.yaml "$corpus"/ 2> /dev/null || true
cd "$findings"
exec "$build/deck_reader_fuzzer" "$corpus" -max_total_time="$seconds" -max_len=8192 -timeout=10 \
  -artifact_prefix="$findings/" -print_final_stats=1
