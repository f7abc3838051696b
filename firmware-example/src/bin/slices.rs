//! Planning in slices under RTIC 2: the roadmap fixture's query (`fixture/`: niendorf-urban
//! with its pop-up, as `roadmap.rs` plans it) planned with `Planner::start_plan` and
//! `Planner::step` of [`SLICE_WORK`] units, the planning task yielding to the executor after
//! every slice, while a second task of the same priority ticks every [`TICK_US`] µs.
//!
//! Both tasks are async software tasks at priority 1, so they share one executor and neither
//! preempts the other: the ticker runs only when the planner yields, and its ticks during the
//! query show that slicing keeps it running. The binary logs the slices, the longest slice in
//! SysTick ticks (the 168 MHz core clock of QEMU's model; under `-icount shift=0` one
//! instruction takes 1 ns of virtual time), the ticks the ticker made while the query was in
//! progress and the longest gap between two of them, and exits 0 only if the sliced route is
//! the one a single `plan` call gives (summary equal, every path bit for bit), that route's
//! length, primitives and work are the host's, it took more than one slice, and the ticker
//! ticked during the query.
//!
//! It does not use the firmware library: the library's SysTick clock would collide with the
//! RTIC monotonic's SysTick handler. It has its own exit and fault handlers.
#![no_std]
#![no_main]

use core::future::Future;
use core::pin::Pin;
use core::sync::atomic::{AtomicU32, Ordering};
use core::task::{Context, Poll};
use cortex_m::peripheral::SYST;
use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::debug;
use rtic_monotonics::systick::prelude::*;
use skyroute::planner::PlanStep;
use skyroute::{Planner, Popup, Query, RouteSummary, Search, Vec2};
use static_cell::ConstStaticCell;

/// The defmt transport the library's binaries use (semihosting, no panic path).
#[path = "../log_transport.rs"]
mod log_transport;

// The roadmap fixture's 3-D constants (altitudes, pop-up height, altitude sum) are the
// `roadmap` binary's; this one plans the planar query.
#[allow(dead_code)]
mod fixture {
    include!(concat!(env!("ROADMAP_FIXTURE"), "/query.rs"));
}
static NETWORK: &[u8] = include_bytes!(concat!(env!("ROADMAP_FIXTURE"), "/network.bin"));
use fixture::*;

/// The core clock SysTick counts at in QEMU's netduinoplus2 (the STM32F405's SYSCLK).
const CORE_HZ: u32 = 168_000_000;
/// The monotonic's rate: SysTick interrupts at 10 kHz, each `SYSTICK_RELOAD` core ticks.
const MONO_HZ: u32 = 10_000;
const SYSTICK_RELOAD: u32 = CORE_HZ / MONO_HZ;
/// The work of one planning slice.
pub const SLICE_WORK: u64 = 5_000;
/// The ticker's period, µs.
pub const TICK_US: u32 = 200;
/// Largest accepted relative difference between the route's length and the host's.
const TOLERANCE: f32 = 1e-4;

systick_monotonic!(Mono, MONO_HZ);

/// The planner's state, in RAM (see `roadmap.rs`).
static PLANNER: ConstStaticCell<Planner<'static, V_CAP, E_CAP, P_CAP, R_CAP>> =
    ConstStaticCell::new(Planner::new());

/// Ticker ticks since start.
static TICKS: AtomicU32 = AtomicU32::new(0);
/// The longest gap between two ticks while the query is in progress, in core ticks.
static LONGEST_GAP: AtomicU32 = AtomicU32::new(0);
/// Whether the query is in progress (the ticker then measures its gaps).
static PLANNING: AtomicU32 = AtomicU32::new(0);

/// Core clock ticks since the monotonic started: the monotonic's count times the reload, plus
/// SysTick's progress through the current period (read until the count is stable across it).
fn core_ticks() -> u64 {
    loop {
        let before = Mono::now().ticks();
        let current = SYST::get_current();
        if Mono::now().ticks() == before {
            let into = (SYSTICK_RELOAD - 1).saturating_sub(current);
            return before as u64 * SYSTICK_RELOAD as u64 + into as u64;
        }
    }
}

