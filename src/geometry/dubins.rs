//! Dubins shortest paths for a turn radius `r` (Dubins 1957; the six candidate words of
//! Shkel & Lumelsky 2001).
//!
//! Every word is solved from the geometry of its turning circles rather than from the normalised
//! closed forms, which makes the special cases explicit:
//! * **CSC** (LSL, RSR, LSR, RSL): the straight is the common tangent of the start circle (centre
//!   `c1`, direction `k1`) and the goal circle (`c2`, `k2`). With `v = c2 − c1`, the tangent of
//!   heading φ and length `L` satisfies `v = L·u(φ) + (k2 − k1)·r·n(φ)` (u the unit vector, n its
//!   left normal), so `L = sqrt(|v|² − (k2−k1)²r²)` and `φ = ∠v + atan2((k1−k2)·r, L)`.
//! * **CCC** (RLR, LRL): the middle circle touches both end circles, so its centre lies at
//!   `c1 + 2r·u(∠v ± γ)` with `cos γ = |v| / 4r`. Both signs are tried and the shorter kept:
//!   choosing one branch by formula is where well-known implementations went wrong.
//!
//! Pitfalls handled: an `acos`/`sqrt` argument a rounding error outside its domain is clamped;
//! coincident circle centres (a goal on the start's turning circle) take φ = start heading so
//! the path never gains a spurious full loop; turn angles within [`ANGLE_TOLERANCE`] of 2π count
//! as zero; headings of any magnitude are reduced first. Work is done relative to the start
//! position, so nearly coincident poses keep their full precision.
//!
//! [`ANGLE_TOLERANCE`]: super::ANGLE_TOLERANCE

use super::{wrap_to_pi, wrap_to_tau, Arc, Pose, Primitive, Segment, Turn, Vec2};

/// The six Dubins words. `L` left arc, `R` right arc, `S` straight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[repr(u8)]
pub enum DubinsWord {
    /// Left, straight, left.
    Lsl = 0,
    /// Right, straight, right.
    Rsr = 1,
    /// Left, straight, right.
    Lsr = 2,
    /// Right, straight, left.
    Rsl = 3,
    /// Right, left, right.
    Rlr = 4,
    /// Left, right, left.
    Lrl = 5,
}

impl DubinsWord {
    /// All six words, in their numeric order.
    pub const ALL: [DubinsWord; 6] = [
        DubinsWord::Lsl,
        DubinsWord::Rsr,
        DubinsWord::Lsr,
        DubinsWord::Rsl,
        DubinsWord::Rlr,
        DubinsWord::Lrl,
    ];

    /// The word with numeric code `code` (0–5), as stored in a network.
    pub fn from_code(code: u8) -> Option<Self> {
        Self::ALL.get(code as usize).copied()
    }

    /// The numeric code stored in a network.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The turns of the first and last letters, and of the middle one (`None` for a straight).
    pub fn letters(self) -> (Turn, Option<Turn>, Turn) {
        use Turn::{Left as L, Right as R};
        match self {
            DubinsWord::Lsl => (L, None, L),
            DubinsWord::Rsr => (R, None, R),
            DubinsWord::Lsr => (L, None, R),
            DubinsWord::Rsl => (R, None, L),
            DubinsWord::Rlr => (R, Some(L), R),
            DubinsWord::Lrl => (L, Some(R), L),
        }
    }

    /// Whether the word is curve-curve-curve.
    pub fn is_ccc(self) -> bool {
        self.letters().1.is_some()
    }

    /// The word's name in capitals, e.g. `"LSR"`.
    pub fn name(self) -> &'static str {
        ["LSL", "RSR", "LSR", "RSL", "RLR", "LRL"][self as usize]
    }
}

/// A set of admissible Dubins words (for example without the CCC words).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct WordSet(u8);

impl WordSet {
    /// All six words.
    pub const ALL: WordSet = WordSet(0b11_1111);
    /// The four CSC words only.
    pub const CSC_ONLY: WordSet = WordSet(0b00_1111);

    /// Whether `w` is in the set.
    pub fn contains(self, w: DubinsWord) -> bool {
        self.0 & (1 << w as u8) != 0
    }
}

/// One end of Dubins paths, prepared once to solve many paths from or to it: the pose with its
/// heading reduced to (−π, π], and that heading's unit vector.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DubinsEnd {
    /// The pose, its heading reduced to (−π, π].
    pub pose: Pose,
    /// The unit vector of the reduced heading.
    pub direction: Vec2,
}

