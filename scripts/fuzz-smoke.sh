#!/usr/bin/env bash
# A short run of every cargo-fuzz target (fuzz/, its own workspace, nightly toolchain):
# writes the networks the planner target loads (fuzz/networks/: Voronoi networks of ruz-popups
# and voronoi-dense, and the firmware fixtures' roadmap, terrain and landmark networks), seeds
# the loader's corpus with the smaller of them, then runs each target for FUZZ_SECONDS (default 20) seconds.
# A crash fails the run and leaves its input in fuzz/artifacts/TARGET/.
#
#   scripts/fuzz-smoke.sh [TARGET ...]     (default: load planner_ops voronoi decision scenario dem)
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
# The loader's seeds: the small images (a mutated megabyte image costs milliseconds a run), and
# a sparse roadmap of niendorf-urban.
"$skyroute" build scenarios/niendorf-urban.geojson --sample-spacing 400 -o fuzz/corpus/load/roadmap-sparse.bin >/dev/null
cp fuzz/networks/ruz-voronoi.bin fuzz/networks/voronoi-dense.bin fuzz/networks/terrain-jacksboro.bin fuzz/corpus/load/
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
for t in "${targets[@]}"; do
    max_len=()
    if [[ $t == load ]]; then
        max_len=(-max_len=400000)
    fi
    log=target/fuzz-logs/$t.log
    echo "fuzz: $t for ${seconds} s (log: $log)"
    if ! (cd fuzz && SKYROUTE_FUZZ_NETWORKS="$root/fuzz/networks" \
        cargo +nightly fuzz run "$t" -- -max_total_time="$seconds" -rss_limit_mb=4096 \
        ${max_len[@]+"${max_len[@]}"} -print_final_stats=1) >"$log" 2>&1; then
        tail -40 "$log"
        echo "fuzz: $t FAILED (the input is in fuzz/artifacts/$t/)" >&2
        exit 1
    fi
    grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|cov:" "$log" | tail -4
done
