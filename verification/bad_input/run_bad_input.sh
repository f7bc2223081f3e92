#!/usr/bin/env bash
# Bad-input suite: bad input never crashes igacontact and never loses data.
#
# Usage: run_bad_input.sh IGACONTACT [WORK_DIR]      (CTest: verification.bad_input)
#
# Every case is a file in this folder:
#   NAME.yaml  a one-change copy of base.yaml. Run twice in a scratch folder, as
#              `igacontact NAME.yaml -q -o result.h5` and `igacontact NAME.yaml -q`
#              (default output NAME.h5).
#   NAME.args  a command-line problem: `args: ...` is the command line (shell words,
#              run in a scratch folder holding base.yaml), `setup: ...` an optional
#              shell command run there first.
# Header lines of a case:
#   # expect: TEXT      stderr must contain TEXT (required)
#   # at: LINE:COL      stderr must contain "NAME.yaml:LINE:COL: error: " (located);
#                       "none" for errors that have no position in the file
#                       ("NAME.yaml: error: " then)
#   # exit: N           expected exit code (default 2: bad input or usage)
#   # skip-if-root: yes permission cases: root ignores file modes, so they cannot fail
#   # needs: petsc      cases of the PETSc backend: skipped when `igacontact --version`
#                       does not list it (a build without PETSc refuses them earlier)
#   env: NAME=VALUE ... (.args) environment variables for the run (shell words)
# For every run: it ends within RUN_LIMIT_S seconds (a hang is killed and fails), the
# exit code is the expected one (a crash, 3 or 0 fails), the
# message is there, and the scratch folder is unchanged: an existing results file
# (result.h5, a copy of base.yaml's results) is byte-identical and no file (results,
# temporary "*.tmp-<pid>", XDMF) was created.
set -uo pipefail

exe="${1:?usage: run_bad_input.sh IGACONTACT [WORK_DIR]}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
work="${2:-$(mktemp -d)}"
exe="$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")"
rm -rf "$work" && mkdir -p "$work" || exit 1

# The base deck must run: every case is one change away from a valid deck.
mkdir -p "$work/base"
cp "$here/base.yaml" "$work/base/"
if ! (cd "$work/base" && "$exe" base.yaml -q -o base.h5) || [ ! -s "$work/base/base.h5" ]; then
  echo "FAIL: base.yaml does not run; the suite would test nothing" >&2
  exit 1
fi
reference="$work/base/base.h5"
RUN_LIMIT_S="${RUN_LIMIT_S:-120}"  # the longest case takes under 2 s
has_petsc=no
[[ "$("$exe" --version)" == *petsc* ]] && has_petsc=yes

header() {  # header FILE KEY -> the value of "# KEY: value", if any
  sed -n "s/^# $2: //p" "$1" | head -n 1
}

listing() {  # names, sizes and checksums of every entry in a folder (sorted)
  (cd "$1" && find . -mindepth 1 -printf '%p %y %s\n' | sort && find . -type f -exec md5sum {} + | sort)
}

n_pass=0 n_fail=0 n_skip=0
failures=()

