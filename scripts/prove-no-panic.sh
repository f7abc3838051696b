#!/usr/bin/env bash
# Which code of a release firmware binary can still reach a panic: disassembles each ELF given
# (default: every firmware-example binary already built for the STM32F405), finds every branch
# to a panic entry point of `core` (panic_fmt, panic_bounds_check, slice_index_fail,
# unwrap/expect failures, assertion and division panics) and names the function it is in, with
# the source frames inlined at that branch (llvm-addr2line -i). Exits 1 when any of those
# frames is in the skyroute core (`src/`), even when the core's code was inlined into a
# firmware function or into a generic function of `core`. The link check (scripts/prove-no-panic-link.sh) is the stronger form: it
# fails unless no panic path survives at all.
#
#   scripts/prove-no-panic.sh [ELF ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
# shellcheck source=lib/firmware-disassembly.sh
source "$root/scripts/lib/firmware-disassembly.sh"
firmware_elfs "$@"
status=0
for elf in "${elfs[@]}"; do
    disassemble "$elf" "$elf.dis"
    python3 - "$elf.dis" "$elf" "$root" <<'PY' || status=1
import collections, os, re, shutil, subprocess, sys
root = sys.argv[3]
sys.path.insert(0, os.path.join(root, "scripts", "lib"))
from panic_entries import ENTRY
path, elf = sys.argv[1:3]
name = os.path.basename(elf)
core_src = os.path.join(root, "src") + os.sep
entry = re.compile("<" + ENTRY.pattern + ">")
branch = re.compile(r"\s(bl|b|b\.w|blx|beq|bne|b\.n)(\.w)?\s")
cur, sites = None, []
for line in open(path, errors="replace"):
    m = re.match(r"^([0-9a-f]+) <(.*)>:$", line)
    if m:
        if not m.group(2).startswith("$"):  # $t, $d: Thumb/data mapping symbols, not functions
            cur = m.group(2)
        continue
    t = entry.search(line)
    if t and cur and branch.search(line):
        sites.append((cur, line.split(":")[0].strip(), t.group(1).split("::")[-1]))
# The source files of the frames inlined at each site, innermost first.
addr2line = shutil.which("llvm-addr2line") or shutil.which("arm-none-eabi-addr2line")
files = [[] for _ in sites]
if sites and addr2line:
    out = subprocess.run([addr2line, "-i", "-e", elf, "-a"] + ["0x" + a for _, a, _ in sites],
                         capture_output=True, text=True, check=True).stdout
    k = -1
    for l in out.splitlines():
        if l.startswith("0x"):
            k += 1
        elif k >= 0:
            files[k].append(os.path.realpath(l.rsplit(":", 1)[0]))
callers, in_core = collections.defaultdict(set), set()
for (fn, _, target), fs in zip(sites, files):
    core_frames = [f for f in fs if f.startswith(core_src)]
    # `core`'s own functions branch to its panic entry points by design; one counts only when
    # code of the skyroute core was inlined into it (a closure in a generic `core` function).
    if fn.startswith("core::") and not core_frames:
        continue
    callers[fn].add(target)
    if core_frames or ("skyroute::" in fn and "firmware_example" not in fn):
        in_core.add(fn)
        callers[fn].update("from " + os.path.relpath(f, root) for f in core_frames)
print(f"{name}: {len(callers)} functions can reach a panic, {len(in_core)} of them through the skyroute core")
if sites and not addr2line:
    print("  (no llvm-addr2line: code of the core inlined into other functions is not attributed)")
for f in sorted(callers):
    print(f"  {'CORE ' if f in in_core else '     '}{f[:140]} -> {', '.join(sorted(callers[f]))}")
sys.exit(1 if in_core else 0)
PY
done
exit $status
