//! The panic handler of a `prove-no-panic` build, shared by every firmware binary (the library's
//! and `slices`, which includes this file as its own module): it calls a function that exists
//! nowhere, so the release build links only if the optimiser removed every path to a panic, and
//! otherwise the linker names the handler (`scripts/prove-no-panic-link.sh`;
//! `scripts/prove-no-panic.sh` then names the code that still reaches one).

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    extern "C" {
        fn skyroute_firmware_can_panic() -> !;
    }
    // SAFETY: never linked; a build whose panics all optimise away has no call to it.
    unsafe { skyroute_firmware_can_panic() }
}
