//! The pop-up decision on arbitrary alternatives and limits (NaN, infinities, counts beyond
//! the capacities): an error, or a choice that meets both limits with one valid alternative
//! per pop-up, within the documented work.
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use skyroute::planner::decision::{decide, decision_work_bound, Alternative, DecisionLimits};

#[derive(Arbitrary, Debug)]
struct Input {
    alternatives: Vec<Vec<(f32, f32, f32)>>,
    time_max: f32,
    fuel_max: f32,
}

fuzz_target!(|input: Input| {
    let alts: Vec<Vec<Alternative>> = input
        .alternatives
        .iter()
        .map(|a| {
            a.iter()
                .map(|&(risk, time, fuel)| Alternative { risk, time, fuel })
                .collect()
        })
        .collect();
    let slices: Vec<&[Alternative]> = alts.iter().map(|a| a.as_slice()).collect();
    let limits = DecisionLimits {
        time_max: input.time_max,
        fuel_max: input.fuel_max,
    };
    if let Ok(d) = decide(&slices, &limits) {
        assert_eq!(d.choice.len(), alts.len());
        for (u, &k) in d.choice.iter().enumerate() {
            assert!((k as usize) < alts[u].len());
        }
        // No pop-ups: the empty choice, which the limits do not constrain.
        if !alts.is_empty() {
            let tol = 1e-4 * (1.0 + limits.time_max.abs().max(limits.fuel_max.abs()));
            assert!(d.mean_time <= limits.time_max + tol, "time limit broken");
            assert!(d.mean_fuel <= limits.fuel_max + tol, "fuel limit broken");
        }
        let counts: Vec<usize> = alts.iter().map(Vec::len).collect();
        assert!(d.work <= decision_work_bound(&counts));
    }
});
