//! The test tiers. `SKYROUTE_TIER=fast` (the default: plain `cargo test --workspace`) shrinks
//! the random counts and skips the tests that build whole Babel networks or the full-size
//! scenario networks repeatedly; `SKYROUTE_TIER=full` (what `scripts/test.sh` runs) runs
//! everything with the big counts. See `docs/TESTING.md`.

use std::sync::OnceLock;

/// Which tier this process runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tier {
    /// The default: what a developer runs while working (under 3 minutes warm on 2 cores).
    Fast,
    /// Everything, with the big random counts and external references.
    Full,
}

/// The tier from `SKYROUTE_TIER` (`fast` or unset: fast; `full`: full). Any other value
/// panics, so a typo does not silently run the fast tier.
pub fn tier() -> Tier {
    static TIER: OnceLock<Tier> = OnceLock::new();
    *TIER.get_or_init(|| match std::env::var("SKYROUTE_TIER") {
        Err(std::env::VarError::NotPresent) => Tier::Fast,
        Ok(v) if v.is_empty() || v.eq_ignore_ascii_case("fast") => Tier::Fast,
        Ok(v) if v.eq_ignore_ascii_case("full") => Tier::Full,
        Ok(v) => panic!("SKYROUTE_TIER={v:?}: expected `fast` (the default) or `full`"),
        Err(e) => panic!("SKYROUTE_TIER: {e}"),
    })
}

/// Whether this is the full tier.
pub fn full_tier() -> bool {
    tier() == Tier::Full
}

/// The number of random cases: `fast` in the fast tier, `full` in the full tier.
pub fn cases(fast: usize, full: usize) -> usize {
    match tier() {
        Tier::Fast => fast,
        Tier::Full => full,
    }
}

/// For a test that runs only in the full tier: in the fast tier prints that `test` was skipped
/// (and why) and returns false; in the full tier returns true. Use as
/// `if !full_tier_only("name", "builds every Babel network") { return; }`.
pub fn full_tier_only(test: &str, why: &str) -> bool {
    if full_tier() {
        return true;
    }
    skipped(test, &format!("{why}; run with SKYROUTE_TIER=full"));
    false
}

/// Prints `SKIPPED in the fast tier: …` to the process's stderr directly (not through
/// `eprintln!`, which the test harness captures), so `cargo test` shows it.
pub fn skipped(test: &str, why: &str) {
    use std::io::Write;
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED in the fast tier: {test} ({why})"
    );
}
