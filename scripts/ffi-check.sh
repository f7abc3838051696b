#!/usr/bin/env bash
# The C ABI's checks (ffi/, docs/INTEGRATION.md):
#   1. the committed header ffi/include/skyroute.h is what cbindgen (pinned below; installed
#      with `cargo install --locked` if absent) generates from ffi/ now;
#   2. the host static library, the niendorf-urban network (the ground tool), the C test
#      program ffi/tests/c/plan.c compiled with gcc against both, and the Rust test
#      ffi/tests/c_plan.rs that runs the C program and compares its output with the same calls
#      through the Rust API, floats bit for bit;
#   3. the static library for thumbv7em-none-eabihf (the target added with rustup if missing),
#      with its size and the planner's RAM there.
# Runnable from any directory; stops at the first failure.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
unset CARGO_TARGET_DIR
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

cbindgen_version=0.29.4
target=thumbv7em-none-eabihf
out=target/ffi
mkdir -p "$out"

banner() {
    printf '\n\033[1m---- %s ----\033[0m\n' "$*"
}

banner "header (cbindgen $cbindgen_version)"
if [[ $(cbindgen --version 2>/dev/null || true) != "cbindgen $cbindgen_version" ]]; then
    cargo install cbindgen --locked --version "$cbindgen_version"
fi
(cd ffi && cbindgen --quiet --config cbindgen.toml --crate skyroute-ffi \
    --output "$root/$out/skyroute.h")
if ! diff -u ffi/include/skyroute.h "$out/skyroute.h"; then
    echo "ffi/include/skyroute.h is not what cbindgen generates from ffi/: copy $out/skyroute.h" \
        "over it (the diff above is committed → generated)" >&2
    exit 1
fi
echo "ffi/include/skyroute.h is up to date"

banner "host static library, network, C program"
cargo build -q --release -p skyroute-ffi
cargo build -q --release -p skyroute-prep --bin skyroute
network=$out/niendorf-urban.bin
target/release/skyroute build scenarios/niendorf-urban.geojson -o "$network" >/dev/null
gcc -std=c11 -Wall -Wextra -Wpedantic -Werror -O2 -I ffi/include ffi/tests/c/plan.c \
    target/release/libskyroute_ffi.a -lpthread -ldl -lm -o "$out/plan"
echo "host libskyroute_ffi.a: $(stat -c %s target/release/libskyroute_ffi.a) bytes"

banner "C program against the Rust API"
# Absolute paths: cargo runs the test in ffi/.
SKYROUTE_FFI_PLAN=$root/$out/plan SKYROUTE_FFI_NETWORK=$root/$network \
    cargo test -q --release -p skyroute-ffi --test c_plan -- --ignored

banner "$target static library"
installed=$(rustup target list --installed)
if ! grep -qx "$target" <<<"$installed"; then
    rustup target add "$target"
fi
cargo build -q --release -p skyroute-ffi --target "$target"
lib=target/$target/release/libskyroute_ffi.a
echo "$lib: $(stat -c %s "$lib") bytes (with the release profile's line tables)"
# The library needs nothing from outside it (no C library, no allocator): every symbol a member
# uses, a member defines (readelf: nm would read the members' embedded LLVM bitcode).
members=$(mktemp -d)
(cd "$members" && ar x "$root/$lib")
undefined=$(for o in "$members"/*.o; do readelf -sW "$o"; done |
    awk '$7 == "UND" && $8 != "" {print $8}' | sort -u)
defined=$(for o in "$members"/*.o; do readelf -sW "$o"; done |
    awk '$7 != "UND" && ($5 == "GLOBAL" || $5 == "WEAK") {print $8}' | sort -u)
rm -rf "$members"
external=$(comm -23 <(echo "$undefined") <(echo "$defined"))
if [[ -n $external ]]; then
    echo "the $target library needs symbols it does not define:" $external >&2
    exit 1
fi
echo "every symbol the library uses, it defines"
if command -v llvm-size >/dev/null && command -v llvm-objdump >/dev/null; then
    # Every member's code and data (the Rust core library's included): an upper bound of what a
    # link with --gc-sections keeps.
    llvm-size -t "$lib" | tail -n 1 |
        awk '{print "all members: text " $1 " B, data " $2 " B, bss " $3 " B"}'
    # The planner's bytes on the target: the constant sr_planner_size() returns (movw/movt).
    llvm-objdump -d --disassemble-symbols=sr_planner_size "$lib" 2>/dev/null |
        awk '/movw\tr0, #/ {sub(/#/, "", $NF); lo = $NF} /movt\tr0, #/ {sub(/#/, "", $NF); hi = $NF}
             END {if (lo != "") print "planner on the target: " hi * 65536 + lo " B (sr_planner_size)"}'
else
    echo "llvm-size or llvm-objdump not installed: section sizes not shown"
fi
