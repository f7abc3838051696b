#!/usr/bin/env bash
# bench/compare.sh: skyroute next to real peers on this machine, one table of ratios.
#
#   bench/compare.sh                 (from the repository root; about 5 minutes on 2 cores once
#                                     target/ is built; the first run also installs and compiles)
#
# 1. Queries: OMPL's PRM* (with the DiscreteMotionValidator and with the DubinsMotionValidator)
#    and LazyPRM in C++ (Debian libompl-dev, bench/ompl_cpp/) over a forward-only
#    DubinsStateSpace, roadmaps of skyroute's vertex count, on niendorf-urban and
#    on a denser generated city (bench/make_dense_city.py); skyroute's queries timed in-process
#    (bench/peers, `peers plan`); OMPL's routes checked with skyroute's exact predicates
#    (`peers check`) and densely; the C++ point checker checked against skyroute's.
# 2. Dubins shortest paths: skyroute (f32), OMPL's DubinsStateSpace::distance and Andrew
#    Walker's dubins.c (downloaded from PyPI's `dubins` sdist into the work folder, not
#    committed), on the same random pose pairs.
# 3. Single-source shortest paths: the core's heap over the network's edges, petgraph and SciPy.
# 4. callgrind instruction counts of skyroute's niendorf-urban queries, and its top functions.
# Then bench/peers_table.py prints the table (and writes WORK/table.md).
#
# It installs what is missing: libompl-dev libeigen3-dev g++ cmake valgrind (apt-get, with
# sudo unless root) and scipy numpy (pip). Settings (environment): WORK (default
# /tmp/skyroute-peers), QUERIES (100), PAIRS (1000000), SOURCES (20), SEED (20240611),
# JOBS (cargo -j, 1). Not part of scripts/test.sh.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WORK=${WORK:-/tmp/skyroute-peers}
QUERIES=${QUERIES:-100}
PAIRS=${PAIRS:-1000000}
SOURCES=${SOURCES:-20}
SEED=${SEED:-20240611}
JOBS=${JOBS:-1}
RESOLUTION_M=1.0       # OMPL's motion check: one state per metre along each Dubins path
SIMPLIFY_S=1.0         # cap of OMPL's PathSimplifier::simplify per route
COMMAND="QUERIES=$QUERIES PAIRS=$PAIRS SOURCES=$SOURCES SEED=$SEED bench/compare.sh"
mkdir -p "$WORK/bin" "$WORK/cg"
cd "$ROOT"

step() { printf '\n== %s\n' "$*" >&2; }
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO=sudo; fi

step "dependencies"
missing=()
for p in libompl-dev libeigen3-dev g++ cmake valgrind pkg-config; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}"
fi
python3 -c 'import scipy, numpy' 2>/dev/null || python3 -m pip install -q scipy numpy
WALKER=$(ls -d "$WORK"/dubins-sdist/dubins-*/dubins 2>/dev/null | head -1 || true)
if [ -z "$WALKER" ]; then
    mkdir -p "$WORK/dubins-sdist"
    python3 -m pip download -q --no-binary :all: --no-deps dubins -d "$WORK/dubins-sdist"
    tar -xzf "$WORK"/dubins-sdist/dubins-*.tar.gz -C "$WORK/dubins-sdist"
    WALKER=$(ls -d "$WORK"/dubins-sdist/dubins-*/dubins | head -1)
fi

step "build"
cargo build --release -q -j"$JOBS" -p skyroute-prep --bin skyroute
cargo build --release -q -j"$JOBS" --example peers \
    --manifest-path bench/peers/Cargo.toml --target-dir "$ROOT/target"
SKY=$ROOT/target/release/skyroute
PEERS=$ROOT/target/release/examples/peers
# Compile flags from pkg-config. Link with -lompl only: Debian's ompl.pc also names the
# unversioned boost .so files of boost -dev packages that libompl-dev does not install, and
# libompl.so already links its boost libraries itself.
g++ -O2 $(pkg-config --cflags ompl) -std=c++17 -o "$WORK/bin/ompl_peers" \
    bench/ompl_cpp/main.cpp bench/ompl_cpp/prm.cpp -L"$(pkg-config --variable=libdir ompl)" -lompl -lpthread
gcc -O2 -I"$WALKER/include" -o "$WORK/bin/walker_bench" bench/walker/walker_bench.c "$WALKER/src/dubins.c" -lm
OMPL=$WORK/bin/ompl_peers

# Median wall time of 3 whole `skyroute build` processes on one thread, as JSON.
time_build() {
    local scenario=$1 out=$2 json=$3 t=()
    for _ in 1 2 3; do
        local t0 t1
        t0=$(date +%s%N)
        RAYON_NUM_THREADS=1 "$SKY" build "$scenario" -o "$out" >/dev/null
        t1=$(date +%s%N)
        t+=("$(( t1 - t0 ))")
    done
    local med
    med=$(printf '%s\n' "${t[@]}" | sort -n | sed -n 2p)
    printf '{"runs_ns": [%s], "median_s": %s, "threads": 1}\n' "$(IFS=,; echo "${t[*]}")" \
        "$(awk "BEGIN{print $med/1e9}")" > "$json"
}

step "networks"
python3 bench/make_dense_city.py "$WORK/dense-city.geojson"
declare -A SCENARIO=([niendorf]=scenarios/niendorf-urban.geojson [dense]=$WORK/dense-city.geojson
                     [jacksboro]=scenarios/medeiros-jacksboro.geojson)
