#!/usr/bin/env bash
# Boots a firmware ELF in QEMU (netduinoplus2: STM32F405, Cortex-M4F; or QEMU_MACHINE=mps2-an500,
# a Cortex-M7, for ELFs built with firmware-example's `mps2-an500` feature) and decodes its defmt
# output (semihosting → QEMU's stdout → defmt-print). Exits with the firmware's own verdict
# (semihosting exit status); 124 when it does not finish within FIRMWARE_TIMEOUT seconds.
#
#   scripts/run-firmware.sh path/to/firmware.elf
#
# Also the cargo runner of firmware-example (`cargo run --release` there).
set -euo pipefail

if [[ $# -lt 1 ]]; then
    echo "usage: $0 FIRMWARE.elf" >&2
    exit 2
fi
elf=$1
timeout_s=${FIRMWARE_TIMEOUT:-300}
machine=${QEMU_MACHINE:-netduinoplus2}
case $machine in
    netduinoplus2) cpu=cortex-m4 ;;
    mps2-an500) cpu=cortex-m7 ;;
    *) echo "run-firmware: unknown QEMU_MACHINE $machine (netduinoplus2 or mps2-an500)" >&2; exit 2 ;;
esac
for tool in qemu-system-arm defmt-print; do
    if ! command -v "$tool" >/dev/null; then
        echo "run-firmware: $tool is missing (scripts/test.sh installs it)" >&2
        exit 127
    fi
done

# -icount shift=0: a deterministic virtual clock, one instruction per nanosecond, so SysTick
# counts are repeatable run to run (but they are not Cortex-M4 cycle counts).
set +e
timeout --foreground "$timeout_s" \
    qemu-system-arm -cpu "$cpu" -machine "$machine" -nographic \
    -monitor none -serial null \
    -semihosting-config enable=on,target=native -icount shift=0 \
    -kernel "$elf" </dev/null |
    defmt-print -e "$elf"
status=("${PIPESTATUS[@]}")
set -e
qemu_status=${status[0]}
print_status=${status[1]}
if [[ $qemu_status -eq 124 ]]; then
    echo "run-firmware: timed out after ${timeout_s}s" >&2
elif [[ $qemu_status -ne 0 ]]; then
    echo "run-firmware: the firmware exited with status $qemu_status (failure)" >&2
elif [[ $print_status -ne 0 ]]; then
    echo "run-firmware: defmt-print failed with status $print_status" >&2
    exit "$print_status"
fi
exit "$qemu_status"
