//! The onboard decision of Ruz et al.: when pop-up threats are announced, pick one bypass
//! alternative per pop-up so that the total risk is least while the mean time factor and the
//! mean fuel factor stay within their limits (the paper's eqs 33–36).
//!
//! That is a multiple-choice knapsack with two budget constraints. It is solved exactly by a
//! depth-first branch and bound over the pop-ups in fixed memory: a partial choice is cut
//! when its risk plus the least risk of every remaining pop-up cannot beat the best complete
//! choice, or when its time (fuel) plus the least time (fuel) of every remaining pop-up
//! already exceeds the budget `n·T_max` (`n·F_max`). Both cuts only discard choices that cannot
//! be optimal or feasible, so the result is the exact optimum (ties go to the first choice in
//! lexicographic order of alternative indices). Work: at most one node per prefix of a choice,
//! `Σ_{d=1..n} Π_{i≤d} a_i` ([`decision_work_bound`]), 4⁸·4/3 ≈ 87 000 for 8 pop-ups of 4
//! alternatives.

use heapless::Vec;

/// The most pop-ups one decision covers.
pub const MAX_DECISION_POPUPS: usize = 8;

/// The most alternatives a pop-up has.
pub const MAX_ALTERNATIVES: usize = 4;

/// The largest magnitude of a time or fuel factor or limit (they are normalised, near
/// [0, 1]): beyond it a figure is refused as [`DecisionError::BadNumber`], which keeps every
/// sum of at most [`MAX_DECISION_POPUPS`] factors exact enough and finite in f32.
pub const MAX_FACTOR: f32 = 1e6;

/// One bypass alternative's figures.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Alternative {
    /// Its risk R_K (a kill probability, in [0, 1]).
    pub risk: f32,
    /// Its time factor f_t (the paper's eq. 28; lower is better).
    pub time: f32,
    /// Its fuel factor F_c (eqs 30–32; lower is better).
    pub fuel: f32,
}

/// The limits on the mean factors over the pop-ups (eqs 35–36).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DecisionLimits {
    /// T_max: the largest mean time factor.
    pub time_max: f32,
    /// F_cmax: the largest mean fuel factor.
    pub fuel_max: f32,
}

/// Which limit a decision could not meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Limit {
    /// The mean time factor.
    Time,
    /// The mean fuel factor.
    Fuel,
}

/// The chosen alternatives and their figures.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Decision {
    /// The alternative chosen for each pop-up, in the order given.
    pub choice: Vec<u8, MAX_DECISION_POPUPS>,
    /// The total risk Σ R_K of the choice.
    pub risk: f32,
    /// Its mean time factor.
    pub mean_time: f32,
    /// Its mean fuel factor.
    pub mean_fuel: f32,
    /// Search nodes visited (at most [`decision_work_bound`]).
    pub work: u64,
}

/// Why [`decide`] gave no choice.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DecisionError {
    /// More than [`MAX_DECISION_POPUPS`] pop-ups.
    TooManyPopups {
        /// Pop-ups given.
        count: usize,
    },
    /// A pop-up has no alternative, or more than [`MAX_ALTERNATIVES`].
    BadAlternativeCount {
        /// The pop-up.
        popup: usize,
        /// Its alternatives.
        count: usize,
    },
    /// A figure or a limit is NaN, infinite or beyond [`MAX_FACTOR`] in magnitude, or a risk
    /// is outside [0, 1].
    BadNumber {
        /// The pop-up (`usize::MAX` for the limits).
        popup: usize,
    },
    /// No choice meets both limits. `limit` is the tightest one: `least` is the smallest mean
    /// of that factor among the choices meeting the other limit, so relaxing `limit` to `least`
    /// makes the instance feasible. When relaxing either limit alone would do, it is the one
    /// that would have to be relaxed the most, relative to itself; when only one would, that
    /// one; when neither would (no choice meets either limit), the time limit, with `least`
    /// infinite.
    Infeasible {
        /// The tightest limit.
        limit: Limit,
        /// The least mean of that factor a choice meeting the other limit reaches.
        least: f32,
        /// The limit's value.
        max: f32,
    },
}

/// The most search nodes [`decide`] visits for pop-ups with `alternatives[i]` alternatives:
/// `Σ_{d=1..n} Π_{i≤d} a_i` (one per prefix of a choice).
pub fn decision_work_bound(alternatives: &[usize]) -> u64 {
    let mut total = 0u64;
    let mut level = 1u64;
    for &a in alternatives {
        level = level.saturating_mul(a as u64);
        total = total.saturating_add(level);
    }
    total
}

