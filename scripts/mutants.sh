#!/usr/bin/env bash
# A cargo-mutants run of one core file against chosen tests of one host-tests binary, the way
# docs/RELIABILITY.md records its mutation scores:
#
#   scripts/mutants.sh FILE BINARY OUT [FILTER ...]
#   RE='validate_terrain|validate_line_edge' scripts/mutants.sh src/network/terrain.rs core /tmp/mut-terrain elevation_coding
#
# FILE is a file of the core (src/…), BINARY a test binary of host-tests (core or modes), OUT
# the folder cargo-mutants writes (OUT/mutants.out/{caught,missed,timeout,unviable}.txt), and
# each FILTER a libtest name filter (a test runs if its path contains any of them; none: the
# whole binary). RE, if set, keeps only the mutants whose name matches it (cargo-mutants --re;
# a name reads `src/network/terrain.rs:47:50: replace && with || in …`). TIMEOUT (seconds,
# default 120) bounds each mutant's test run. COPY_TARGET=true copies ./target into the
# mutants' build folder, so their first build reuses the compiled dependencies.
#
# Why a script: cargo-mutants' own baseline runs `cargo test` in the mutated file's package,
# not in host-tests, so it must be skipped, and with it the check that the test command works.
# A command that fails for every mutant (two filters handed to `cargo test` instead of to the
# test binary fail that way) would count every mutant as caught. So the script first lists the
# tests the filters select, unmutated, and stops if there are none; then it hands the filters
# to the test binary (after cargo-mutants' `-- --`).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
if [ $# -lt 3 ]; then
    sed -n '2,14p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
    exit 2
fi
file=$1 binary=$2 out=$3
shift 3
[ -f "$file" ] || { echo "mutants.sh: no file $file" >&2; exit 2; }
command -v cargo-mutants >/dev/null || cargo install cargo-mutants --locked

selected=$(cargo test -q -p host-tests --test "$binary" --profile mutants -- "$@" --list 2>/dev/null | grep -c ': test$' || true)
if [ "$selected" -eq 0 ]; then
    echo "mutants.sh: the filters ${*:-(none)} select no test of host-tests' $binary binary" >&2
    exit 1
fi
echo "mutants.sh: $selected tests of $binary selected by: ${*:-(all)}"

re_args=()
if [ -n "${RE:-}" ]; then
    re_args=(--re "$RE")
fi
rm -rf "$out"
# `--cargo-arg` (not `--cargo-test-arg`) so that each mutant's build, too, compiles only the
# chosen test binary, not every target of host-tests; the `mutants` profile (Cargo.toml) is the
# test profile without debug information.
exec nice cargo mutants --file "$file" --test-package host-tests \
    --cargo-arg=--test --cargo-arg="$binary" --profile mutants --baseline skip \
    --timeout "${TIMEOUT:-120}" --copy-target "${COPY_TARGET:-false}" "${re_args[@]}" -o "$out" -- -- "$@"
