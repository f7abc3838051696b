//! skyroute on a Cortex-M4F: what the five firmware binaries share.
//!
//! Each binary embeds its own fixture with `include!`/`include_bytes!`: `src/bin/roadmap.rs`
//! embeds `fixture/` (a roadmap network), `terrain.rs` `fixture-terrain/` (a terrain network
//! over the Jacksboro DEM), `landmark.rs` `fixture-landmark/` (a Babel landmark network),
//! `voronoi.rs` `fixture-voronoi/` (a Judd & McLain Voronoi network of radar threats): the
//! network image in flash and the constants of `query.rs` (written by host-tests'
//! `firmware_fixture`: capacities, query, the host's answers). Each keeps its planner in a
//! `static` sized by those capacities, and its entry point
//!
//! 1. calls [`start`] (or, for a Voronoi network, [`voronoi::run`] calls [`boot`] and
//!    `load_voronoi`): starts the SysTick [`clock`], loads (validates) the image and logs the
//!    network;
//! 2. runs its mission: [`popup_mission::run`] for a roadmap or terrain network (adds the
//!    fixture's pop-up, then runs the [`autopilot`] route task for a few cycles, measuring each
//!    `plan` call with SysTick; every route's length must match the host's), [`landmark::run`]
//!    for a landmark network (plans from the stored start to the stored goal, loses a landmark
//!    in flight with `update_rosette`, plans again; both answers must equal the host's),
//!    [`voronoi::run`] for a Voronoi network (plans, a radar pops up: `add_threat`, re-plans from
//!    a pose along the route; every answer must equal the host's);
//! 3. [`exit`]s through semihosting with the verdict: success only if the host match holds.
//!
//! The fifth, `ruz.rs`, embeds `fixture-ruz/` (a ruz-popups roadmap whose image stores the
//! pop-ups' bypass alternatives, and `query.rs`: announcements with the host's decisions and
//! routes), calls [`start`], lets [`ruz::run`] plan the nominal route, decide every
//! announcement from the stored alternatives, fly the choice and re-plan, comparing each answer
//! with the host's, and [`exit`]s with the verdict.
//!
//! Logs go over defmt (semihosting); panics and hard faults exit with failure. Run a binary with
//! `scripts/run-firmware.sh` (or `cargo run --release --bin roadmap` in `firmware-example/`).
#![no_std]

pub mod autopilot;
pub mod clock;
pub mod landmark;
mod log_transport;
pub mod popup_mission;
pub mod ruz;
pub mod stack;
pub mod voronoi;

use clock::Clock;
use core::sync::atomic::{AtomicUsize, Ordering};
use cortex_m_rt::{exception, ExceptionFrame};
use cortex_m_semihosting::debug::{self, ExitStatus};
use skyroute::planner::PlannerConfig;
use skyroute::Planner;

/// The route task's period (both missions), milliseconds.
pub const PERIOD_MS: u32 = 20;

/// Start-up, shared by every binary: starts SysTick, logs the planner's capacities and size,
/// loads `network` into `planner` (validating it once, timed), re-checks the image's checksum
/// as a flight loop would (`Network::verify`, timed), applies `config` when given, and logs the
/// network (and for a terrain network its grid, altitude and safety height). `None` (after
/// logging the error) when the core peripherals are taken, `load` fails or the image is
/// found corrupted.
pub fn start<const V: usize, const E: usize, const P: usize, const R: usize>(
    planner: &mut Planner<'static, V, E, P, R>,
    network: &'static [u8],
    config: Option<PlannerConfig>,
) -> Option<Clock> {
    let clock = boot::<V, E, P, R>()?;
    let (loaded, load_ticks) = with_stack_peak("load", || {
        let t = clock.now();
        let loaded = planner.load(network);
        (loaded, clock.now() - t)
    });
    if let Err(e) = loaded {
        defmt::error!("load failed: {}", e);
        return None;
    }
    if let Some(config) = config {
        planner.set_config(config);
    }
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
    // The in-flight re-check of the image in flash: one whole checksum pass, timed.
    let t0 = clock.now();
    let intact = net.verify().is_ok();
    let verify_ticks = clock.now() - t0;
    defmt::info!(
        "verify (checksum of the image in flash): {=bool} in {=u64} ticks",
        intact,
        verify_ticks
    );
    if !intact {
        return None;
    }
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
    Some(clock)
}

/// The start of every binary, before its network is loaded: takes the core peripherals,
/// starts SysTick and logs the planner's capacities and size. `None` (after logging) when the
/// core peripherals are taken already.
pub fn boot<const V: usize, const E: usize, const P: usize, const R: usize>() -> Option<Clock> {
    let clock = start_clock()?;
    defmt::info!(
        "planner capacities V={=usize} E={=usize} P={=usize} R={=usize}: {=usize} B of RAM",
        V,
        E,
        P,
        R,
        core::mem::size_of::<Planner<'static, V, E, P, R>>()
    );
    Some(clock)
}

/// Takes the core peripherals, starts SysTick and logs the board. `None` (after logging) when
/// the core peripherals are taken already.
pub fn start_clock() -> Option<Clock> {
    let Some(core) = cortex_m::Peripherals::take() else {
        defmt::error!("core peripherals already taken");
        return None;
    };
    let clock = Clock::start(core.SYST);
    defmt::info!(
        "skyroute firmware example: STM32F405 (Cortex-M4F), SysTick at {=u32} Hz",
        clock::CORE_HZ
    );
    Some(clock)
}

/// Runs `op` with the stack below the caller painted again ([`stack::repaint`]) and logs the
/// deepest stack use during it, measured from the top of RAM (so the caller's frames count).
pub fn with_stack_peak<T>(name: &str, op: impl FnOnce() -> T) -> T {
    // The mark so far is kept before the paint erases it.
    PROGRAM_PEAK.fetch_max(stack::high_water().0, Ordering::Relaxed);
    stack::repaint();
    let result = op();
    let (used, _) = stack::high_water();
    PROGRAM_PEAK.fetch_max(used, Ordering::Relaxed);
    defmt::info!("stack {=str}: peak {=usize} B", name, used);
    result
}

/// The deepest stack use seen before the last [`stack::repaint`], bytes.
static PROGRAM_PEAK: AtomicUsize = AtomicUsize::new(0);

/// Logs the peak stack use of the whole program so far (the marks of every
/// [`with_stack_peak`] and [`stack::high_water`] since); every mission ends with it.
pub fn log_stack() {
    let (now, stack_size) = stack::high_water();
    let stack_used = PROGRAM_PEAK.load(Ordering::Relaxed).max(now);
    defmt::info!(
        "stack: peak {=usize} B of the {=usize} B left above .data/.bss",
        stack_used,
        stack_size
    );
}

/// Ends the program through semihosting: QEMU exits with status 0 when `ok`, 1 otherwise.
pub fn exit(ok: bool) -> ! {
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

#[cfg(not(feature = "prove-no-panic"))]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    defmt::error!("panic: {}", defmt::Display2Format(info));
    exit(false)
}

#[cfg(feature = "prove-no-panic")]
mod panic_proof;

#[exception]
unsafe fn HardFault(frame: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc {=u32:#010x}", frame.pc());
    exit(false)
}