/// Yields once to the executor: returns `Pending` after waking itself, so that the other
/// tasks of the same priority that are ready run before this one goes on.
struct YieldNow(bool);

impl Future for YieldNow {
    type Output = ();
    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<()> {
        if self.0 {
            Poll::Ready(())
        } else {
            self.0 = true;
            cx.waker().wake_by_ref();
            Poll::Pending
        }
    }
}

/// A 64-bit FNV-1a hash of the route's paths, every field's bits.
fn route_hash<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &Planner<'_, V, E, P, R>,
) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: u32| {
        for b in x.to_le_bytes() {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in planner.route_paths() {
        eat(p.start.position.x.to_bits());
        eat(p.start.position.y.to_bits());
        eat(p.start.heading.to_bits());
        eat(p.radius.to_bits());
        eat(p.word as u32);
        for l in p.lengths {
            eat(l.to_bits());
        }
    }
    h
}

/// Ends the program through semihosting: QEMU exits with status 0 when `ok`, 1 otherwise.
fn exit(ok: bool) -> ! {
    let status = if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    };
    loop {
        debug::exit(status);
        cortex_m::asm::bkpt();
    }
}

#[cfg(not(feature = "prove-no-panic"))]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("panic: {}", defmt::Display2Format(info));
    exit(false)
}

/// With the `prove-no-panic` feature the link fails unless no panic path survives, as in the
/// library's binaries.
#[cfg(feature = "prove-no-panic")]
#[path = "../panic_proof.rs"]
mod panic_proof;

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#010x}", frame.pc());
    exit(false)
}

/// The query of `roadmap.rs`'s mission.
const QUERY: Query = Query {
    start: START,
    goal: GOAL,
    search: Search::Dijkstra,
};

/// The one-call route the sliced one must equal: its summary and path hash.
struct Reference {
    summary: RouteSummary,
    hash: u64,
}

#[rtic::app(device = stm32f4::stm32f405, dispatchers = [USART1])]
mod app {
    use super::*;

    #[shared]
    struct Shared {}

    #[local]
    struct Local {
        planner: &'static mut Planner<'static, V_CAP, E_CAP, P_CAP, R_CAP>,
        reference: Reference,
    }

    /// Loads the network, converts the start from latitude and longitude (checked against the
    /// host's pose), adds the pop-up, plans once in one call (the reference), then starts the
    /// monotonic and both tasks.
    #[init]
    fn init(cx: init::Context) -> (Shared, Local) {
        let Some(planner) = PLANNER.try_take() else {
            defmt::error!("the planner was taken before init");
            exit(false);
        };
        if let Err(e) = planner.load(NETWORK) {
            defmt::error!("load failed: {}", e);
            exit(false);
        }
        planner.set_config(CONFIG);
        // The start as the autopilot gives it, in the network's frame as on the host.
        let (lon, lat, compass) = START_GEO;
        match planner.network().local_frame().pose(lon, lat, compass) {
            Ok(p)
                if p.position.x.to_bits() == START_FROM_GEO.position.x.to_bits()
                    && p.position.y.to_bits() == START_FROM_GEO.position.y.to_bits()
                    && p.heading.to_bits() == START_FROM_GEO.heading.to_bits() =>
            {
                defmt::info!("start from lon/lat: {}, the host's bit for bit", p)
            }
            other => {
                defmt::error!(
                    "start from lon/lat: {}, host {}",
                    other.ok(),
                    START_FROM_GEO
                );
                exit(false);
            }
        }
        let (x, y, radius) = POPUP;
        if let Err(e) = planner.add_popup(Popup::Circle {
            centre: Vec2::new(x, y),
            radius,
        }) {
            defmt::error!("add_popup failed: {}", e);
            exit(false);
        }
        let summary = match planner.plan(&QUERY, BUDGET) {
            Ok(s) => s,
            Err(e) => {
                defmt::error!("plan failed: {}", e);
                exit(false);
            }
        };
        let reference = Reference {
            summary,
            hash: route_hash(planner),
        };
        defmt::info!(
            "one call: {=f32} m, {=u32} primitives, work {=u64}; unit bound {=u64}",
            summary.length,
            summary.primitives,
            summary.work.total(),
            planner.step_unit_bound()
        );
        Mono::start(cx.core.SYST, CORE_HZ);
        ticker::spawn().ok();
        plan_in_slices::spawn().ok();
        (Shared {}, Local { planner, reference })
    }

