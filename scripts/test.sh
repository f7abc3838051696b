#!/usr/bin/env bash
# The project's whole check, as CI runs it (.ci/run): installs what is missing, then
#   format → structure check → clippy (host, thumbv7em, thumbv7em+defmt) → core docs → OMPL and SciPy references → tests →
#   firmware fixture → firmware build → firmware clippy → firmware under QEMU → sizes, for the
#   roadmap (niendorf-urban, binary `roadmap`), again for terrain (medeiros-jacksboro, binary
#   `terrain`; thinned for the STM32F405, and whole on the larger target: QEMU's mps2-an500,
#   a Cortex-M7 with an STM32H743's 2 MiB flash and 1 MiB RAM) and for landmarks (babel-II-N, binary `landmark`: plan, lose a landmark in
#   flight, re-plan) and for radar threats (ruz-popups as a Voronoi network, binary `voronoi`:
#   plan, a radar pops up in flight, re-plan) and for the pop-up switch (ruz-popups with its
#   stored bypass alternatives, binary `ruz`: decide a sequence of announcements, fly the
#   choices and re-plan, and a worst-case decision, as the host does) and for planning in
#   slices (the roadmap fixture, binary `slices` with the feature `slices`: RTIC 2, a task
#   ticking while the query is planned a slice at a time) → no recursion, no panic path (the
#   disassembly, and a link with an undefined panic handler), stack bound → a short run of every fuzz target
#   (scripts/fuzz-smoke.sh; skipped, with a message, where no nightly toolchain is installed).
# Runnable from any directory. Stops at the first failing step; KEEP_GOING=1 runs every step
# and fails at the end instead.
#
# Knobs (environment):
#   SKYROUTE_BUILD_ARGS  arguments of the ground tool that builds the firmware's network
#                        (default below: niendorf-urban)
#   FIXTURE_SYNTHETIC=1  use the fixture tool's small synthetic grid network instead (debugging)
#   FIXTURE_ARGS         extra options of the fixture tool, e.g. "--start x,y,h --goal x,y
#                        --popup x,y,r" (local metres, radians CCW from east); defaults: see
#                        host-tests/src/bin/firmware_fixture/
#   FIRMWARE_TIMEOUT     seconds the firmware may run under QEMU (default 300)
#   KEEP_GOING=1         run every step even after a failure
#   SWEEP_QUERIES        random queries per mode of the work bound sweep (default 20000; the
#                        recorded long run, docs/RELIABILITY.md, is SWEEP_QUERIES=100000)
#   STEPS=REGEX          run only the steps whose name matches REGEX (grep -E), e.g.
#                        STEPS=firmware for the six firmware binaries' steps, or
#                        STEPS='voronoi firmware' for one binary's
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

# Each workspace builds into its own target/ (the firmware ELFs' paths below rely on it; an
# exported CARGO_TARGET_DIR would leave QEMU running a stale ELF).
unset CARGO_TARGET_DIR

cargo_bin=${CARGO_HOME:-$HOME/.cargo}/bin
export PATH="$cargo_bin:$PATH"

