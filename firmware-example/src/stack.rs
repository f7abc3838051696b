//! Peak stack use, from cortex-m-rt's `paint-stack` feature: at reset the whole stack region
//! (`_stack_end` up to `_stack_start`, i.e. the RAM left above `.data`/`.bss`) is filled with
//! `STACK_PAINT_VALUE`; the deepest word that no longer holds it marks the high-water mark.

use cortex_m_rt::STACK_PAINT_VALUE;

extern "C" {
    /// Lowest address of the stack region (end of `.bss`/`.uninit`), from cortex-m-rt's link.x.
    static _stack_end: u32;
    /// Initial stack pointer (top of RAM).
    static _stack_start: u32;
}

/// `(used, size)` in bytes: the most stack used so far, and the stack region's size.
pub fn high_water() -> (usize, usize) {
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let top = core::ptr::addr_of!(_stack_start) as usize;
    let mut p = bottom;
    while p < top {
        // SAFETY: `bottom..top` is RAM that cortex-m-rt reserves for the stack and painted at
        // reset; words below the current stack pointer belong to no Rust object, and words
        // above it are only read (volatile, aligned: both symbols are 4-byte aligned).
        let word = unsafe { core::ptr::read_volatile(p as *const u32) };
        if word != STACK_PAINT_VALUE {
            break;
        }
        p += 4;
    }
    (top - p, top - bottom)
}
