#!/usr/bin/env bash
# Which functions of a release firmware binary can still reach a panic: disassembles each ELF
# given (default: every firmware-example binary already built for the STM32F405) and lists every
# function that branches to a panic entry point of `core` (panic_fmt, panic_bounds_check,
# slice_index_fail, unwrap/expect failures, assertion and division panics). Exits 1 when a
# function of the skyroute core is among them. The link check, `cargo build --release
# --features prove-no-panic` in firmware-example, is the stronger form: it fails unless no
# panic path survives at all, and the firmware's own defmt transport and panic formatting keep
# it failing today (see docs/RELIABILITY.md).
#
#   scripts/prove-no-panic.sh [ELF ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=lib/firmware-disassembly.sh
source "$root/scripts/lib/firmware-disassembly.sh"
firmware_elfs "$@"
status=0
for elf in "${elfs[@]}"; do
    disassemble "$elf" "$elf.dis"
    python3 - "$elf.dis" "$(basename "$elf")" "$root/scripts/lib" <<'PY' || status=1
import collections, re, sys
sys.path.insert(0, sys.argv[3])
from panic_entries import ENTRY
path, name = sys.argv[1:3]
entry = re.compile("<" + ENTRY.pattern + ">")
cur, callers = None, collections.defaultdict(set)
for line in open(path, errors="replace"):
    m = re.match(r"^([0-9a-f]+) <(.*)>:$", line)
    if m:
        if not m.group(2).startswith("$"):  # $t, $d: Thumb/data mapping symbols, not functions
            cur = m.group(2)
        continue
    t = entry.search(line)
    if t and cur and re.search(r"\s(bl|b|b\.w|blx|beq|bne|b\.n)(\.w)?\s", line) and not cur.startswith("core::"):
        callers[cur].add(t.group(1).split("::")[-1])
core = [f for f in callers if "skyroute::" in f and "firmware_example" not in f]
print(f"{name}: {len(callers)} functions can reach a panic, {len(core)} of them in the skyroute core")
for f in sorted(callers):
    print(f"  {'CORE ' if f in core else '     '}{f[:140]} -> {', '.join(sorted(callers[f]))}")
sys.exit(1 if core else 0)
PY
done
exit $status
