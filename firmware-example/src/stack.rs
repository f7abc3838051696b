//! Peak stack use, from cortex-m-rt's `paint-stack` feature: at reset the whole stack region
//! (`_stack_end` up to `_stack_start`, i.e. the RAM left above `.data`/`.bss`) is filled with
//! `STACK_PAINT_VALUE`; the deepest word that no longer holds it marks the high-water mark.
//! [`repaint`] paints the part below the current stack pointer again, so that the mark after an
//! operation is that operation's peak: the firmware measures each planner call this way.

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

/// Bytes kept unpainted below the stack pointer by [`repaint`]: its own frame and the calls it
/// makes live there.
const REPAINT_GUARD: usize = 256;

/// Paints the stack region below the current stack pointer (less [`REPAINT_GUARD`]) again, so
/// that [`high_water`] next reports the deepest use since this call.
#[inline(never)]
pub fn repaint() {
    let bottom = core::ptr::addr_of!(_stack_end) as usize;
    let sp = cortex_m::register::msp::read() as usize;
    let mut p = bottom;
    while p + REPAINT_GUARD < sp {
        // SAFETY: `bottom..sp − guard` lies below the stack pointer: no live Rust object is
        // there (the stack grows down and nothing else is placed in this region), and the
        // address is 4-byte aligned.
        unsafe { core::ptr::write_volatile(p as *mut u32, STACK_PAINT_VALUE) };
        p += 4;
    }
}
