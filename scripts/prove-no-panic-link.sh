#!/usr/bin/env bash
# The mechanical proof that no panic path survives in the release firmware: builds each
# firmware-example binary with the `prove-no-panic` feature, whose panic handler calls a symbol
# that exists nowhere, so each link succeeds only if the optimiser removed every call to the
# handler. Builds into its own target directory (firmware-example/target/prove-no-panic), so
# the ELFs that run under QEMU are not replaced. The fixtures must exist (scripts/test.sh
# writes them). Exits 1 naming each binary whose link failed; scripts/prove-no-panic.sh then
# lists the code that can still panic.
#
#   scripts/prove-no-panic-link.sh [BIN ...]    (default: roadmap terrain landmark voronoi ruz)
#
# The `slices` binary is not in the default list: RTIC's executor and timer queue keep two
# panics of their own (docs/RELIABILITY.md, "Panic paths left in the release firmware").
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bins=("$@")
[[ ${#bins[@]} -gt 0 ]] || bins=(roadmap terrain landmark voronoi ruz)
failed=()
cd "$root/firmware-example"
for bin in "${bins[@]}"; do
    log=$(mktemp)
    if CARGO_TARGET_DIR="$root/firmware-example/target/prove-no-panic" \
        cargo build --release --bin "$bin" --features prove-no-panic >"$log" 2>&1; then
        echo "$bin: links with the undefined panic handler: no panic path survives"
    elif grep -q skyroute_firmware_can_panic "$log"; then
        echo "$bin: a panic path survives (the link needs skyroute_firmware_can_panic)"
        failed+=("$bin")
    else
        cat "$log" >&2
        echo "$bin: the build failed for another reason" >&2
        failed+=("$bin")
    fi
    rm -f "$log"
done
[[ ${#failed[@]} -eq 0 ]] || { echo "no proof for: ${failed[*]}" >&2; exit 1; }
