#!/usr/bin/env bash
# Whether the release firmware can recurse: disassembles each ELF given (default: every
# firmware-example binary already built for the STM32F405), builds the call graph of its direct
# calls and tail calls (bl, b, b.w and conditional branches to another function's symbol) and
# lists every cycle (a strongly connected component of more than one function, or a function
# that calls itself). Exits 1 when a cycle contains a function of the skyroute core. Calls
# through a function pointer (`blx rN`: the `dyn FnMut` observer of `plan_observed`, formatting
# callbacks) are not in the graph; the core makes none back into itself.
#
#   scripts/no-recursion.sh [ELF ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=lib/firmware-disassembly.sh
source "$root/scripts/lib/firmware-disassembly.sh"
firmware_elfs "$@"
status=0
for elf in "${elfs[@]}"; do
    disassemble "$elf" "$elf.calls.dis"
    python3 - "$elf.calls.dis" "$(basename "$elf")" <<'PY' || status=1
import collections, re, sys
path, name = sys.argv[1:]
head = re.compile(r"^([0-9a-f]+) <(.*)>:$")
call = re.compile(r"\s(bl|b|b\.w|b\.n|beq|bne|bhs|blo|bhi|bls|bge|blt|bgt|ble|bmi|bpl|bcs|bcc)(\.w|\.n)?\s+[^<]*<([^>+]+)(\+0x[0-9a-f]+)?>")
graph, cur = collections.defaultdict(set), None
for line in open(path, errors="replace"):
    m = head.match(line)
    if m:
        if not m.group(2).startswith("$"):  # $t, $d: Thumb/data mapping symbols, not functions
            cur = m.group(2)
        continue
    c = call.search(line)
    if c and c.group(3).startswith("$"):
        continue
    if c and cur and not c.group(4) and c.group(3) != cur:
        graph[cur].add(c.group(3))
    elif c and cur and not c.group(4) and c.group(3) == cur and line.split()[1] == "bl":
        graph[cur].add(cur)  # a call (not a loop's branch) to its own entry
# Tarjan's strongly connected components, iteratively.
index, low, on, stack, sccs, counter = {}, {}, set(), [], [], [0]
for root_fn in list(graph):
    if root_fn in index:
        continue
    work = [(root_fn, iter(sorted(graph.get(root_fn, ()))))]
    index[root_fn] = low[root_fn] = counter[0]; counter[0] += 1
    stack.append(root_fn); on.add(root_fn)
    while work:
        v, it = work[-1]
        nxt = next(it, None)
        if nxt is not None:
            if nxt not in index:
                index[nxt] = low[nxt] = counter[0]; counter[0] += 1
                stack.append(nxt); on.add(nxt)
                work.append((nxt, iter(sorted(graph.get(nxt, ())))))
            elif nxt in on:
                low[v] = min(low[v], index[nxt])
            continue
        work.pop()
        if work:
            low[work[-1][0]] = min(low[work[-1][0]], low[v])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v:
                    break
            if len(comp) > 1 or v in graph.get(v, ()):
                sccs.append(comp)
core = [c for c in sccs if any("skyroute::" in f and "firmware_example" not in f for f in c)]
print(f"{name}: {sum(len(v) for v in graph.values())} direct calls among {len(graph)} functions; "
      f"{len(sccs)} cycles, {len(core)} through the skyroute core")
for c in sccs:
    print(f"  {'CORE ' if c in core else '     '}" + " -> ".join(f[:80] for f in sorted(c)))
sys.exit(1 if core else 0)
PY
done
exit $status