/// The budget on the sum of `n` factors whose mean is limited to `max`: `s + |s|·10⁻⁶ + 10⁻⁶`
/// with `s = n·max`, computed in f32 in that order. A choice whose sum is at most the budget
/// meets the limit: the small tolerance, never negative whatever the sign of the limit, lets a
/// choice exactly at a limit meet it in spite of the rounding of the sums.
pub fn decision_budget(n: usize, max: f32) -> f32 {
    let sum = n as f32 * max;
    sum + libm::fabsf(sum) * 1e-6 + 1e-6
}

/// The search's state: the best complete choice so far and the budgets.
struct Search<'a> {
    alts: &'a [&'a [Alternative]],
    /// Least risk, time and fuel over the pop-ups from index `d` on.
    rest: [(f32, f32, f32); MAX_DECISION_POPUPS + 1],
    time_budget: f32,
    fuel_budget: f32,
    /// Which constraints apply (the infeasibility analysis drops one).
    use_time: bool,
    use_fuel: bool,
    /// What is minimised: 0 risk, 1 time, 2 fuel.
    objective: usize,
    path: [u8; MAX_DECISION_POPUPS],
    best: Option<(f32, [u8; MAX_DECISION_POPUPS])>,
    work: u64,
}

fn key(a: &Alternative, objective: usize) -> f32 {
    match objective {
        0 => a.risk,
        1 => a.time,
        _ => a.fuel,
    }
}

impl Search<'_> {
    /// Visits every choice for the pop-ups that the bounds do not prune, depth first and in
    /// alternative order, keeping the best complete one. An explicit stack of one frame per
    /// pop-up (its next alternative and the prefix's value, time and fuel) replaces recursion:
    /// at most [`MAX_DECISION_POPUPS`] + 1 frames.
    fn visit(&mut self) {
        /// A pop-up's frame: its index, the next alternative to try, the prefix's sums.
        #[derive(Clone, Copy, Default)]
        struct Frame {
            d: usize,
            next: usize,
            value: f32,
            time: f32,
            fuel: f32,
        }
        let mut frames = [Frame::default(); MAX_DECISION_POPUPS + 1];
        let mut len = 1usize;
        while let Some(top) = len.checked_sub(1) {
            let Some(&frame) = frames.get(top) else {
                break;
            };
            let Some(alts) = self.alts.get(frame.d) else {
                // Every pop-up has its alternative: a complete choice.
                if self.best.is_none_or(|(b, _)| frame.value < b) {
                    self.best = Some((frame.value, self.path));
                }
                len -= 1;
                continue;
            };
            let Some(a) = alts.get(frame.next) else {
                len -= 1; // every alternative of this pop-up tried
                continue;
            };
            let k = frame.next;
            if let Some(f) = frames.get_mut(top) {
                f.next += 1;
            }
            self.work += 1;
            let rest = self
                .rest
                .get(frame.d + 1)
                .copied()
                .unwrap_or((0.0, 0.0, 0.0));
            let (v, t, f) = (
                frame.value + key(a, self.objective),
                frame.time + a.time,
                frame.fuel + a.fuel,
            );
            let rest_value = match self.objective {
                0 => rest.0,
                1 => rest.1,
                _ => rest.2,
            };
            if self.best.is_some_and(|(b, _)| v + rest_value >= b)
                || (self.use_time && t + rest.1 > self.time_budget)
                || (self.use_fuel && f + rest.2 > self.fuel_budget)
            {
                continue;
            }
            if let Some(p) = self.path.get_mut(frame.d) {
                *p = k as u8;
            }
            if let Some(child) = frames.get_mut(len) {
                *child = Frame {
                    d: frame.d + 1,
                    next: 0,
                    value: v,
                    time: t,
                    fuel: f,
                };
                len += 1;
            }
        }
    }
}

