#!/usr/bin/env bash
# A static upper bound on the stack of each release firmware binary, from its disassembly alone
# (no run): every function's frame is the sum of all that it takes from the stack pointer
# (`push`, `push.w`, `vpush`, `sub sp, #N`, `str rN, [sp, #-N]!`; the sum over all of them, so
# a frame set up on two paths is counted twice, never missed; a stack pointer set from a
# register fails the run), and the bound of a function is its frame plus the largest bound
# among the functions it calls directly or by a tail call. A call through a pointer (`blx rN`,
# `bx rN`) may reach every function whose address the program holds (found in `.rodata`,
# `.data`, literal pools and `movw`/`movt` pairs). Calls into panic entry points are cut: a
# panic ends the program. The bound is a longest path in that graph; a cycle (recursion, or the
# over-approximated pointer calls of the formatting code) is cut where it closes and printed,
# and a cycle through the skyroute core fails the run (scripts/no-recursion.sh proves there is
# none among direct calls).
#
# Printed per binary: the bound from `main` plus a Cortex-M4F exception entry with its FPU
# context (26 words) plus the deepest exception handler (SysTick; HardFault does not return, so
# it adds to whatever was in use when taken; exceptions here do not nest), the deepest chain,
# and the bound from each core function the firmware calls.
#
#   scripts/stack-bound.sh [ELF ...]     (default: every firmware-example release binary)
#   STACK_PEAKS="roadmap:10584 ..." scripts/stack-bound.sh   (also fails when a measured
#                                        whole-program peak exceeds its binary's bound)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=lib/firmware-disassembly.sh
source "$root/scripts/lib/firmware-disassembly.sh"
firmware_elfs "$@"
status=0
for elf in "${elfs[@]}"; do
    disassemble "$elf" "$elf.stack.dis"
    python3 "$root/scripts/lib/stack_bound.py" "$elf.stack.dis" "$(basename "$elf")" "$elf" \
        "${STACK_PEAKS:-}" || status=1
done
exit $status
