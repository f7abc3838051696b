#!/usr/bin/env bash
# Onboard figures for every scenario: builds each scenarios/*.geojson network with the ground
# tool, generates a firmware fixture for it (the fixture tool's default query for a roadmap, the
# stored start and goal of a landmark network, the terrain firmware's query for
# medeiros-jacksboro, the scenario's start and goal and a radar popping up on the route for a
# Voronoi network), links the mode's firmware binary with it for the STM32F405 (netduinoplus2)
# or, when that does not link (flash or RAM overflow), for the larger target (mps2-an500:
# 2 MiB / 1 MiB), runs it under QEMU with -icount shift=0 and prints one Markdown row per
# scenario: network bytes, where it ran, flash and RAM of the linked ELF, instructions of each
# operation (SysTick ticks × instructions per tick of the machine), counted work and its bound,
# peak stack, and the firmware's verdict (routes equal to the host's).
#
#   scripts/onboard-figures.sh [SCENARIO_NAME ...]      (default: every scenario)
#
# Writes the table to target/onboard-figures.md too. Takes about a minute per scenario (a
# release LTO link each); not part of scripts/test.sh. Needs what test.sh installs
# (thumbv7em-none-eabihf, qemu-system-arm, defmt-print).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
unset CARGO_TARGET_DIR
work=target/onboard-figures
mkdir -p "$work"
out=target/onboard-figures.md
terrain_query="--start -3547.7197,-9893.968,0.78498753 --goal 3539.5775,9895.5724 --popup-on-route 100"

cargo build --release -q -p skyroute-prep --bin skyroute
cargo build --release -q -p host-tests --bin firmware_fixture
skyroute=target/release/skyroute
fixture_tool=target/release/firmware_fixture

if [[ $# -gt 0 ]]; then
    names=("$@")
else
    names=()
    for f in scenarios/*.geojson; do names+=("$(basename "$f" .geojson)"); done
fi

header="| scenario | mode | network (B) | target | flash (B) | RAM .bss (B) | load | verify | pop-up / threat | plan | re-plan | work (bound) | peak stack (B) | verdict |"
rule="|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
printf '%s\n%s\n' "$header" "$rule" | tee "$out"

for name in "${names[@]}"; do
    scenario=scenarios/$name.geojson
    dir=$root/$work/$name
    rm -rf "$dir" && mkdir -p "$dir"
    build_args=()
    case $name in babel-I | babel-I-bridged) build_args=(--hull-repair) ;; esac
    if ! "$skyroute" build "$scenario" "${build_args[@]}" -o "$dir/src.bin" >"$dir/build.log" 2>&1; then
        echo "| $name | — | — | — | — | — | — | — | — | — | — | — | — | build failed: $(tail -1 "$dir/build.log") |" | tee -a "$out"
        continue
    fi
    mode=$("$skyroute" info "$dir/src.bin" | head -1 | sed -E 's/.*: ([a-zA-Z]+) network.*/\1/')
    bytes=$(stat -c %s "$dir/src.bin")
    case $mode in
        roadmap) bin=roadmap; fixture_args=() ;;
        terrain) bin=terrain; read -r -a fixture_args <<<"$terrain_query" ;;
        landmark) bin=landmark; fixture_args=() ;;
        voronoi | Voronoi) bin=voronoi; fixture_args=(--scenario "$scenario" --threat-on-route 3000 --replan-after 5000) ;;
        *) echo "| $name | $mode | $bytes | — | — | — | — | — | — | — | — | — | — | unknown mode |" | tee -a "$out"; continue ;;
    esac
    if ! "$fixture_tool" "$dir/src.bin" "$dir/fixture" "${fixture_args[@]}" >"$dir/fixture.log" 2>&1; then
        echo "| $name | $mode | $bytes | — | — | — | — | — | — | — | — | — | — | fixture failed: $(tail -1 "$dir/fixture.log") |" | tee -a "$out"
        continue
    fi
    target=""
    for machine in netduinoplus2 mps2-an500; do
        features=()
        [[ $machine == mps2-an500 ]] && features=(--features mps2-an500)
        if (cd firmware-example && SKYROUTE_FIXTURE_DIR="$dir/fixture" \
            CARGO_TARGET_DIR="target/figures-$machine" \
            cargo build --release "${features[@]}" --bin "$bin") >"$dir/link-$machine.log" 2>&1; then
            target=$machine
            break
        fi
    done
    if [[ -z $target ]]; then
        echo "| $name | $mode | $bytes | none | — | — | — | — | — | — | — | — | — | links for neither target: $(grep -m1 -oE "region \`[A-Z]+' overflowed by [0-9]+ bytes" "$dir/link-mps2-an500.log" || echo 'see link log') |" | tee -a "$out"
        continue
    fi
    elf=firmware-example/target/figures-$target/thumbv7em-none-eabihf/release/$bin
    set +e
    QEMU_MACHINE=$target FIRMWARE_TIMEOUT=${FIRMWARE_TIMEOUT:-600} \
        bash scripts/run-firmware.sh "$elf" >"$dir/run.log" 2>&1
    status=$?
    set -e
    python3 - "$elf" "$dir/run.log" "$name" "$mode" "$bytes" "$target" "$status" <<'EOF' | tee -a "$out"
import re, sys
sys.path.insert(0, "scripts")
from elf_sizes import sizes
elf, log, name, mode, size, target, status = sys.argv[1:]
flash, ram, _ = sizes(elf, 0x10000000)  # the whole RAM window of either target
text = open(log, errors="replace").read()
per_tick = {"netduinoplus2": 168e6, "mps2-an500": 25e6}[target]
per_tick = 1e9 / per_tick  # -icount shift=0: one instruction per virtual nanosecond
def ticks(pattern):
    m = re.search(pattern, text)
    return f"{int(m.group(1)) * per_tick / 1e6:.2f} M" if m else "—"
load = ticks(r"load(?:_voronoi)? \(validation[^)]*\) took (\d+) ticks")
verify = ticks(r"verify \(checksum[^)]*\): true in (\d+) ticks")
popup = ticks(r"(?:pop-up|add_threat) \([^)]*\)[^\n]* in (\d+) ticks")
plan = ticks(r"(?:cycle 0: plan|plan:) took (\d+) SysTick ticks")
replan = ticks(r"re-plan: took (\d+) SysTick ticks")
w = re.search(r"work (\d+)(?: \(host \d+\))? of bound (\d+)", text)
work = f"{int(w.group(1)):,} ({int(w.group(2)):,})".replace(",", " ") if w else "—"
s = re.search(r"stack: peak (\d+) B", text)
stack = s.group(1) if s else "—"
verdict = "PASS (routes equal to the host's)" if status == "0" and "PASS" in text else f"FAIL (exit {status})"
machine = {"netduinoplus2": "STM32F405", "mps2-an500": "larger (M7)"}[target]
print(f"| {name} | {mode} | {int(size):,} | {machine} | {flash:,} | {ram:,} | {load} | {verify} | {popup} | {plan} | {replan} | {work} | {stack} | {verdict} |".replace(",", " "))
EOF
done
echo "wrote $out"
