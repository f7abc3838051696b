//! skyroute on a Cortex-M4F: the network image lies in flash, the planner in a `static`.
//!
//! Loads `fixture/network.bin` (with the `terrain` feature: `fixture-terrain/network.bin`, a
//! terrain network over the Jacksboro DEM), adds the fixture's pop-up, then runs the
//! [`autopilot`] route task for a few cycles, measuring each `plan` call with SysTick. Logs over
//! defmt (semihosting); exits through semihosting with success only if the route's length
//! matches the one the host computed (`query.rs`, written by host-tests' `firmware_fixture`).
//!
//! With the `landmark` feature it loads `fixture-landmark/network.bin` (a Babel landmark
//! network) and runs [`landmark::run`] instead: plan from the stored start to the stored goal,
//! lose a landmark in flight (`update_rosette`), plan again; both lengths must equal the host's.
//!
//! Run it with `scripts/run-firmware.sh` (or `cargo run --release` here).
#![no_std]
#![no_main]

#[cfg(all(feature = "terrain", feature = "landmark"))]
compile_error!("the features `terrain` and `landmark` exclude each other");

// The landmark mission uses only part of the task's API (one cycle at a time, no primitives).
#[cfg_attr(feature = "landmark", allow(dead_code))]
mod autopilot;
mod clock;
#[cfg(feature = "landmark")]
mod landmark;
mod stack;

#[cfg(not(feature = "landmark"))]
use autopilot::{Cycle, Next, RouteTask};
use clock::Clock;
use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::debug::{self, ExitStatus};
use defmt_semihosting as _; // the defmt transport: semihosting writes to QEMU's stdout
use skyroute::Planner;
#[cfg(not(feature = "landmark"))]
use skyroute::{Popup, Query, Search, Vec2};
use static_cell::ConstStaticCell;

/// The generated fixture: capacities, query, pop-up, expected route length, work budget (for
/// a landmark network: capacities, weather, the landmark to lose, both expected answers).
#[cfg(not(any(feature = "terrain", feature = "landmark")))]
mod fixture {
    include!("../fixture/query.rs");
}
#[cfg(feature = "terrain")]
mod fixture {
    include!("../fixture-terrain/query.rs");
}
#[cfg(feature = "landmark")]
mod fixture {
    include!("../fixture-landmark/query.rs");
}
use fixture::*;

/// The network image, in flash (`.rodata`); the planner reads it where it lies.
#[cfg(not(any(feature = "terrain", feature = "landmark")))]
static NETWORK: &[u8] = include_bytes!("../fixture/network.bin");
#[cfg(feature = "terrain")]
static NETWORK: &[u8] = include_bytes!("../fixture-terrain/network.bin");
#[cfg(feature = "landmark")]
static NETWORK: &[u8] = include_bytes!("../fixture-landmark/network.bin");

/// The planner's state, all of it (≈ 20·V + 2·E + 140·P + 24·R + 1.3 KiB). A network too large
/// for the RAM fails at link time, not in flight. `Planner::new()` is all zero bytes, so it lands
/// in `.bss` and costs no flash (the size step reports `.data` and `.bss` separately).
type FlightPlanner = Planner<'static, V_CAP, E_CAP, P_CAP, R_CAP>;
static PLANNER: ConstStaticCell<FlightPlanner> = ConstStaticCell::new(Planner::new());

/// Plan cycles to run, and their period.
#[cfg(not(feature = "landmark"))]
const CYCLES: u32 = 3;
const PERIOD_MS: u32 = 20;
/// Largest accepted relative difference between the target's and the host's route length.
#[cfg(not(feature = "landmark"))]
const TOLERANCE: f32 = 1e-4;

#[entry]
fn main() -> ! {
    let ok = run();
    exit(ok)
}

fn run() -> bool {
    let Some(core) = cortex_m::Peripherals::take() else {
        defmt::error!("core peripherals already taken");
        return false;
    };
    let clock = Clock::start(core.SYST);
    defmt::info!(
        "skyroute firmware example: STM32F405 (Cortex-M4F), SysTick at {=u32} Hz",
        clock::CORE_HZ
    );

    let planner = PLANNER.take();
    defmt::info!(
        "planner capacities V={=usize} E={=usize} P={=usize} R={=usize}: {=usize} B of RAM",
        V_CAP,
        E_CAP,
        P_CAP,
        R_CAP,
        core::mem::size_of::<FlightPlanner>()
    );

    let t = clock.now();
    if let Err(e) = planner.load(NETWORK) {
        defmt::error!("load failed: {}", e);
        return false;
    }
    let load_ticks = clock.now() - t;
    #[cfg(not(feature = "landmark"))]
    planner.set_config(CONFIG);
    let net = planner.network();
    defmt::info!(
        "network: {=u32} vertices, {=u32} edges, {=u32} obstacles, {=usize} B in flash, turn radius {=f32} m, clearance {=f32} m",
        net.vertex_count(),
        net.edge_count(),
        net.obstacle_count(),
        net.byte_len(),
        net.turn_radius(),
        net.clearance()
    );
    defmt::info!(
        "load (validation) took {=u64} ticks = {=u64} us",
        load_ticks,
        Clock::ticks_to_us(load_ticks)
    );
    if let (Some(t), Some((altitude, safety))) = (net.terrain(), planner.altitude()) {
        defmt::info!(
            "terrain: {=u32} x {=u32} cells of {=f32} m, altitude {=f32} m, safety height {=f32} m, band +-{=f32} m, blocking code {=u8}",
            t.cols,
            t.rows,
            t.cell_m,
            altitude,
            safety,
            t.widen_m,
            planner.blocking_code()
        );
    }

    mission(planner, clock)
}