impl DubinsEnd {
    /// `pose` prepared; `None` when it is not finite.
    pub fn new(pose: &Pose) -> Option<Self> {
        if !pose.is_finite() {
            return None;
        }
        let pose = Pose {
            position: pose.position,
            heading: wrap_to_pi(pose.heading),
        };
        Some(Self {
            pose,
            direction: pose.direction(),
        })
    }
}

/// A Dubins path: a start pose, a turn radius, a word and the length of each of its three
/// pieces in metres (a piece of length 0 is skipped when flown).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DubinsPath {
    /// Where the path starts.
    pub start: Pose,
    /// Turn radius, metres.
    pub radius: f32,
    /// The word.
    pub word: DubinsWord,
    /// Lengths of the three pieces, metres (arc pieces: radius × turn angle).
    pub lengths: [f32; 3],
}

impl DubinsPath {
    /// The shortest path from `start` to `goal` with turn radius `radius` over all six words.
    /// `None` when an input is not finite or the radius is not positive.
    pub fn shortest(start: &Pose, goal: &Pose, radius: f32) -> Option<Self> {
        Self::shortest_among(start, goal, radius, WordSet::ALL)
    }

    /// The shortest path using only the words in `words`. `None` when an input is not finite,
    /// the radius is not positive, or no admissible word connects the poses (possible only
    /// without the CCC words: every CSC word may be infeasible when the circles overlap, but LSL
    /// and RSR never are).
    pub fn shortest_among(start: &Pose, goal: &Pose, radius: f32, words: WordSet) -> Option<Self> {
        Self::shortest_between(
            &DubinsEnd::new(start)?,
            &DubinsEnd::new(goal)?,
            radius,
            words,
        )
    }

    /// [`DubinsPath::shortest_among`] between two prepared ends: the same path, bit for bit,
    /// without reducing the headings and evaluating their sines and cosines again for every
    /// word (or, for many paths from or to one pose, for every path).
    pub fn shortest_between(
        start: &DubinsEnd,
        goal: &DubinsEnd,
        radius: f32,
        words: WordSet,
    ) -> Option<Self> {
        let mut best: Option<Self> = None;
        for w in DubinsWord::ALL {
            if !words.contains(w) {
                continue;
            }
            if let Some(p) = Self::word_between(start, goal, radius, w) {
                if best.is_none_or(|b| p.length() < b.length()) {
                    best = Some(p);
                }
            }
        }
        best
    }

    /// The path of word `word` from `start` to `goal`, or `None` if that word cannot connect
    /// them (or an input is not finite, or the radius is not positive).
    pub fn with_word(start: &Pose, goal: &Pose, radius: f32, word: DubinsWord) -> Option<Self> {
        Self::word_between(
            &DubinsEnd::new(start)?,
            &DubinsEnd::new(goal)?,
            radius,
            word,
        )
    }

    /// [`DubinsPath::with_word`] between two prepared ends (the same path, bit for bit).
    pub fn word_between(
        start: &DubinsEnd,
        goal: &DubinsEnd,
        radius: f32,
        word: DubinsWord,
    ) -> Option<Self> {
        if !(radius > 0.0) || !radius.is_finite() {
            return None;
        }
        let r = radius;
        // Work relative to the start position.
        let s = Pose {
            position: Vec2::default(),
            heading: start.pose.heading,
        };
        let g = Pose {
            position: goal.pose.position - start.pose.position,
            heading: goal.pose.heading,
        };
        let (n1, n3) = (start.direction.perp(), goal.direction.perp());
        let (k1, middle, k3) = word.letters();
        // v = c3 − c1, formed as g + r·(k3·n3 − k1·n1) (n: the unit left normals): subtracting
        // the two r-sized centres lost the precision of a short v (≈ 1e-7·r absolute), which
        // for nearly coincident poses made the tangent direction, and so a loop, a coin toss
        // (a goal 0.3 mm straight ahead at r = 115 m got LSL/RSR loops of 2πr). With equal
        // headings the normals now cancel exactly and v is the goal offset itself.
        let v = g.position + (n3 * k3.sign() - n1 * k1.sign()) * r;
        let d = v.norm();
        let angles = match middle {
            None => csc_angles(&s, &g, k1, k3, v, d, r)?,
            // The start circle's centre, `k1.centre(&s, r)`.
            Some(_) => ccc_angles(&s, &g, k1, s.position + n1 * (r * k1.sign()), v, d, r)?,
        };
        let lengths = match middle {
            None => [angles.0 * r, angles.1, angles.2 * r],
            Some(_) => [angles.0 * r, angles.1 * r, angles.2 * r],
        };
        if lengths.iter().any(|l| !l.is_finite()) {
            return None; // poses so far apart that a length overflows f32
        }
        Some(Self {
            start: start.pose,
            radius,
            word,
            lengths,
        })
    }

