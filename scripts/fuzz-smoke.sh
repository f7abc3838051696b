#!/usr/bin/env bash
# A short run of every cargo-fuzz target (fuzz/, its own workspace, nightly toolchain):
# writes the networks the planner target loads (fuzz/networks/: Voronoi networks of ruz-popups
# and voronoi-dense, the firmware fixtures' roadmap, terrain and landmark networks, and the
# three-dimensional roadmap of niendorf-urban-3d), seeds
# the loader's corpus with the smaller of them, then runs each target for FUZZ_SECONDS (default 20) seconds.
# A crash fails the run and leaves its input in fuzz/artifacts/TARGET/.
#
#   scripts/fuzz-smoke.sh [TARGET ...]     (default: load planner_ops voronoi decision scenario dem)
#   LOAD_RUNS=10000000 scripts/fuzz-smoke.sh load   (the loader's long run: the small images'
#                                                    corpus, fuzz/corpus/load-small/, until that
#                                                    many executions)
#   FUZZ_RUNS=10000000 scripts/fuzz-smoke.sh decision   (a long run of any target: its usual
#                                                    corpus, until that many executions)
#   UNIT_SECONDS=N    the longest any one input may run before it counts as a failure (default 60)
#
# Without a nightly toolchain it says so and exits 0: the fuzz run is skipped, not failed.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
cargo_bin=${CARGO_HOME:-$HOME/.cargo}/bin
export PATH="$cargo_bin:$PATH"

if ! rustup toolchain list 2>/dev/null | grep -q '^nightly'; then
    echo "SKIPPED fuzz smoke run: no nightly toolchain (rustup toolchain list); cargo-fuzz needs one"
    exit 0
fi
if ! command -v cargo-fuzz >/dev/null; then
    cargo install cargo-fuzz --locked
fi
seconds=${FUZZ_SECONDS:-20}
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
    targets=(load planner_ops voronoi decision scenario dem)
fi

mkdir -p fuzz/networks fuzz/corpus/load
cargo build --release -q -p skyroute-prep
skyroute=target/release/skyroute
"$skyroute" build scenarios/ruz-popups.geojson --mode voronoi -o fuzz/networks/ruz-voronoi.bin >/dev/null
"$skyroute" build scenarios/voronoi-dense.geojson -o fuzz/networks/voronoi-dense.bin >/dev/null
cp firmware-example/fixture/network.bin fuzz/networks/roadmap-niendorf.bin
cp firmware-example/fixture-terrain/network.bin fuzz/networks/terrain-jacksboro.bin
cp firmware-example/fixture-landmark/network.bin fuzz/networks/landmark-babel-II-N.bin
cp firmware-example/fixture-ruz/network.bin fuzz/networks/roadmap-ruz-alternatives.bin
"$skyroute" build scenarios/niendorf-urban-3d.geojson -o fuzz/networks/roadmap-3d.bin >/dev/null
cp fuzz/networks/roadmap-3d.bin fuzz/corpus/load/
# The loader's seeds: the small images (a mutated megabyte image costs milliseconds a run), and
# a sparse roadmap of niendorf-urban.
"$skyroute" build scenarios/niendorf-urban.geojson --sample-spacing 400 -o fuzz/corpus/load/roadmap-sparse.bin >/dev/null
cp fuzz/networks/ruz-voronoi.bin fuzz/networks/voronoi-dense.bin fuzz/networks/terrain-jacksboro.bin fuzz/corpus/load/
# Small images of every mode (a few kB each, so a run takes microseconds): the `skyroute init`
# templates, the terrain one over a 30 x 30 window of the shipped DEM. They seed the loader's
# corpus here and `fuzz/corpus/load-small/`, the corpus of the long run (LOAD_RUNS).
small=target/fuzz-small
mkdir -p "$small" fuzz/corpus/load-small
python3 - scenarios/jacksboro-dem.asc "$small/dem.asc" <<'PY'
import sys
lines = open(sys.argv[1]).read().split("\n")
head = dict(l.split() for l in lines[:6])
rows = [l.split() for l in lines[6:] if l.strip()]
r0, c0, n = 100, 100, 30  # the window's first row (from the north) and column, and its side
cell = float(head["cellsize"])
with open(sys.argv[2], "w") as out:
    out.write(f"ncols {n}\nnrows {n}\n")
    out.write(f"xllcorner {float(head['xllcorner']) + c0 * cell:.8f}\n")
    out.write(f"yllcorner {float(head['yllcorner']) + (len(rows) - r0 - n) * cell:.8f}\n")
    out.write(f"cellsize {head['cellsize']}\nNODATA_value {head['NODATA_value']}\n")
    for row in rows[r0:r0 + n]:
        out.write(" ".join(row[c0:c0 + n]) + "\n")
