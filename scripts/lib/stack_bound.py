"""The static stack bound of one firmware binary from its llvm-objdump disassembly.

Usage: stack_bound.py DISASSEMBLY NAME [PEAKS]; see scripts/stack-bound.sh for the method.
"""

import collections
import re
import struct
import subprocess
import sys

from panic_entries import ENTRY

HEAD = re.compile(r"^([0-9a-f]+) <(.*)>:$")
INSN = re.compile(r"^\s*[0-9a-f]+:\s+(\S+)\s*(.*)$")
TARGET = re.compile(r"<([^>+]+)(\+0x[0-9a-f]+)?>")
BRANCHES = {"b", "b.w", "b.n"} | {
    "b" + cc + suffix
    for cc in ("eq", "ne", "hs", "lo", "hi", "ls", "ge", "lt", "gt", "le", "mi", "pl", "cs", "cc", "vs", "vc")
    for suffix in ("", ".w", ".n")
}
# A Cortex-M4F exception entry with the FPU context: 8 words of integer state, 16 S registers,
# FPSCR and one reserved word (ARMv7-M ARM, B1.5.7).
EXCEPTION_ENTRY = 26 * 4
# Handlers that run on the thread's stack besides `main`'s tree; HardFault does not return,
# so its frame adds to whatever was in use when it was taken, like SysTick's.
HANDLERS = ("SysTick", "HardFault")
def register_count(operands):
    """Registers in a `{r4, r5, lr}` or `{d8-d11}` list."""
    body = operands[operands.index("{") + 1 : operands.index("}")]
    n = 0
    for part in body.split(","):
        part = part.strip()
        if "-" in part:
            lo, hi = part.split("-")
            n += int(hi[1:]) - int(lo[1:]) + 1
        elif part:
            n += 1
    return n, body.strip()[0]


def immediate(text):
    m = re.search(r"#(-?(?:0x[0-9a-f]+|\d+))", text)
    return abs(int(m.group(1), 0)) if m else None


def stack_taken(mnemonic, operands):
    """Bytes an instruction takes from the stack pointer (0 for all else)."""
    if mnemonic in ("push", "push.w") or (mnemonic.startswith("stmdb") and operands.startswith("sp!")):
        return 4 * register_count(operands)[0]
    if mnemonic == "vpush":
        n, kind = register_count(operands)
        return n * (8 if kind == "d" else 4)
    if mnemonic in ("sub", "sub.w", "subw") and re.match(r"sp,\s*(sp,\s*)?#", operands):
        return immediate(operands)
    if mnemonic.startswith("str") and re.search(r"\[sp, #-\d+\]!", operands):
        return immediate(operands.split("[sp")[1])
    if re.match(r"(sub|add|mov)(s|\.w)?$", mnemonic) and re.match(r"sp,\s*r\d", operands):
        raise ValueError(f"a stack pointer set from a register: {mnemonic} {operands}")
    return 0


def parse(path):
    frames = collections.Counter()
    calls = collections.defaultdict(set)
    indirect = collections.defaultdict(int)
    starts = {}
    current = None
    for line in open(path, errors="replace"):
        m = HEAD.match(line)
        if m:
            if not m.group(2).startswith("$"):  # $t, $d: Thumb/data mapping symbols
                current = m.group(2)
                frames[current] += 0
                starts[int(m.group(1), 16)] = current
            continue
        m = INSN.match(line)
        if not m or current is None:
            continue
        mnemonic, operands = m.group(1), m.group(2)
        frames[current] += stack_taken(mnemonic, operands)
        if mnemonic in ("bl", "blx") or mnemonic in BRANCHES:
            t = TARGET.search(operands)
            if t and not t.group(2) and not t.group(1).startswith("$") and t.group(1) != current:
                # A panic ends the program (the handler logs and exits, and may itself panic:
                # the firmware's one call cycle), so the bound covers the paths that do not.
                if not ENTRY.match(t.group(1)):
                    calls[current].add(t.group(1))
            elif t is None and mnemonic == "blx":
                indirect[current] += 1
        elif mnemonic == "bx" and not operands.startswith("lr"):
            indirect[current] += 1
    return frames, calls, indirect, starts