    /// A lower bound of [`DubinsPath::length`] for every path these functions compute between
    /// a pose at `start` and a pose at `goal` (any headings, any word), at turn radius
    /// `radius`: no path is shorter than the distance between its ends, and the computed
    /// lengths fall short of the true ones by far less than the margin taken off (10⁻⁴ of the
    /// distance and 10⁻² of the radius; the largest shortfall is the straight of up to
    /// 6.4·10⁻³·r that a CSC word with nearly touching circles rounds to zero).
    pub fn length_lower_bound(start: Vec2, goal: Vec2, radius: f32) -> f32 {
        (start.distance(goal) * (1.0 - 1e-4) - 1e-2 * radius).max(0.0)
    }

    /// Total length, metres.
    pub fn length(&self) -> f32 {
        self.lengths[0] + self.lengths[1] + self.lengths[2]
    }

    /// The path's primitives in order; pieces of zero length are `None`.
    pub fn primitives(&self) -> [Option<Primitive>; 3] {
        self.pieces().map(|p| p.map(|(prim, _)| prim))
    }

    /// The primitives with the heading each one starts with.
    fn pieces(&self) -> [Option<(Primitive, f32)>; 3] {
        let (k1, middle, k3) = self.word.letters();
        let mut pose = self.start;
        let mut out = [None; 3];
        let kinds = [Some(k1), middle, Some(k3)];
        for ((kind, &len), slot) in kinds.iter().zip(self.lengths.iter()).zip(out.iter_mut()) {
            // A piece of zero length (or an arc whose turn angle rounds to zero) is skipped, not
            // built: a zero-length right arc has sweep −0.0, which `Arc::turn` reads as a *left*
            // turn, so its end heading came out flipped by π and every later piece was built on
            // the wrong side (e.g. RSR/RSL/RLR with a zero first arc, LRL with a zero middle
            // arc: the flown path ended far from the goal although `length()` was right).
            let angle = len / self.radius;
            if !(len > 0.0) || (kind.is_some() && !(angle > 0.0)) {
                continue;
            }
            let prim = match kind {
                Some(turn) => Primitive::Arc(Arc::from_pose(&pose, *turn, self.radius, angle)),
                None => Primitive::Line(Segment::new(
                    pose.position,
                    pose.position + pose.direction() * len,
                )),
            };
            let heading = pose.heading;
            let end = prim.pose_at(len);
            // A straight keeps the heading exactly; an arc's end heading comes from its geometry.
            pose = match prim {
                Primitive::Line(_) => Pose {
                    position: end.position,
                    heading: pose.heading,
                },
                Primitive::Arc(_) => end,
            };
            *slot = Some((prim, heading));
        }
        out
    }

    /// The pose at arc length `s` from the start (clamped to the path).
    pub fn sample(&self, s: f32) -> Pose {
        let mut rest = s.max(0.0);
        let mut last = self.start;
        for (prim, heading) in self.pieces().into_iter().flatten() {
            // On a straight the heading is the one it was built with: `Primitive::pose_at`
            // recomputes it from the rounded end points, which for a straight of a few mm at
            // coordinates of hundreds of metres is off by up to radians (0 when they coincide).
            let at = |s: f32| match prim {
                Primitive::Line(seg) => Pose {
                    position: seg.point_at(s),
                    heading,
                },
                Primitive::Arc(a) => a.pose_at(s),
            };
            let len = prim.length();
            if rest <= len {
                return at(rest);
            }
            rest -= len;
            last = at(len);
        }
        last
    }

    /// The pose at the end of the path.
    pub fn end(&self) -> Pose {
        self.sample(self.length())
    }

