#!/usr/bin/env bash
# The k-sweep of the Voronoi mode (docs/THREATS.md, "Experiments"): for k in 0.1 0.5 0.9 1.0,
# plans ruz-popups as a Voronoi scenario with its pop-ups (the default) and without them
# (--no-scenario-popups), voronoi-dense, and ruz-popups as a roadmap under the same cost (the
# ground planner of `plan --threat-weight` on a roadmap network); prints one table row per plan
# (k, length km, exposure flown, exposure by the three-point rule, planning time as `plan`
# prints it) and renders one picture per case into docs/img/ with the routes side by side.
#
#   scripts/voronoi_k_sweep.sh [OUT_DIR]     (work files; default: a temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p skyroute-prep
S=target/release/skyroute
W=${1:-$(mktemp -d)}
mkdir -p "$W" docs/img
KS="0.1 0.5 0.9 1.0"
RUZ=scenarios/ruz-popups.geojson
DENSE=scenarios/voronoi-dense.geojson

$S build $RUZ --mode voronoi -o "$W/ruz-v.bin" >/dev/null
$S build $DENSE -o "$W/dense.bin" >/dev/null
$S build $RUZ -o "$W/ruz-r.bin" >/dev/null

# One plan: prints "| case | k | length km | exposure flown | three-point | time |".
row() {
    local case=$1 k=$2 out=$3
    shift 3
    local line
    line=$($S plan "$@" --threat-weight "$k" -o "$out" | tail -1)
    python3 - "$out" "$case" "$k" "$line" <<'PY'
import json, re, sys
path, case, k, line = sys.argv[1:]
r = json.load(open(path))
three = r.get("exposure_coarse_three_point", r.get("exposure_three_point"))
t = re.search(r"([0-9.]+) s ->", line).group(1)
print(f"| {case} | {k} | {r['length_m'] / 1000:.1f} | {r['exposure_flown']:.1f} | {three:.1f} | {t} s |")
PY
}

echo "| case | k | length km | exposure flown | exposure three-point | planning time |"
echo "|---|---|---|---|---|---|"
for case in ruz-popups ruz-nominal dense roadmap; do
    routes=()
    for k in $KS; do
        out="$W/$case-$k.json"
        case $case in
            ruz-popups) row "ruz-popups (voronoi, pop-ups applied)" "$k" "$out" "$W/ruz-v.bin" --scenario $RUZ --mode voronoi ;;
            ruz-nominal) row "ruz-popups (voronoi, nominal)" "$k" "$out" "$W/ruz-v.bin" --scenario $RUZ --mode voronoi --no-scenario-popups ;;
            dense) row "voronoi-dense" "$k" "$out" "$W/dense.bin" --scenario $DENSE ;;
            roadmap) row "ruz-popups (roadmap, ground, pop-ups applied)" "$k" "$out" "$W/ruz-r.bin" --scenario $RUZ ;;
        esac
        routes+=(--route "$out")
    done
    case $case in
        ruz-popups) $S render "$W/ruz-v.bin" "${routes[@]}" --scenario $RUZ --mode voronoi -o docs/img/voronoi-k-sweep-ruz-popups.png >/dev/null ;;
        ruz-nominal) $S render "$W/ruz-v.bin" "${routes[@]}" --scenario $RUZ --mode voronoi -o docs/img/voronoi-k-sweep-ruz-nominal.png >/dev/null ;;
        dense) $S render "$W/dense.bin" "${routes[@]}" --scenario $DENSE -o docs/img/voronoi-k-sweep-dense.png >/dev/null ;;
        roadmap) $S render "$W/ruz-r.bin" "${routes[@]}" --no-edges --scenario $RUZ -o docs/img/roadmap-k-sweep-ruz-popups.png >/dev/null ;;
    esac
done