# check_run NAME DIR EXPECTED_EXIT EXPECT AT DECKNAME -- COMMAND...
check_run() {
  local name=$1 dir=$2 want_exit=$3 expect=$4 at=$5 deck=$6
  shift 7
  local before after code err problems=()
  before="$(listing "$dir")"
  (cd "$dir" && timeout -s KILL "$RUN_LIMIT_S" "$@" > "$work/$name.out" 2> "$work/$name.err" < /dev/null)
  code=$?
  [ "$code" -eq 137 ] && problems+=("killed after ${RUN_LIMIT_S} s (a hang)")
  err="$(cat "$work/$name.err")"
  after="$(listing "$dir")"
  [ "$code" -eq "$want_exit" ] || problems+=("exit code $code, expected $want_exit")
  [ -n "$err" ] || problems+=("no message on stderr")
  [[ "$err" == *"$expect"* ]] || problems+=("message lacks: $expect")
  if [ -n "$at" ]; then
    local located
    if [ "$at" = none ]; then located="$deck: error: "; else located="$deck:$at: error: "; fi
    [[ "$err" == *"$located"* ]] || problems+=("message not located as: $located")
  fi
  cmp -s "$reference" "$dir/result.h5" || problems+=("the existing results file changed")
  [ "$before" = "$after" ] || problems+=("files changed: $(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | tr '\n' ' ')")
  if [ ${#problems[@]} -eq 0 ]; then
    n_pass=$((n_pass + 1))
  else
    n_fail=$((n_fail + 1))
    failures+=("$name: $(IFS=';'; echo "${problems[*]}")")
    printf 'FAIL %s (%s)\n  %s\n  stderr: %s\n' "$name" "$*" "$(IFS=';'; echo "${problems[*]}")" "$err" >&2
  fi
}

prepare() {  # prepare NAME -> a fresh scratch folder with base.yaml and result.h5
  local dir="$work/$1"
  rm -rf "$dir" && mkdir -p "$dir"
  cp "$here/base.yaml" "$dir/"
  cp "$reference" "$dir/result.h5"
  echo "$dir"
}

shopt -s nullglob
for deck in "$here"/*.yaml; do
  name="$(basename "$deck" .yaml)"
  [ "$name" = base ] && continue
  expect="$(header "$deck" expect)"
  if [ -z "$expect" ]; then
    n_fail=$((n_fail + 1)); failures+=("$name: no '# expect:' line"); continue
  fi
  if [ "$(header "$deck" needs)" = petsc ] && [ "$has_petsc" = no ]; then
    echo "SKIP $name (this igacontact was built without PETSc)"
    n_skip=$((n_skip + 1)); continue
  fi
  want_exit="$(header "$deck" exit)"; want_exit="${want_exit:-2}"
  at="$(header "$deck" at)"
  dir="$(prepare "$name")"
  cp "$deck" "$dir/"
  check_run "$name" "$dir" "$want_exit" "$expect" "$at" "$name.yaml" -- "$exe" "$name.yaml" -q -o result.h5
  check_run "$name.default_output" "$dir" "$want_exit" "$expect" "$at" "$name.yaml" -- "$exe" "$name.yaml" -q
done

for case_file in "$here"/*.args; do
  name="$(basename "$case_file" .args)"
  expect="$(header "$case_file" expect)"
  args="$(sed -n 's/^args: //p' "$case_file" | head -n 1)"
  setup="$(sed -n 's/^setup: //p' "$case_file" | head -n 1)"
  env_line="$(sed -n 's/^env: //p' "$case_file" | head -n 1)"
  if [ -z "$expect" ] || [ -z "$args" ]; then
    n_fail=$((n_fail + 1)); failures+=("$name: needs '# expect:' and 'args:' lines"); continue
  fi
  if [ "$(header "$case_file" skip-if-root)" = yes ] && [ "$(id -u)" -eq 0 ]; then
    echo "SKIP $name (running as root: file permissions do not apply)"
    n_skip=$((n_skip + 1)); continue
  fi
  if [ "$(header "$case_file" needs)" = petsc ] && [ "$has_petsc" = no ]; then
    echo "SKIP $name (this igacontact was built without PETSc)"
    n_skip=$((n_skip + 1)); continue
  fi
  want_exit="$(header "$case_file" exit)"; want_exit="${want_exit:-2}"
  dir="$(prepare "$name")"
  if [ -n "$setup" ] && ! (cd "$dir" && eval "$setup"); then
    n_fail=$((n_fail + 1)); failures+=("$name: setup failed: $setup"); continue
  fi
  eval "words=($args)"
  eval "variables=($env_line)"
  check_run "$name" "$dir" "$want_exit" "$expect" "" "" -- env "${variables[@]}" "$exe" "${words[@]}"
done

echo "bad input: $n_pass runs passed, $n_fail failed, $n_skip skipped"
if [ "$n_fail" -gt 0 ]; then
  printf '  %s\n' "${failures[@]}"
  exit 1
fi
# Permissions (chmod 000 after the listing) would make cleanup fail as non-root.
chmod -R u+rwx "$work" 2>/dev/null
exit 0
