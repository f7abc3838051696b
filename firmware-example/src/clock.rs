//! A 64-bit tick counter from SysTick, and a busy-wait [`DelayNs`] on top of it.
//!
//! SysTick counts down from `0xFF_FFFF` at the core clock; its exception, taken on every wrap,
//! counts wraps, so `ticks = wraps · 2²⁴ + (0xFF_FFFF − current)`.
//!
//! **Board HAL:** on a real board the HAL configures the clock tree (the STM32F405 starts on its
//! 16 MHz HSI; a flight computer would run its PLL at 168 MHz) and usually provides a monotonic
//! timer and a `DelayNs` of its own (e.g. `stm32f4xx-hal`'s `SysDelay`/`Delay<TIMx>`). Use
//! those instead of this module and keep [`CORE_HZ`] equal to the real core clock.

use crate::autopilot::Ticks;
use core::sync::atomic::{AtomicU32, Ordering};
use cortex_m::peripheral::{syst::SystClkSource, SCB, SYST};
use cortex_m_rt::exception;
use embedded_hal::delay::DelayNs;

/// The core clock SysTick counts at. QEMU's netduinoplus2 models the STM32F405 at 168 MHz
/// (SYSCLK); with `-icount shift=0` one instruction takes 1 ns of virtual time, so a tick is
/// about six instructions there, not a cycle-accurate Cortex-M4 cycle.
#[cfg(not(feature = "mps2-an500"))]
pub const CORE_HZ: u32 = 168_000_000;
/// The core clock SysTick counts at. QEMU's mps2-an500 clocks its Cortex-M7 at 25 MHz: with
/// `-icount shift=0` a tick is 40 instructions.
#[cfg(feature = "mps2-an500")]
pub const CORE_HZ: u32 = 25_000_000;

const RELOAD: u32 = 0x00FF_FFFF;

/// SysTick wraps since [`Clock::start`].
static WRAPS: AtomicU32 = AtomicU32::new(0);

#[exception]
fn SysTick() {
    WRAPS.fetch_add(1, Ordering::Relaxed);
}

/// A handle to the running SysTick counter (it owns the peripheral, so nothing else can
/// reconfigure it). `Copy`: hand it to whatever needs time.
#[derive(Clone, Copy)]
pub struct Clock {
    _private: (),
}

impl Clock {
    /// Starts SysTick as a free-running counter at the core clock, with its wrap exception.
    pub fn start(mut syst: SYST) -> Self {
        syst.disable_counter();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_interrupt();
        syst.enable_counter();
        Self { _private: () }
    }

    /// Ticks since [`Clock::start`].
    pub fn now(&self) -> u64 {
        now()
    }

    /// Converts ticks to microseconds.
    pub fn ticks_to_us(ticks: u64) -> u64 {
        ticks * 1_000_000 / CORE_HZ as u64
    }
}

/// Ticks since SysTick was started (0 before).
pub fn now() -> u64 {
    loop {
        let wraps = WRAPS.load(Ordering::Acquire);
        let current = SYST::get_current();
        // A wrap between reading `wraps` and `current` whose exception has not run yet shows as
        // a pending SysTick with a freshly reloaded (near-full) counter.
        let pending = SCB::is_pendst_pending();
        if WRAPS.load(Ordering::Acquire) != wraps {
            continue; // the exception ran meanwhile: read again
        }
        let elapsed = RELOAD - current.min(RELOAD);
        let missed = u64::from(pending && elapsed < RELOAD / 2);
        return ((wraps as u64 + missed) << 24) + elapsed as u64;
    }
}

impl Ticks for Clock {
    fn ticks(&self) -> u64 {
        now()
    }

    fn hz(&self) -> u32 {
        CORE_HZ
    }
}

/// Busy-waits on the tick counter (QEMU has no board HAL; see the module documentation).
impl DelayNs for Clock {
    fn delay_ns(&mut self, ns: u32) {
        let ticks = (ns as u64 * CORE_HZ as u64).div_ceil(1_000_000_000);
        let start = now();
        while now().wrapping_sub(start) < ticks {
            core::hint::spin_loop();
        }
    }
}

defmt::timestamp!("{=u64:us}", Clock::ticks_to_us(now()));