# The network the firmware embeds: built by the ground tool from this scenario.
scenario=scenarios/niendorf-urban.geojson
network_src=target/fixture/network-src.bin
SKYROUTE_BUILD_ARGS=${SKYROUTE_BUILD_ARGS:-"build $scenario -o $network_src"}
fixture_dir=firmware-example/fixture
# The terrain firmware's network: medeiros-jacksboro thinned to fit the STM32F405's 128 KiB RAM
# (the search state is ~22 B per edge): nodes 400 m apart, edges up to 5 km, nodes 60 m
# farther out from their corners to leave room for turns among the fewer nodes.
terrain_scenario=scenarios/medeiros-jacksboro.geojson
terrain_src=target/fixture/terrain-src.bin
terrain_full_src=target/fixture/terrain-full-src.bin
terrain_full_fixture_dir=firmware-example/fixture-terrain-full
terrain_fixture_dir=firmware-example/fixture-terrain
# P and Q of the scenario in its local frame (heading: compass 45° with the meridian convergence).
terrain_query="--start -3547.7197,-9893.968,0.78498753 --goal 3539.5775,9895.5724 --popup-on-route 100"
# The landmark firmware's network: babel-II-N as `skyroute build` writes it (289 KB in format v4).
landmark_scenario=scenarios/babel-II-N.geojson
landmark_src=target/fixture/landmark-src.bin
landmark_fixture_dir=firmware-example/fixture-landmark
# The Voronoi firmware's network: ruz-popups (a roadmap scenario) taken as a Voronoi scenario;
# the fixture tool reads the scenario for its start P and goal Q in the network's local frame.
voronoi_scenario=scenarios/ruz-popups.geojson
voronoi_src=target/fixture/voronoi-src.bin
voronoi_fixture_dir=firmware-example/fixture-voronoi
# The pop-up switch firmware (Ruz et al.): a ruz-popups roadmap whose image stores the pop-ups'
# bypass alternatives, samples 2 km apart (198 KB; the scenario's 1.5 km make 934 KB, most of
# the STM32F405's 1 MiB flash).
ruz_scenario=scenarios/ruz-popups.geojson
ruz_sample_spacing=2000
ruz_src=target/fixture/ruz-src.bin
ruz_fixture_dir=firmware-example/fixture-ruz
# The three-dimensional roadmap firmware: the roadmap binary linked with niendorf-urban-3d's
# network in its own target directory (SKYROUTE_FIXTURE_DIR), the ELF copied as roadmap-3d so
# that its log does not replace the planar one's.
roadmap3d_scenario=scenarios/niendorf-urban-3d.geojson
roadmap3d_src=target/fixture/roadmap3d-src.bin
roadmap3d_fixture_dir=firmware-example/fixture-3d
roadmap3d_release=firmware-example/target/roadmap-3d/thumbv7em-none-eabihf/release
# The firmware binaries' ELFs: $firmware_release/{roadmap,terrain,landmark,voronoi,ruz,slices}.
firmware_release=firmware-example/target/thumbv7em-none-eabihf/release

script_start=$SECONDS
failed=()
timings=()

banner() {
    printf '\n\033[1m==== %s ====\033[0m\n' "$*"
}

# step NAME COMMAND...: runs COMMAND under a banner, records its time, and stops the script on
# failure (or, with KEEP_GOING=1, records the failure and goes on).
step() {
    local name=$1
    shift
    if [[ -n ${STEPS:-} ]] && ! grep -qE -- "$STEPS" <<<"$name"; then
        return 0
    fi
    banner "$name"
    local t0=$SECONDS status=0
    # A subshell with -e of its own: inside `cmd || …` bash would ignore -e in functions.
    set +e
    (
        set -e
        "$@"
    )
    status=$?
    set -e
    timings+=("$(printf '%4ds  %s' $((SECONDS - t0)) "$name")")
    if [[ $status -ne 0 ]]; then
        echo "FAILED ($status): $name" >&2
        failed+=("$name")
        if [[ ${KEEP_GOING:-0} != 1 ]]; then
            summary
            exit "$status"
        fi
    fi
}