/// What the firmware does with the loaded network.
#[cfg(feature = "landmark")]
use landmark::run as mission;
#[cfg(not(feature = "landmark"))]
use popup_and_plan as mission;

/// Roadmap and terrain: adds the fixture's pop-up, then plans [`CYCLES`] times with the
/// [`RouteTask`]; true only if every route's length matches the host's.
#[cfg(not(feature = "landmark"))]
fn popup_and_plan(planner: &'static mut FlightPlanner, clock: Clock) -> bool {
    let (x, y, radius) = POPUP;
    let t = clock.now();
    let popup = planner.add_popup(Popup::Circle {
        centre: Vec2::new(x, y),
        radius,
    });
    let popup_ticks = clock.now() - t;
    match popup {
        Ok(s) => defmt::info!(
            "pop-up ({=f32}, {=f32}) r={=f32} m: {} in {=u64} ticks, bound {=u64} work",
            x,
            y,
            radius,
            s,
            popup_ticks,
            planner.worst_case_popup_work()
        ),
        Err(e) => {
            defmt::error!("add_popup failed: {}", e);
            return false;
        }
    }

    let bound = planner.worst_case_work();
    defmt::info!("worst-case work bound {=u64}, budget {=u64}", bound, BUDGET);
    if bound != BUDGET {
        defmt::warn!("the host computed a different bound: fixture out of date?");
    }

    let query = Query {
        start: START,
        goal: GOAL,
        search: Search::Dijkstra,
    };
    let mut verdict = false;
    let mut task = RouteTask::new(planner, clock, clock, PERIOD_MS, BUDGET);
    let cycles = task.run(
        // Query source: an autopilot reads its navigation filter and mission here.
        |_| query,
        // Route sink: an autopilot hands the primitives to path following here.
        |cycle: &Cycle<'_>| {
            let summary = match cycle.outcome {
                Ok(s) => s,
                Err(e) => {
                    defmt::error!("cycle {=u32}: plan failed: {}", cycle.index, e);
                    verdict = false;
                    return Next::Stop;
                }
            };
            if cycle.index == 0 {
                defmt::info!("query: {}", cycle.query);
            }
            defmt::info!(
                "cycle {=u32}: route {=f32} m, {=u32} primitives (host {=u32}), {=u32} network edges, arrival heading {=f32} rad",
                cycle.index,
                summary.length,
                summary.primitives,
                EXPECTED_PRIMITIVES,
                summary.network_edges,
                summary.arrival_heading
            );
            defmt::info!(
                "cycle {=u32}: work {=u64} (host {=u64}) of bound {=u64}: {}",
                cycle.index,
                summary.work.total(),
                EXPECTED_WORK,
                bound,
                summary.work
            );
            defmt::info!(
                "cycle {=u32}: plan took {=u64} SysTick ticks = {=u64} us at {=u32} Hz",
                cycle.index,
                cycle.plan_ticks,
                Clock::ticks_to_us(cycle.plan_ticks),
                clock::CORE_HZ
            );
            if cycle.index == 0 {
                for (i, p) in cycle.route.iter().enumerate() {
                    defmt::debug!("  primitive {=usize}: {}", i, p);
                }
            }
            let error = (summary.length - EXPECTED_LENGTH).abs() / EXPECTED_LENGTH;
            verdict = error < TOLERANCE && summary.primitives == cycle.route.len() as u32;
            if !verdict {
                defmt::error!(
                    "route length {=f32} m, host expected {=f32} m (relative error {=f32})",
                    summary.length,
                    EXPECTED_LENGTH,
                    error
                );
                return Next::Stop;
            }
            if cycle.index + 1 < CYCLES {
                Next::Continue
            } else {
                Next::Stop
            }
        },
    );
    if task.planner().network().terrain().is_some() {
        defmt::info!(
            "turn arcs checked in the last query: {}",
            task.planner().arc_check_stats()
        );
    }
    let (stack_used, stack_size) = stack::high_water();
    defmt::info!(
        "stack: peak {=usize} B of the {=usize} B left above .data/.bss",
        stack_used,
        stack_size
    );
    if verdict {
        defmt::info!(
            "PASS: {=u32} cycles, route length {=f32} m matches the host's {=f32} m",
            cycles,
            task.planner()
                .route_summary()
                .map_or(f32::NAN, |s| s.length),
            EXPECTED_LENGTH
        );
    }
    verdict
}

fn exit(ok: bool) -> ! {
    let status: ExitStatus = if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    };
    loop {
        debug::exit(status);
        cortex_m::asm::bkpt();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("panic: {}", defmt::Display2Format(info));
    exit(false)
}

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#010x}", frame.pc());
    exit(false)
}