def address_taken(elf, path, starts):
    """Functions whose address the program holds: a Thumb address (bit 0 set) of a function's
    first instruction in `.rodata` or `.data` (vtables, function pointers), in a literal pool
    (`.word`), or built by a `movw`/`movt` pair. A call through a pointer can reach only these."""
    taken = set()
    for section in (".rodata", ".data"):
        raw = subprocess.run(
            ["llvm-objcopy", "-O", "binary", f"--only-section={section}", elf, "/dev/stdout"],
            capture_output=True,
            check=True,
        ).stdout
        for i in range(0, len(raw) - 3, 4):
            word = struct.unpack_from("<I", raw, i)[0]
            if word & 1 and word - 1 in starts:
                taken.add(starts[word - 1])
    low = {}
    for line in open(path, errors="replace"):
        m = re.search(r"\.word\s+0x([0-9a-f]+)", line)
        if m and int(m.group(1), 16) & 1 and int(m.group(1), 16) - 1 in starts:
            taken.add(starts[int(m.group(1), 16) - 1])
        m = re.search(r"\s(movw|movt)\s+(r\d+), #(\d+)", line)
        if m and m.group(1) == "movw":
            low[m.group(2)] = int(m.group(3))
        elif m and m.group(2) in low:
            word = int(m.group(3)) << 16 | low.pop(m.group(2))
            if word & 1 and word - 1 in starts:
                taken.add(starts[word - 1])
    return taken


def bounds(frames, calls):
    """Each function's frame plus its deepest callee's bound, and the call cycles met (each cut
    at the call that closes it, so the bound holds for the paths that do not recurse)."""
    bound, deepest, cycles = {}, {}, []
    for root in frames:
        if root in bound:
            continue
        work = [(root, iter(sorted(calls.get(root, ()))))]
        while work:
            fn, it = work[-1]
            nxt = next(it, None)
            if nxt is not None:
                if nxt not in bound:
                    on_path = [w[0] for w in work]
                    if nxt in on_path:
                        cycles.append(on_path[on_path.index(nxt) :])
                        continue
                    work.append((nxt, iter(sorted(calls.get(nxt, ())))))
                continue
            work.pop()
            best = max(calls.get(fn, ()), key=lambda c: bound.get(c, 0), default=None)
            bound[fn] = frames.get(fn, 0) + (bound.get(best, 0) if best else 0)
            deepest[fn] = best
    return bound, deepest, cycles


def reachable(calls, roots):
    seen, todo = set(roots), list(roots)
    while todo:
        for c in calls.get(todo.pop(), ()):
            if c not in seen:
                seen.add(c)
                todo.append(c)
    return seen


def short(name):
    name = re.sub(r"::h[0-9a-f]{16}$", "", name)
    for a, b in (("$LT$", "<"), ("$GT$", ">"), ("$u20$", " "), ("$C$", ","), ("..", "::"), ("$u7b$", "{"), ("$u7d$", "}")):
        name = name.replace(a, b)
    return name


def is_core(fn):
    return short(fn).startswith(("skyroute::", "<skyroute::", "_<skyroute::")) and "firmware" not in fn


def main():
    path, name, elf = sys.argv[1:4]
    peaks = dict(p.split(":") for p in (sys.argv[4] if len(sys.argv) > 4 else "").split())
    frames, calls, indirect, starts = parse(path)
    taken = {f for f in address_taken(elf, path, starts) if not ENTRY.match(f)}
    for fn in indirect:
        calls[fn] |= taken - {fn}
    bound, deepest, cycles = bounds(frames, calls)
    roots = ["main", *[h for h in HANDLERS if h in frames]]
    live = reachable(calls, roots)
    status = 0
    handlers = max((bound[h] for h in HANDLERS if h in bound), default=0)
    total = bound["main"] + EXCEPTION_ENTRY + handlers
    print(
        f"{name}: main {bound['main']} B + exception entry {EXCEPTION_ENTRY} B"
        f" + deepest handler {handlers} B = {total} B"
        f" ({len(taken)} functions called through pointers, from {len(indirect)} functions)"
    )
    chain, fn = [], "main"
    while fn:
        chain.append(f"{short(fn)[-60:]} ({frames[fn]})")
        fn = deepest.get(fn)
    print("  deepest chain: " + " -> ".join(chain))
    # The planner operations: core functions that the firmware's own code calls.
    entries = sorted(
        {c for f in live if not is_core(f) for c in calls.get(f, ()) if is_core(c)},
        key=lambda f: -bound[f],
    )
    for f in entries:
        print(f"  core entry {bound[f]:6d} B  {short(f)[:110]}")
    for cycle in cycles:
        if set(cycle) & live:
            core = any(is_core(f) for f in cycle)
            print(f"  {'CORE ' if core else ''}cycle cut: " + " -> ".join(short(f)[-50:] for f in cycle))
            status |= core
    if name in peaks and int(peaks[name]) > total:
        print(f"  MEASURED PEAK {peaks[name]} B ABOVE THE BOUND {total} B")
        status = 1
    elif name in peaks:
        print(f"  measured peak under QEMU {peaks[name]} B <= the bound {total} B")
    sys.exit(status)


main()
