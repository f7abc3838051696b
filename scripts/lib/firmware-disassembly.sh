# Sourced by scripts/prove-no-panic.sh and scripts/no-recursion.sh: `firmware_elfs ELF...` sets
# `elfs` to the ELFs given, or by default to every firmware-example binary already built for
# the STM32F405; `disassemble ELF OUT` writes its demangled disassembly with llvm-objdump (or
# arm-none-eabi-objdump), exiting 2 when neither is installed.
firmware_elfs() {
    local root
    root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
    elfs=("$@")
    if [[ ${#elfs[@]} -eq 0 ]]; then
        for b in roadmap terrain landmark voronoi ruz; do
            elfs+=("$root/firmware-example/target/thumbv7em-none-eabihf/release/$b")
        done
    fi
    local elf
    for elf in "${elfs[@]}"; do
        [[ -f $elf ]] || { echo "$(basename "$0"): $elf not built" >&2; exit 2; }
    done
}

disassemble() {
    local objdump
    objdump=$(command -v llvm-objdump || command -v arm-none-eabi-objdump || true)
    if [[ -z $objdump ]]; then
        echo "$(basename "$0"): llvm-objdump (Debian: llvm) or arm-none-eabi-objdump is needed" >&2
        exit 2
    fi
    "$objdump" -d --no-show-raw-insn -C "$1" >"$2" 2>/dev/null || "$objdump" -d -C "$1" >"$2"
}