    /// The path that turns `turn` on radius `radius` from `start` until it heads straight at
    /// `target`, then flies straight to it (a "CS" path, the first two pieces of `LSL` or `RSR`;
    /// the heading on arrival is free). `None` if `target` lies strictly inside the turn circle
    /// (no tangent reaches it) or an input is not finite.
    ///
    /// With centre `C` and `D = target − C`, `|D| = d ≥ r`, the tangent point's polar angle
    /// about `C` is `φ ∓ acos(r/d)` (`φ` the angle of `D`; minus for a left turn): there the
    /// radius is perpendicular to the line to the target, `cos(θ − φ) = r/d`, and of the two
    /// solutions it is the one where the circle's direction of travel points at the target.
    /// The straight is `√(d² − r²)` long.
    pub fn turn_then_straight(start: &Pose, radius: f32, target: Vec2, turn: Turn) -> Option<Self> {
        if !(start.is_finite() && target.is_finite() && radius.is_finite() && radius > 0.0) {
            return None;
        }
        let centre = turn.centre(start, radius);
        let d = target - centre;
        let dist = d.norm();
        if !(dist >= radius) {
            return None;
        }
        let off = libm::acosf((radius / dist).min(1.0));
        let sign = turn.sign();
        let tangent_angle = d.angle() - sign * off;
        let start_angle = start.heading - sign * core::f32::consts::FRAC_PI_2;
        // Swept angle in the direction of travel, in [0, 2π).
        let sweep = wrap_to_tau(sign * (tangent_angle - start_angle));
        let straight = libm::sqrtf(((dist - radius) * (dist + radius)).max(0.0));
        let word = match turn {
            Turn::Left => DubinsWord::Lsl,
            Turn::Right => DubinsWord::Rsr,
        };
        Some(DubinsPath {
            start: *start,
            radius,
            word,
            lengths: [sweep * radius, straight, 0.0],
        })
    }
}

/// Turn angles (first, last) and the straight's length for a CSC word.
fn csc_angles(
    s: &Pose,
    g: &Pose,
    k1: Turn,
    k3: Turn,
    v: Vec2,
    d: f32,
    r: f32,
) -> Option<(f32, f32, f32)> {
    let (a, b) = (k1.sign(), k3.sign());
    let offset = (a - b) * r; // 0 for LSL/RSR, ±2r for LSR/RSL
    let l_sq = d * d - offset * offset;
    // Touching circles within a band of ±1e-5·offset² either side of l² = 0. Above zero as well
    // as below: the rounding error of l² (≈ 1e-6·r²) is amplified by the square root into a
    // straight of up to ~1e-3·r pointing up to ~5e-4 rad off, so an end arc that should be
    // empty became a spurious full loop (identical poses got LSR/RSL = 4πr).
    let touch = 1e-5 * offset * offset; // 0 for LSL/RSR, whose l² = d² ≥ 0
    let straight = if l_sq > touch {
        libm::sqrtf(l_sq)
    } else if l_sq >= -touch {
        0.0 // touching circles (or d = 0 for LSL/RSR)
    } else {
        return None; // overlapping circles: no inner tangent
    };
    let phi = if offset == 0.0 && d <= 1e-6 * r {
        // Coincident circles: the tangent direction is free; leaving at once avoids a full loop.
        s.heading
    } else {
        v.angle() + libm::atan2f(offset, straight)
    };
    let first = wrap_to_tau(a * (phi - s.heading));
    let last = wrap_to_tau(b * (g.heading - phi));
    Some((first, straight, last))
}

/// Turn angles of the three arcs of a CCC word, the shorter of the two middle-circle branches.
fn ccc_angles(
    s: &Pose,
    g: &Pose,
    k1: Turn,
    c1: Vec2,
    v: Vec2,
    d: f32,
    r: f32,
) -> Option<(f32, f32, f32)> {
    if d > 4.0 * r * (1.0 + 1e-6) {
        return None;
    }
    let a = k1.sign();
    let gamma = libm::acosf((d / (4.0 * r)).clamp(-1.0, 1.0));
    // Coincident end circles (same rule as for CSC): the direction of a v that is only rounding
    // noise is arbitrary and put the middle circle anywhere, so the same pose (headings equal to
    // 1e-8 rad) got RLR/LRL = 2πr; the start heading gives the empty path.
    let psi = if d > 1e-6 * r { v.angle() } else { s.heading };
    let mut best: Option<(f32, f32, f32)> = None;
    for branch in [gamma, -gamma] {
        let c2 = c1 + Vec2::from_angle(psi + branch) * (2.0 * r);
        let c3 = c1 + v;
        // Headings where the arcs meet: at the midpoint of the centres, perpendicular to them.
        let h12 = (c2 - c1).angle() + a * core::f32::consts::FRAC_PI_2;
        let h23 = (c3 - c2).angle() - a * core::f32::consts::FRAC_PI_2;
        let first = wrap_to_tau(a * (h12 - s.heading));
        let middle = wrap_to_tau(-a * (h23 - h12));
        let last = wrap_to_tau(a * (g.heading - h23));
        let total = first + middle + last;
        if best.is_none_or(|(x, y, z)| total < x + y + z) {
            best = Some((first, middle, last));
        }
    }
    best
}
