#!/usr/bin/env bash
# Host instruction counts of the `roadmap` firmware's query (niendorf-urban, free goal heading,
# a pop-up), per phase of `plan`, under callgrind: runs host-tests' `plan_profile` on the
# firmware's fixture (firmware-example/fixture/, written by scripts/test.sh's "firmware fixture"
# step) and prints the instructions of each phase, per plan, averaged over CYCLES plans.
#
#   scripts/profile-urban.sh [FIXTURE_DIR]        (CYCLES=3 by default)
#
# Every phase boundary calls plan_profile's phase_boundary(), and callgrind's --dump-before
# writes one profile per phase. Also leaves the profiles in target/profile-urban/ for
# callgrind_annotate.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
fixture=${1:-firmware-example/fixture}
cycles=${CYCLES:-3}
out=target/profile-urban

command -v valgrind >/dev/null || {
    echo "profile-urban: valgrind is missing (apt-get install valgrind)" >&2
    exit 127
}
cargo build --release -q -p host-tests --bin plan_profile
rm -rf "$out"
mkdir -p "$out"
valgrind --tool=callgrind --callgrind-out-file="$out/callgrind.out" \
    --dump-before='*phase_boundary*' \
    target/release/plan_profile "$fixture" --cycles "$cycles" 2>"$out/valgrind.log"

# Dump k (k ≥ 1) holds what ran since the boundary before it: dump 1 the start-up, then per
# plan the seven phases CheckFree … Route, and the time between plans.
python3 - "$out" "$cycles" <<'EOF'
import glob, re, sys
out, cycles = sys.argv[1], int(sys.argv[2])
def total(path):
    for line in open(path):
        if line.startswith(("summary:", "totals:")):
            return int(line.split()[1])
    raise SystemExit(f"{path}: no totals")
dumps = sorted(glob.glob(f"{out}/callgrind.out.*"), key=lambda p: int(p.rsplit(".", 1)[1]))
counts = [total(p) for p in dumps]
phases = ["CheckFree", "ConnectStart", "ConnectGoal", "ConnectDirect", "Search", "Route"]
# Boundaries per plan: the six phases and Done; the dump before the first boundary is start-up.
per_plan = len(phases) + 1
sums = [0] * len(phases)
for c in range(cycles):
    for i in range(len(phases)):
        sums[i] += counts[1 + c * per_plan + i]
print(f"{'phase':<14} {'instructions / plan':>20}")
for name, s in zip(phases, sums):
    print(f"{name:<14} {s // cycles:>20,}")
print(f"{'plan':<14} {sum(sums) // cycles:>20,}")
EOF
