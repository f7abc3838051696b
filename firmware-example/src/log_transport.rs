//! The defmt transport: frames written to QEMU's standard output through semihosting, with no
//! panic path.
//!
//! It does what `defmt-semihosting` does (encode each frame inside a critical section and
//! write the bytes with the semihosting `WRITE` call) except where that crate panics: a log
//! call that begins while another is in progress is dropped instead. That happens when an
//! exception that cannot be masked (a HardFault) logs in the middle of a log call, or when a
//! log call runs inside another's formatting (a `Format` impl that logs, or a panic raised
//! while formatting whose handler logs): the nested frame, such as that panic message, is lost,
//! and the outer call goes on. With this transport a firmware binary built with the
//! `prove-no-panic` feature links only if nothing at all can panic
//! (`scripts/prove-no-panic-link.sh`).
//!
//! The `slices` binary, which does not use this library, includes this file as its own module.

use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicU8, Ordering};
use cortex_m_semihosting::hio::{self, HostStream};

#[defmt::global_logger]
struct Logger;

/// The one encoder every log call goes through.
static TRANSPORT: Transport = Transport::new();

struct Transport {
    /// How many log calls are in progress: 0 idle, 1 a frame being written, more when a log
    /// call began inside another (those frames are dropped). Changed only inside the critical
    /// section the outer call holds, or by the call that takes it.
    depth: AtomicU8,
    /// The outermost call's critical-section state, restored when its frame ends.
    restore: UnsafeCell<critical_section::RestoreState>,
    encoder: UnsafeCell<defmt::Encoder>,
    /// The host's standard output, opened on the first frame (`None` when the host refused).
    stdout: UnsafeCell<Option<HostStream>>,
}

// SAFETY: every cell is touched only by the call that holds the critical section taken in
// `acquire` at depth 0 (single core: interrupts are masked until `release` at depth 1).
unsafe impl Sync for Transport {}

impl Transport {
    const fn new() -> Self {
        Self {
            depth: AtomicU8::new(0),
            restore: UnsafeCell::new(critical_section::RestoreState::invalid()),
            encoder: UnsafeCell::new(defmt::Encoder::new()),
            stdout: UnsafeCell::new(None),
        }
    }

    /// Whether this call owns the frame being written (depth 1), rather than being a nested
    /// call whose frame is dropped or a call outside any frame.
    fn owns_frame(&self) -> bool {
        self.depth.load(Ordering::Acquire) == 1
    }

    /// Writes `bytes` to the host; a refused write is ignored, as logging must not stop flight.
    ///
    /// # Safety
    /// Only while owning the frame.
    unsafe fn emit(&self, bytes: &[u8]) {
        // SAFETY: the caller owns the frame, so nothing else touches the cell.
        if let Some(out) = unsafe { &mut *self.stdout.get() } {
            let _ = out.write_all(bytes);
        }
    }

    fn acquire(&self) {
        // SAFETY: paired with the `critical_section::release` below or in `release`.
        let restore = unsafe { critical_section::acquire() };
        let depth = self.depth.load(Ordering::Acquire);
        if depth != 0 {
            // A log call inside a log call: the outer one keeps the section and the frame.
            self.depth.store(depth.saturating_add(1), Ordering::Relaxed);
            // SAFETY: a nested acquire's state; releasing it leaves the outer section held.
            unsafe { critical_section::release(restore) };
            return;
        }
        self.depth.store(1, Ordering::Relaxed);
        // SAFETY: depth 1 inside the critical section: this call owns every cell.
        unsafe {
            self.restore.get().write(restore);
            let stdout = &mut *self.stdout.get();
            if stdout.is_none() {
                *stdout = hio::hstdout().ok();
            }
            (*self.encoder.get()).start_frame(|b| self.emit(b));
        }
    }

    /// # Safety
    /// After `acquire`, as defmt guarantees.
    unsafe fn write(&self, bytes: &[u8]) {
        if self.owns_frame() {
            // SAFETY: this call owns the frame.
            unsafe { (*self.encoder.get()).write(bytes, |b| self.emit(b)) };
        }
    }

    /// # Safety
    /// After `acquire`, as defmt guarantees.
    unsafe fn release(&self) {
        match self.depth.load(Ordering::Acquire) {
            0 => {}
            1 => {
                // SAFETY: this call owns the frame and the critical section taken in `acquire`.
                unsafe {
                    (*self.encoder.get()).end_frame(|b| self.emit(b));
                    let restore = self.restore.get().read();
                    // Release: the encoder's writes above happen before the frame is given up.
                    self.depth.store(0, Ordering::Release);
                    critical_section::release(restore);
                }
            }
            depth => self.depth.store(depth - 1, Ordering::Relaxed),
        }
    }
}

// SAFETY: `acquire` and `release` pair as defmt requires, and a nested pair is counted.
unsafe impl defmt::Logger for Logger {
    fn acquire() {
        TRANSPORT.acquire();
    }

    unsafe fn flush() {
        // Semihosting writes block until the host has the bytes: nothing is buffered.
    }

    unsafe fn release() {
        // SAFETY: forwarded under defmt's contract.
        unsafe { TRANSPORT.release() }
    }

    unsafe fn write(bytes: &[u8]) {
        // SAFETY: forwarded under defmt's contract.
        unsafe { TRANSPORT.write(bytes) }
    }
}