PY
for mode in roadmap landmark voronoi terrain; do
    dem=()
    [[ $mode == terrain ]] && dem=(--dem "$small/dem.asc")
    "$skyroute" init --force --mode "$mode" ${dem[@]+"${dem[@]}"} "$small/$mode.geojson" >/dev/null
done
"$skyroute" build "$small/roadmap.geojson" --sample-spacing 500 -o "$small/roadmap.bin" >/dev/null
"$skyroute" build "$small/landmark.geojson" -o "$small/landmark.bin" >/dev/null
"$skyroute" build "$small/voronoi.geojson" -o "$small/voronoi.bin" >/dev/null
"$skyroute" build "$small/terrain.geojson" -o "$small/terrain.bin" >/dev/null
cp "$small"/*.bin fuzz/corpus/load/
cp "$small"/*.bin fuzz/corpus/load-small/
# The parsers' seeds: the shipped scenarios, the shipped DEM and a GeoTIFF of its first rows
# (when GDAL is there).
mkdir -p fuzz/corpus/scenario fuzz/corpus/dem
cp scenarios/*.geojson fuzz/corpus/scenario/
head -c 20000 scenarios/jacksboro-dem.asc >fuzz/corpus/dem/jacksboro-head.asc
if command -v gdal_translate >/dev/null; then
    gdal_translate -q -srcwin 0 0 40 30 -co COMPRESS=DEFLATE scenarios/jacksboro-dem.asc \
        fuzz/corpus/dem/jacksboro-40x30.tif
fi

mkdir -p target/fuzz-logs
# Compile every target first, so that the runs' time limits below count fuzzing only.
(cd fuzz && cargo +nightly fuzz build >"$root/target/fuzz-logs/build.log" 2>&1) || {
    tail -40 target/fuzz-logs/build.log
    exit 1
}
# A slow input is a failure, not a hang: libFuzzer's -timeout fails any one input that runs longer
# than UNIT_SECONDS (default 60; its artifact is kept as for a crash), and a short run that
# overruns its own time by more than 5 minutes is stopped (`timeout`) and failed.
unit_seconds=${UNIT_SECONDS:-60}
for t in "${targets[@]}"; do
    extra=(-max_total_time="$seconds")
    limit=(timeout --kill-after=10 $((seconds + 300)))
    corpus=()
    if [[ $t == load && -n ${LOAD_RUNS:-} ]]; then
        # The long run: the small images only, until LOAD_RUNS executions.
        extra=(-runs="$LOAD_RUNS" -max_len=32768)
        limit=()
        corpus=(corpus/load-small)
    elif [[ -n ${FUZZ_RUNS:-} ]]; then
        extra=(-runs="$FUZZ_RUNS")
        limit=()
    fi
    if [[ $t == load && -z ${LOAD_RUNS:-} ]]; then
        extra+=(-max_len=400000)
    fi
    log=target/fuzz-logs/$t.log
    echo "fuzz: $t: ${extra[*]} -timeout=$unit_seconds (log: $log)"
    if ! (cd fuzz && SKYROUTE_FUZZ_NETWORKS="$root/fuzz/networks" \
        ${limit[@]+"${limit[@]}"} cargo +nightly fuzz run "$t" ${corpus[@]+"${corpus[@]}"} -- \
        -rss_limit_mb=4096 -timeout="$unit_seconds" "${extra[@]}" -print_final_stats=1) \
        >"$log" 2>&1; then
        tail -40 "$log"
        echo "fuzz: $t FAILED (the input is in fuzz/artifacts/$t/)" >&2
        exit 1
    fi
    grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|cov:" "$log" | tail -4
done