    /// Ticks every [`TICK_US`] µs; while the query is in progress, records the longest gap
    /// between two ticks.
    #[task(priority = 1)]
    async fn ticker(_cx: ticker::Context) {
        let mut next = Mono::now();
        let mut last = core_ticks();
        loop {
            next += TICK_US.micros();
            Mono::delay_until(next).await;
            let now = core_ticks();
            TICKS.fetch_add(1, Ordering::Relaxed);
            if PLANNING.load(Ordering::Relaxed) == 1 {
                let gap = (now - last).min(u32::MAX as u64) as u32;
                LONGEST_GAP.fetch_max(gap, Ordering::Relaxed);
            }
            last = now;
        }
    }

    /// Plans the query again in slices of [`SLICE_WORK`], yielding after each, and checks
    /// the result against the one-call route.
    #[task(priority = 1, local = [planner, reference])]
    async fn plan_in_slices(cx: plan_in_slices::Context) {
        let planner = &mut **cx.local.planner;
        let reference = &*cx.local.reference;
        // Let the ticker start its schedule first.
        Mono::delay(1.millis()).await;
        if let Err(e) = planner.start_plan(&QUERY, BUDGET) {
            defmt::error!("start_plan refused: {}", e);
            exit(false);
        }
        PLANNING.store(1, Ordering::Relaxed);
        let ticks_before = TICKS.load(Ordering::Relaxed);
        let started = core_ticks();
        let (mut slices, mut longest, mut most_work, mut done_work) = (0u32, 0u64, 0u64, 0u64);
        let result = loop {
            let t = core_ticks();
            let step = planner.step(SLICE_WORK);
            longest = longest.max(core_ticks() - t);
            slices += 1;
            let so_far = match step {
                PlanStep::InProgress { work_so_far } => work_so_far,
                PlanStep::Done(Ok(s)) => s.work.total(),
                PlanStep::Done(Err(_)) | PlanStep::Idle => done_work,
            };
            most_work = most_work.max(so_far - done_work);
            done_work = so_far;
            match step {
                PlanStep::InProgress { .. } => YieldNow(false).await,
                PlanStep::Done(result) => break Some(result),
                PlanStep::Idle => break None,
            }
        };
        let elapsed = core_ticks() - started;
        PLANNING.store(0, Ordering::Relaxed);
        let ticks = TICKS.load(Ordering::Relaxed) - ticks_before;
        let gap = LONGEST_GAP.load(Ordering::Relaxed);
        defmt::info!(
            "sliced: {=u32} slices of {=u64} work (most in one {=u64}), longest slice {=u64} SysTick ticks, query {=u64} ticks; ticker: {=u32} ticks during the query, longest gap {=u32} ticks (period {=u32})",
            slices,
            SLICE_WORK,
            most_work,
            longest,
            elapsed,
            ticks,
            gap,
            TICK_US * (CORE_HZ / 1_000_000)
        );
        let ok = match result {
            Some(Ok(summary)) => {
                let same = summary == reference.summary && route_hash(planner) == reference.hash;
                let host = (summary.length - EXPECTED_LENGTH).abs() <= TOLERANCE * EXPECTED_LENGTH
                    && summary.primitives == EXPECTED_PRIMITIVES
                    && summary.work.total() == EXPECTED_WORK;
                defmt::info!(
                    "sliced route {=f32} m, {=u32} primitives, work {=u64}: equal to the one-call route: {=bool}; the host's ({=f32} m, work {=u64}): {=bool}",
                    summary.length,
                    summary.primitives,
                    summary.work.total(),
                    same,
                    EXPECTED_LENGTH,
                    EXPECTED_WORK,
                    host
                );
                same && host && slices > 1 && ticks > 0
            }
            Some(Err(e)) => {
                defmt::error!("sliced plan failed: {}", e);
                false
            }
            None => {
                defmt::error!("the query was cancelled");
                false
            }
        };
        exit(ok)
    }
}