/// Picks one alternative per pop-up (`alternatives[u]` are pop-up `u`'s) with the least total
/// risk whose mean time and fuel factors are within `limits` (the sums of the factors within
/// [`decision_budget`]). Exact (module documentation).
/// Work: at most [`decision_work_bound`] nodes; an infeasible instance takes two more
/// searches of as many to name its tightest limit (three in all). No recursion: an explicit
/// stack of at most [`MAX_DECISION_POPUPS`] + 1 frames. No pop-ups: the empty choice,
/// whatever the limits (a mean over no pop-ups constrains nothing).
pub fn decide(
    alternatives: &[&[Alternative]],
    limits: &DecisionLimits,
) -> Result<Decision, DecisionError> {
    let n = alternatives.len();
    if n > MAX_DECISION_POPUPS {
        return Err(DecisionError::TooManyPopups { count: n });
    }
    let factor = |x: f32| x.is_finite() && x.abs() <= MAX_FACTOR;
    if !(factor(limits.time_max) && factor(limits.fuel_max)) {
        return Err(DecisionError::BadNumber { popup: usize::MAX });
    }
    let mut rest = [(0.0f32, 0.0f32, 0.0f32); MAX_DECISION_POPUPS + 1];
    for (u, alts) in alternatives.iter().enumerate().rev() {
        if alts.is_empty() || alts.len() > MAX_ALTERNATIVES {
            return Err(DecisionError::BadAlternativeCount {
                popup: u,
                count: alts.len(),
            });
        }
        let valid = alts
            .iter()
            .all(|a| factor(a.time) && factor(a.fuel) && (0.0..=1.0).contains(&a.risk));
        if !valid {
            return Err(DecisionError::BadNumber { popup: u });
        }
        let least = |f: fn(&Alternative) -> f32| alts.iter().map(f).fold(f32::INFINITY, f32::min);
        let after = rest.get(u + 1).copied().unwrap_or((0.0, 0.0, 0.0));
        if let Some(r) = rest.get_mut(u) {
            *r = (
                after.0 + least(|a| a.risk),
                after.1 + least(|a| a.time),
                after.2 + least(|a| a.fuel),
            );
        }
    }
    let mut search = Search {
        alts: alternatives,
        rest,
        time_budget: decision_budget(n, limits.time_max),
        fuel_budget: decision_budget(n, limits.fuel_max),
        use_time: true,
        use_fuel: true,
        objective: 0,
        path: [0; MAX_DECISION_POPUPS],
        best: None,
        work: 0,
    };
    search.visit();
    let work = search.work;
    let Some((_, path)) = search.best else {
        return Err(infeasible(&mut search, limits));
    };
    let mut choice = Vec::new();
    let (mut risk, mut time, mut fuel) = (0.0f32, 0.0f32, 0.0f32);
    for (u, alts) in alternatives.iter().enumerate() {
        let k = path.get(u).copied().unwrap_or(0);
        let a = alts.get(k as usize).copied().unwrap_or_default();
        let _ = choice.push(k);
        risk += a.risk;
        time += a.time;
        fuel += a.fuel;
    }
    let mean = |x: f32| if n == 0 { 0.0 } else { x / n as f32 };
    Ok(Decision {
        choice,
        risk,
        mean_time: mean(time),
        mean_fuel: mean(fuel),
        work,
    })
}

/// Names the tightest limit of an infeasible instance: the least mean time among choices
/// meeting the fuel limit, and the least mean fuel among those meeting the time limit; the
/// tightest is the limit whose relaxation alone makes the instance feasible, the one that needs
/// the larger relative relaxation when both would ([`DecisionError::Infeasible`]). Work: two
/// more searches of at most [`decision_work_bound`] nodes each.
fn infeasible(search: &mut Search<'_>, limits: &DecisionLimits) -> DecisionError {
    let n = search.alts.len().max(1) as f32;
    let mut least = |objective: usize, use_time: bool, use_fuel: bool| {
        search.objective = objective;
        search.use_time = use_time;
        search.use_fuel = use_fuel;
        search.best = None;
        search.visit();
        search.best.map_or(f32::INFINITY, |(v, _)| v / n)
    };
    let time = least(1, false, true);
    let fuel = least(2, true, false);
    let over = |least: f32, max: f32| (least - max) / max.abs().max(f32::MIN_POSITIVE);
    // A limit whose relaxation alone cannot help (its `least` infinite) is not the one to name
    // while the other's can.
    let name_time = match (time.is_finite(), fuel.is_finite()) {
        (true, false) => true,
        (false, true) => false,
        _ => over(time, limits.time_max) >= over(fuel, limits.fuel_max),
    };
    if name_time {
        DecisionError::Infeasible {
            limit: Limit::Time,
            least: time,
            max: limits.time_max,
        }
    } else {
        DecisionError::Infeasible {
            limit: Limit::Fuel,
            least: fuel,
            max: limits.fuel_max,
        }
    }
}