for key in niendorf dense jacksboro; do
    "$SKY" build "${SCENARIO[$key]}" -o "$WORK/$key.bin" >&2
    "$SKY" export "$WORK/$key.bin" -o "$WORK/$key.json" >&2
done
for key in niendorf dense; do
    time_build "${SCENARIO[$key]}" "$WORK/$key.timed.bin" "$WORK/$key.build.json"
    "$PEERS" map "$WORK/$key.bin" "$WORK/$key.map.txt" > "$WORK/$key.info.json"
done

for key in niendorf dense; do
    step "queries: $key"
    W=$WORK/$key
    vertices=$(python3 -c "import json; print(json.load(open('$W.info.json'))['vertices'])")
    "$PEERS" queries "$W.bin" "$QUERIES" "$SEED" "$W.queries.txt"
    "$PEERS" plan "$W.bin" "$W.queries.txt" "$W.plan.json"
    "$PEERS" validity "$W.bin" 200000 7 "$W.points.txt"
    "$OMPL" validity "$W.map.txt" "$W.points.txt" "$W.validity.json"
    # tag:planner:motion validator. PRM* with OMPL's stock DiscreteMotionValidator, which
    # recomputes the Dubins path for every state it checks, and with its DubinsMotionValidator,
    # which computes it once per motion (same roadmap and checks, less interpolation work).
    for run in prmstar:prmstar:discrete prmstar-dmv:prmstar:dubins lazyprm:lazyprm:discrete; do
        IFS=: read -r tag planner validator <<< "$run"
        "$OMPL" prm "$W.map.txt" "$W.queries.txt" "$planner" "$vertices" "$RESOLUTION_M" 1 \
            "$W.$tag.json" "$W.$tag.routes.txt" "$SIMPLIFY_S" "$validator"
        "$PEERS" check "$W.bin" "$W.$tag.routes.txt" "$W.$tag.check.json"
    done
done

step "callgrind: niendorf queries"
rm -f "$WORK"/cg/*
valgrind --tool=callgrind --callgrind-out-file="$WORK/cg/per.out" \
    --toggle-collect='peers::plan::measured_plan' --dump-after='peers::plan::measured_plan' \
    "$PEERS" plan "$WORK/niendorf.bin" "$WORK/niendorf.queries.txt" "$WORK/cg/plan.json" 1 2>/dev/null
valgrind --tool=callgrind --callgrind-out-file="$WORK/cg/all.out" \
    --toggle-collect='peers::plan::measured_plan' \
    "$PEERS" plan "$WORK/niendorf.bin" "$WORK/niendorf.queries.txt" "$WORK/cg/plan.json" 1 2>/dev/null
callgrind_annotate --inclusive=yes "$WORK/cg/all.out" > "$WORK/cg/annotate.txt" 2> "$WORK/cg/annotate.log"

step "Dubins shortest paths: $PAIRS pairs"
RADIUS=$(python3 -c "import json; print(json.load(open('$WORK/niendorf.info.json'))['turn_radius_m'])")
"$PEERS" pairs "$PAIRS" "$SEED" "$RADIUS" "$WORK/pairs.bin"
"$PEERS" dubins "$WORK/pairs.bin" "$RADIUS" "$WORK/dubins.ours.bin" "$WORK/dubins.ours.json"
"$OMPL" dubins "$WORK/pairs.bin" "$RADIUS" "$WORK/dubins.ompl.bin" "$WORK/dubins.ompl.json"
"$WORK/bin/walker_bench" "$WORK/pairs.bin" "$RADIUS" "$WORK/dubins.walker.bin" "$WORK/dubins.walker.json"
# Instructions per path (wall times of a few hundred ns are noisy here): each solver under
# callgrind on the first 100 000 pairs, one timed pass and the lengths pass, counting only
# inside its solver function.
head -c $((100000 * 48)) "$WORK/pairs.bin" > "$WORK/pairs100k.bin"
cg_dubins() {
    local name=$1; shift
    local toggles=()
    while [ "$1" != -- ]; do toggles+=("--toggle-collect=$1"); shift; done
    shift
    valgrind --tool=callgrind --callgrind-out-file="$WORK/cg/dubins.$name.out" "${toggles[@]}" \
        "$@" "$WORK/pairs100k.bin" "$RADIUS" "$WORK/cg/$name.bin" "$WORK/cg/$name.json" 1 2>/dev/null
}
cg_dubins ours 'peers::dubins::shortest_length' -- "$PEERS" dubins
cg_dubins ompl 'ompl::base::DubinsStateSpace::distance*' -- "$OMPL" dubins
cg_dubins walker dubins_shortest_path dubins_path_length -- "$WORK/bin/walker_bench"

step "single-source shortest paths"
for key in niendorf jacksboro; do
    "$PEERS" sssp "$WORK/$key.bin" "$SOURCES" "$SEED" "$WORK/$key.sssp.bin" "$WORK/$key.sssp.json"
    python3 bench/sssp_scipy.py "$WORK/$key.json" "$WORK/$key.sssp.json" "$WORK/$key.sssp.bin" \
        "$WORK/$key.scipy.json"
done

step "table"
python3 bench/peers_table.py "$WORK" "$COMMAND"