summary() {
    banner "summary"
    printf '%s\n' "${timings[@]}"
    echo "total: $((SECONDS - script_start)) s"
    if [[ ${#failed[@]} -gt 0 ]]; then
        printf 'FAILED: %s\n' "${failed[@]}"
    fi
}

as_root() {
    if [[ $(id -u) -eq 0 ]]; then
        "$@"
    else
        sudo "$@"
    fi
}

install_missing() {
    # (Lists are read whole before grepping: `… | grep -q` would break the writer's pipe.)
    local targets components c
    targets=$(rustup target list --installed)
    if ! grep -qx thumbv7em-none-eabihf <<<"$targets"; then
        rustup target add thumbv7em-none-eabihf
    fi
    components=$(rustup component list --installed)
    for c in clippy rustfmt; do
        if ! grep -q "^$c" <<<"$components"; then
            rustup component add "$c"
        fi
    done
    # Debian packages: QEMU for the firmware, GDAL for the GeoJSON route and GeoTIFF checks,
    # llvm-objdump and llvm-objcopy for the firmware call graphs (no recursion, stack bound),
    # cmake, g++ and libclang (bindgen) for HiGHS, which the ground tool's `milp` feature
    # builds from source.
    local packages=()
    command -v cmake >/dev/null || packages+=(cmake)
    command -v g++ >/dev/null || packages+=(g++)
    compgen -G '/usr/lib/llvm-*/lib/libclang.so*' >/dev/null || packages+=(libclang-dev)
    command -v qemu-system-arm >/dev/null || packages+=(qemu-system-arm)
    command -v ogrinfo >/dev/null || packages+=(gdal-bin)
    { command -v llvm-objdump && command -v llvm-objcopy; } >/dev/null || packages+=(llvm)
    if [[ ${#packages[@]} -gt 0 ]]; then
        as_root apt-get update
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y "${packages[@]}"
    fi
    if ! command -v defmt-print >/dev/null; then
        cargo install defmt-print --locked
    fi
    # The OMPL cross-check needs OMPL's Python bindings.
    if ! python3 -c 'import ompl, numpy' 2>/dev/null; then
        python3 -m pip install ompl numpy
    fi
    # The Voronoi cross-check needs SciPy.
    if ! python3 -c 'import scipy' 2>/dev/null; then
        python3 -m pip install scipy
    fi
    # The mission check (scripts/check_mission.py) loads the missions with pymavlink.
    if ! python3 -c 'import pymavlink' 2>/dev/null; then
        python3 -m pip install pymavlink
    fi
    local qemu_version
    qemu_version=$(qemu-system-arm --version)
    echo "rustc: $(rustc --version)"
    echo "qemu:  ${qemu_version%%$'\n'*}"
    echo "defmt-print: $(defmt-print --version)"
    echo "gdal:  $(ogrinfo --version)"
}

fmt_check() {
    cargo fmt --all --check
    (cd firmware-example && cargo fmt --check)
    (cd fuzz && cargo fmt --check)
}

ompl_reference() {
    python3 scripts/ompl_dubins_reference.py
}

scipy_voronoi_reference() {
    python3 scripts/voronoi_reference.py
}

scipy_vertical_reference() {
    python3 scripts/vertical_reference.py
}

# Builds the niendorf-urban network with the ground tool and writes the firmware's fixture
# (FIXTURE_SYNTHETIC=1: a small synthetic grid network instead, for debugging the firmware alone).
fixture() {
    local extra=()
    # shellcheck disable=SC2206 # FIXTURE_ARGS is meant to split
    extra=(${FIXTURE_ARGS:-})
    if [[ ${FIXTURE_SYNTHETIC:-0} == 1 ]]; then
        echo "network: synthetic (FIXTURE_SYNTHETIC=1)"
        cargo run --release -q -p host-tests --bin firmware_fixture -- \
            --synthetic "$fixture_dir" ${extra[@]+"${extra[@]}"}
        return
    fi
    echo "network: skyroute $SKYROUTE_BUILD_ARGS"
    mkdir -p "$(dirname "$network_src")"
    rm -f "$network_src"
    # shellcheck disable=SC2086 # the arguments are meant to split
    cargo run --release -q -p skyroute-prep --bin skyroute -- $SKYROUTE_BUILD_ARGS
    if [[ ! -f $network_src ]]; then
        echo "skyroute build did not write $network_src" >&2
        return 1
    fi
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$network_src" "$fixture_dir" ${extra[@]+"${extra[@]}"}
}

# firmware_build BIN [CARGO ARGS...]: builds the firmware binary BIN (roadmap, terrain,
# landmark, voronoi, ruz or, with `--features slices`, slices), which embeds its own fixture
# (fixture/, fixture-terrain/, fixture-landmark/, fixture-voronoi/, fixture-ruz/; slices:
# fixture/).
firmware_build() {
    local bin=$1
    shift
    (cd firmware-example && cargo build --release --bin "$bin" "$@")
}

# firmware_clippy BIN [CARGO ARGS...]: lints the firmware library and the binary BIN, warnings
# denied.
firmware_clippy() {
    local bin=$1
    shift
    (cd firmware-example && cargo clippy --release --bin "$bin" "$@" -- -D warnings)
}

terrain_fixture() {
    mkdir -p "$(dirname "$terrain_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$terrain_scenario" \
        -o "$terrain_src" --node-spacing 400 --max-edge 5000 --node-margin 60
    # shellcheck disable=SC2086 # the query's options are meant to split
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$terrain_src" "$terrain_fixture_dir" $terrain_query
}

# The larger target (firmware-example's `mps2-an500` feature: QEMU's Cortex-M7 board with an
# STM32H743's 2 MiB flash and 1 MiB RAM): the whole medeiros-jacksboro network, which the
# STM32F405's RAM cannot hold, with the terrain firmware's query.
terrain_full_fixture() {
    mkdir -p "$(dirname "$terrain_full_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$terrain_scenario" \
        -o "$terrain_full_src"
    # shellcheck disable=SC2086 # the query's options are meant to split
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$terrain_full_src" "$terrain_full_fixture_dir" $terrain_query
}

# large_target_build BIN: builds BIN for the larger target into its own target directory.
large_target_build() {
    (cd firmware-example && CARGO_TARGET_DIR=target/mps2-an500 \
        cargo build --release --features mps2-an500 --bin "$1")
}

# The babel-II-N landmark network and the fixture: the host plans stored start → stored goal in
# weather 0, loses the first landmark overflown and plans again, as the firmware will.
landmark_fixture() {
    mkdir -p "$(dirname "$landmark_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$landmark_scenario" \
        -o "$landmark_src"
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$landmark_src" "$landmark_fixture_dir"
}

# The ruz-popups Voronoi network and the fixture: the host plans P → Q, adds a radar (3 km
# reference distance) on the middle of the route's longest straight, and re-plans from 5 km along
# the route, as the firmware will.
voronoi_fixture() {
    mkdir -p "$(dirname "$voronoi_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$voronoi_scenario" \
        --mode voronoi -o "$voronoi_src"
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$voronoi_src" "$voronoi_fixture_dir" --scenario "$voronoi_scenario" \
        --threat-on-route 3000 --replan-after 5000
}

# The Ruz switch's fixture: ruz-popups as a roadmap network whose image stores every pop-up's
# bypass alternatives (`skyroute build` plans and scores them); the host plans the nominal
# route, decides a sequence of announcements, flies each choice and re-plans, and decides a
# worst case, with the core calls the firmware makes (network.bin and query.rs).
ruz_fixture() {
    mkdir -p "$(dirname "$ruz_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$ruz_scenario" -o "$ruz_src" \
        --sample-spacing "$ruz_sample_spacing"
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$ruz_src" "$ruz_fixture_dir" --ruz --scenario "$ruz_scenario"
}

# The 3-D roadmap's fixture: the query from the vertex nearest the start's altitude to the
# goal's nearest vertex's, and a 100 m pop-up on the route's longest straight reaching up to the
# middle of the vertices' altitudes (80 m).
roadmap3d_fixture() {
    mkdir -p "$(dirname "$roadmap3d_src")"
    cargo run --release -q -p skyroute-prep --bin skyroute -- build "$roadmap3d_scenario" \
        -o "$roadmap3d_src"
    cargo run --release -q -p host-tests --bin firmware_fixture -- \
        "$roadmap3d_src" "$roadmap3d_fixture_dir" --popup-on-route 100
}

# The roadmap binary with the 3-D fixture, copied as roadmap-3d.
roadmap3d_build() {
    (cd firmware-example && SKYROUTE_FIXTURE_DIR="$root/$roadmap3d_fixture_dir" \
        CARGO_TARGET_DIR=target/roadmap-3d cargo build --release --bin roadmap)
    cp "$roadmap3d_release/roadmap" "$roadmap3d_release/roadmap-3d"
}

# firmware_run ELF [MACHINE]: boots the firmware ELF under QEMU (netduinoplus2 unless MACHINE
# says otherwise); its exit code is the verdict.
# firmware_run ELF [MACHINE]: boots ELF under QEMU; its decoded log is also kept in
# target/firmware-logs/MACHINE-NAME.log (the stack bound step reads the measured peaks there).
firmware_run() {
    local machine=${2:-netduinoplus2}
    mkdir -p target/firmware-logs
    QEMU_MACHINE=$machine FIRMWARE_TIMEOUT=${FIRMWARE_TIMEOUT:-300} \
        bash scripts/run-firmware.sh "$1" 2>&1 | tee "target/firmware-logs/$machine-$(basename "$1").log"
    return "${PIPESTATUS[0]}"
}

# The static stack bound of each netduinoplus2 binary, checked against the whole-program peak
# that binary measured under QEMU.
stack_bound() {
    local peaks=() b peak
    for b in roadmap terrain landmark voronoi ruz; do
        peak=$(grep -oE 'stack: peak [0-9]+ B' "target/firmware-logs/netduinoplus2-$b.log" 2>/dev/null |
            tail -1 | grep -oE '[0-9]+' || true)
        [[ -n $peak ]] && peaks+=("$b:$peak")
    done
    STACK_PEAKS="${peaks[*]-}" scripts/stack-bound.sh
}

# firmware_size ELF [FLASH RAM]: the firmware's flash and RAM from the ELF's section headers
# (scripts/elf_sizes.py); FLASH and RAM are the target's sizes in bytes (default the
# STM32F405's 1 MiB and 128 KiB).
firmware_size() {
    python3 scripts/elf_sizes.py "$1" "${2:-1048576}" "${3:-131072}"
}

step "install missing tools" install_missing
step "cargo fmt --check" fmt_check
step "structure (file and function sizes, import cycles, mode dispatch)" \
    python3 scripts/check_structure.py
# The workspace with the ground tool's `milp` feature, then the ground tool alone with neither
# `milp` nor `png` (the crate the features change; the fuzz workspace builds it without `png`):
# every cfg of the host code, each crate checked once. The first also builds HiGHS for the test
# step: dependencies have the same profile in both (Cargo.toml), so the test step reuses the
# build scripts' output.
step "clippy (host, all targets, milp)" \
    cargo clippy --workspace --all-targets --features skyroute-prep/milp -- -D warnings
step "clippy (ground tool, all targets, without milp and png)" \
    cargo clippy -p skyroute-prep --all-targets --no-default-features -- -D warnings
step "clippy (skyroute, thumbv7em-none-eabihf)" \
    cargo clippy -p skyroute --target thumbv7em-none-eabihf -- -D warnings
step "clippy (skyroute, thumbv7em-none-eabihf, defmt)" \
    cargo clippy -p skyroute --target thumbv7em-none-eabihf --features defmt -- -D warnings
step "core docs (cargo doc, warnings denied)" \
    env RUSTDOCFLAGS="-D warnings" cargo doc -p skyroute --no-deps
step "OMPL Dubins reference" ompl_reference
step "SciPy Voronoi reference" scipy_voronoi_reference
step "SciPy vertical-profile reference (LP)" scipy_vertical_reference
step "cargo test --workspace (full tier)" \
    env SKYROUTE_TIER=full cargo test --workspace --features skyroute-prep/milp
step "C ABI (header vs cbindgen, C program vs Rust API, thumbv7em library)" scripts/ffi-check.sh
step "work bound sweep (random queries per mode, docs/RELIABILITY.md)" \
    cargo run --release -q -p host-tests --bin work_sweep -- --queries "${SWEEP_QUERIES:-20000}"
step "firmware fixture" fixture
step "firmware build (release, bin roadmap)" firmware_build roadmap
step "firmware clippy (bin roadmap)" firmware_clippy roadmap
step "firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/roadmap"
step "firmware size" firmware_size "$firmware_release/roadmap"
step "3-D roadmap firmware fixture (niendorf-urban-3d)" roadmap3d_fixture
step "3-D roadmap firmware build (release, bin roadmap, fixture-3d)" roadmap3d_build
step "3-D roadmap firmware under QEMU (netduinoplus2)" firmware_run "$roadmap3d_release/roadmap-3d"
step "3-D roadmap firmware size" firmware_size "$roadmap3d_release/roadmap-3d"
step "terrain firmware fixture (medeiros-jacksboro)" terrain_fixture
step "terrain firmware build (release, bin terrain)" firmware_build terrain
step "terrain firmware clippy (bin terrain)" firmware_clippy terrain
step "terrain firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/terrain"
step "terrain firmware size" firmware_size "$firmware_release/terrain"
step "large target: terrain firmware fixture (full medeiros-jacksboro)" terrain_full_fixture
step "large target: terrain firmware build (release, mps2-an500)" large_target_build terrain
step "large target: terrain firmware under QEMU (mps2-an500, Cortex-M7)" \
    firmware_run firmware-example/target/mps2-an500/thumbv7em-none-eabihf/release/terrain mps2-an500
step "large target: terrain firmware size" firmware_size \
    firmware-example/target/mps2-an500/thumbv7em-none-eabihf/release/terrain 2097152 1048576
step "landmark firmware fixture (babel-II-N)" landmark_fixture
step "landmark firmware build (release, bin landmark)" firmware_build landmark
step "landmark firmware clippy (bin landmark)" firmware_clippy landmark
step "landmark firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/landmark"
step "landmark firmware size" firmware_size "$firmware_release/landmark"
step "voronoi firmware fixture (ruz-popups)" voronoi_fixture
step "voronoi firmware build (release, bin voronoi)" firmware_build voronoi
step "voronoi firmware clippy (bin voronoi)" firmware_clippy voronoi
step "voronoi firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/voronoi"
step "voronoi firmware size" firmware_size "$firmware_release/voronoi"
step "ruz switch firmware fixture (ruz-popups)" ruz_fixture
step "ruz switch firmware build (release, bin ruz)" firmware_build ruz
step "ruz switch firmware clippy (bin ruz)" firmware_clippy ruz
step "ruz switch firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/ruz"
step "ruz switch firmware size" firmware_size "$firmware_release/ruz"
# Planning in slices under RTIC 2 on the roadmap fixture (the `slices` feature: RTIC and the
# STM32F405's device crate, which the other binaries do not link).
step "slices firmware build (release, bin slices, feature slices)" \
    firmware_build slices --features slices
step "slices firmware clippy (bin slices, feature slices)" \
    firmware_clippy slices --features slices
step "slices firmware under QEMU (netduinoplus2)" firmware_run "$firmware_release/slices"
step "slices firmware size" firmware_size "$firmware_release/slices"
step "no recursion in the core (the five firmware binaries' call graphs)" scripts/no-recursion.sh
step "no panic path in the core (the five firmware binaries' disassembly)" scripts/prove-no-panic.sh
step "no panic path at all (the five firmware binaries linked with an undefined panic handler)" \
    scripts/prove-no-panic-link.sh
step "stack bound (static, from the five firmware binaries' disassembly)" stack_bound

step "fuzz smoke run (each cargo-fuzz target for FUZZ_SECONDS, default 20 s)" \
    scripts/fuzz-smoke.sh

summary
[[ ${#failed[@]} -eq 0 ]]
