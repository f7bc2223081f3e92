#!/usr/bin/env bash
# Penalty sweep of one contact pair: one run (one results file) per penalty value,
# two at a time, then a table and a plot (scripts/sweep_penalty.py).
# Usage: scripts/sweep_penalty.sh DECK PAIR V1 V2 ... [--out DIR] [--jobs N] [--set PATH=VALUE]...
#   --out DIR   where the results go (default sweep_<deck stem>/): DIR/penalty_<V>.h5 and
#               .json (the --summary json line), DIR/sweep.csv, DIR/sweep.png
#   --jobs N    runs in parallel (default 2; each run single-threaded, OMP_NUM_THREADS=1)
#   --set ...   passed to every run (e.g. a coarser mesh)
# Builds igacontact first (scripts/build.sh), unless IGACONTACT_EXE names a binary.
# Example: scripts/sweep_penalty.sh inputs/hertz.yaml cyl_floor 1e4 1e5 1e6 1e7 1e8
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IGACONTACT_BUILD_DIR:-$root/build}"

usage() { sed -n '2,10p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2; exit 2; }

out="" jobs=2 sets=() positional=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --set) sets+=(--set "$2"); shift 2 ;;
    -h|--help) usage ;;
    *) positional+=("$1"); shift ;;
  esac
done
[ ${#positional[@]} -ge 3 ] || usage
deck="${positional[0]}" pair="${positional[1]}" values=("${positional[@]:2}")
[ -f "$deck" ] || { echo "error: deck $deck not found" >&2; exit 2; }
stem="$(basename "${deck%.*}")"
out="${out:-sweep_$stem}"
mkdir -p "$out"

exe="${IGACONTACT_EXE:-}"
if [ -z "$exe" ]; then
  "$root/scripts/build.sh" igacontact
  exe="$build/bin/igacontact"
fi

# One line per value: "VALUE"; xargs runs `run_one VALUE` $jobs at a time. A failed run
# (exit 1) still leaves its results file and summary; the table reports its status.
export exe deck pair out
sets_joined=""
[ ${#sets[@]} -eq 0 ] || sets_joined="$(printf '%q ' "${sets[@]}")"
export sets_joined
run_one() {
  local v="$1"
  eval "local extra=($sets_joined)"
  OMP_NUM_THREADS=1 "$exe" "$deck" -o "$out/penalty_$v.h5" -q --summary json \
    --set "contact.$pair.penalty=$v" "${extra[@]+"${extra[@]}"}" > "$out/penalty_$v.json" 2> "$out/penalty_$v.err" || true
  [ -s "$out/penalty_$v.err" ] || rm -f "$out/penalty_$v.err"
  echo "penalty $v: done" >&2
}
export -f run_one
printf '%s\n' "${values[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ {}

status=0
/usr/bin/python3 "$root/scripts/sweep_penalty.py" "$out" "$pair" "${values[@]}" || status=$?

n=$(( ${#values[@]} - 1 ))
cat <<EOF

Slurm: the same sweep as a job array (one task per penalty), e.g. sweep.sbatch:
  #!/bin/bash
  #SBATCH --array=0-$n --cpus-per-task=1 --time=00:30:00 --output=$out/slurm_%a.log
  values=(${values[*]})
  v=\${values[\$SLURM_ARRAY_TASK_ID]}
  mkdir -p $out
  OMP_NUM_THREADS=1 $exe $deck -o $out/penalty_\$v.h5 -q --summary json --set contact.$pair.penalty=\$v ${sets_joined}> $out/penalty_\$v.json
Submit with \`sbatch sweep.sbatch\` (the array range is 0-$n: one task per value, read from
SLURM_ARRAY_TASK_ID), then, when all tasks are done, tabulate and plot with
\`/usr/bin/python3 scripts/sweep_penalty.py $out $pair ${values[*]}\`.
EOF
exit $status
