//! What a network was built from, as digests stored in the image, and the check that a scenario
//! still matches them before anything is planned with it.
//!
//! Every part of a scenario that decides what the aircraft may fly through gets one SHA-256
//! digest (its first 8 bytes are stored, [`ProvenanceRecord`]): the mode, the vehicle, the
//! clearance, each no-fly zone, each threat disc, each landmark with its rosettes (in order:
//! the network indexes landmarks by position in the file), the weather names, the DEM file's
//! bytes with the altitude and safety height, and in landmark mode the start and the goal (a
//! landmark network fixes them at build time). The digests are of the parsed values (`f64`
//! bits, names), so reformatting the file changes nothing. Not digested, because they only set
//! how dense the network is and may be overridden on the command line: sample spacing,
//! neighbour radius, k-nearest fallback, CCC words, arc step, line elements, seed, directions
//! (the rosettes' length is in the landmark digests) and threat weight (threat circles are hard
//! discs today); nor the query (start, waypoints, goal outside landmark mode) and the `popup`
//! features, which `skyroute plan` applies in flight.

use crate::scenario::{Endpoint, Mode, Scenario};
use sha2::{Digest, Sha256};
use skyroute::network::format::ProvenanceRecord;
use skyroute::Network;
use std::fmt;
use std::path::Path;

/// What a provenance record is the digest of. The codes are stored in network images: never
/// renumber one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(u8)]
pub enum Kind {
    /// `planner.mode`.
    Mode = 1,
    /// Every `vehicle` field.
    Vehicle = 2,
    /// `planner.clearance_m` as the build used it (0 when absent).
    Clearance = 3,
    /// One no-fly zone's ring (after `--hull-repair`, if it was given).
    NoFly = 4,
    /// One threat disc: centre and radius.
    Threat = 5,
    /// One landmark: its index, name, position, `d_max_m` and every rosette.
    Landmark = 6,
    /// The weather names, in order.
    Weather = 7,
    /// The DEM file's bytes, the flight altitude and the safety height.
    Terrain = 8,
    /// Landmark mode: the start and the goal (position, heading, range).
    Endpoints = 9,
}

impl Kind {
    const ALL: [Kind; 9] = [
        Kind::Mode,
        Kind::Vehicle,
        Kind::Clearance,
        Kind::NoFly,
        Kind::Threat,
        Kind::Landmark,
        Kind::Weather,
        Kind::Terrain,
        Kind::Endpoints,
    ];

    fn from_code(code: u8) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| *k as u8 == code)
    }

    /// Whether a scenario has exactly one item of this kind (where it has any).
    fn is_single(self) -> bool {
        !matches!(self, Kind::NoFly | Kind::Threat | Kind::Landmark)
    }

    /// How a person calls one item of this kind, singular and plural.
    fn nouns(self) -> (&'static str, &'static str) {
        match self {
            Kind::Mode => ("planner.mode", "planner.mode"),
            Kind::Vehicle => ("vehicle", "vehicles"),
            Kind::Clearance => ("planner.clearance_m", "clearances"),
            Kind::NoFly => ("no-fly zone", "no-fly zones"),
            Kind::Threat => ("threat", "threats"),
            Kind::Landmark => ("landmark", "landmarks"),
            Kind::Weather => ("weather list", "weather lists"),
            Kind::Terrain => (
                "terrain (DEM file, altitude_m, safety_height_m)",
                "terrains",
            ),
            Kind::Endpoints => ("start and goal", "start and goal"),
        }
    }
}

/// One digested part of a scenario, with a label that names it in messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Item {
    /// What it is.
    pub kind: Kind,
    /// The first 8 bytes of its SHA-256, little-endian.
    pub digest: u64,
    /// How messages name it, e.g. `no-fly zone "B12"`.
    pub label: String,
}

impl Item {
    /// The record stored in a network image.
    pub fn record(&self) -> ProvenanceRecord {
        ProvenanceRecord {
            kind: self.kind as u8,
            digest: self.digest,
        }
    }
}

/// Feeds values into a digest in a canonical form: numbers as their little-endian bits,
/// strings with their length in front (so no two sequences of fields share an encoding).
struct Feed(Sha256);

impl Feed {
    fn new(kind: Kind) -> Self {
        let mut h = Sha256::new();
        h.update(b"skyroute provenance 1");
        h.update([kind as u8]);
        Feed(h)
    }
    fn f64(&mut self, x: f64) -> &mut Self {
        self.0.update(x.to_bits().to_le_bytes());
        self
    }
    fn opt(&mut self, x: Option<f64>) -> &mut Self {
        match x {
            Some(_) => self.0.update([1]),
            None => self.0.update([0]),
        }
        self.f64(x.unwrap_or(0.0))
    }
    fn u64(&mut self, x: u64) -> &mut Self {
        self.0.update(x.to_le_bytes());
        self
    }
    fn str(&mut self, s: &str) -> &mut Self {
        self.u64(s.len() as u64);
        self.0.update(s.as_bytes());
        self
    }
    fn bytes(&mut self, b: &[u8]) -> &mut Self {
        self.u64(b.len() as u64);
        self.0.update(b);
        self
    }
    fn finish(self) -> u64 {
        let out = self.0.finalize();
        let mut first = [0u8; 8];
        first.copy_from_slice(&out[..8]);
        u64::from_le_bytes(first)
    }
}

fn item(kind: Kind, label: String, fill: impl FnOnce(&mut Feed)) -> Item {
    let mut feed = Feed::new(kind);
    fill(&mut feed);
    Item {
        kind,
        digest: feed.finish(),
        label,
    }
}

fn endpoint(f: &mut Feed, e: &Option<Endpoint>) {
    match e {
        None => {
            f.u64(0);
        }
        Some(e) => {
            f.u64(1)
                .f64(e.lon)
                .f64(e.lat)
                .opt(e.heading_deg)
                .opt(e.dist_m);
        }
    }
}

/// Why the scenario's digests could not be computed.
#[derive(Debug)]
pub struct DemUnreadable(pub String);

impl fmt::Display for DemUnreadable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for DemUnreadable {}

/// The digests of everything in `s` that decides what a network built from it may fly
/// through (see the module's documentation). Reads the DEM file in terrain mode.
pub fn scenario_items(s: &Scenario) -> Result<Vec<Item>, DemUnreadable> {
    let mut items = vec![item(Kind::Mode, "planner.mode".into(), |f| {
        f.str(s.planner.mode.as_str());
    })];
    let v = &s.vehicle;
    items.push(item(Kind::Vehicle, "vehicle".into(), |f| {
        f.f64(v.v_nominal_mps)
            .f64(v.v_min_mps)
            .f64(v.v_max_mps)
            .f64(v.a_lat_max_mps2)
            .f64(v.a_long_min_mps2)
            .f64(v.a_long_max_mps2)
            .f64(v.wingspan_m);
    }));
    items.push(item(Kind::Clearance, "planner.clearance_m".into(), |f| {
        f.f64(s.planner.clearance_m.unwrap_or(0.0));
    }));
    for z in &s.no_fly {
        items.push(item(
            Kind::NoFly,
            format!("no-fly zone {:?}", z.name),
            |f| {
                f.u64(z.ring.len() as u64);
                for &(lon, lat) in &z.ring {
                    f.f64(lon).f64(lat);
                }
                // Holes follow the ring, each its length then its points; a zone without holes
                // adds nothing.
                for hole in &z.holes {
                    f.u64(hole.len() as u64);
                    for &(lon, lat) in hole {
                        f.f64(lon).f64(lat);
                    }
                }
            },
        ));
    }
    for t in &s.threats {
        items.push(item(Kind::Threat, format!("threat {:?}", t.name), |f| {
            f.f64(t.lon).f64(t.lat).f64(t.radius_m);
        }));
    }
    for (i, l) in s.landmarks.iter().enumerate() {
        items.push(item(
            Kind::Landmark,
            format!("landmark {:?}", l.name),
            |f| {
                f.u64(i as u64)
                    .str(&l.name)
                    .f64(l.lon)
                    .f64(l.lat)
                    .f64(l.d_max_m);
                f.u64(l.quality.len() as u64);
                for (weather, rosette) in &l.quality {
                    f.str(weather);
                    for &q in rosette {
                        f.f64(q);
                    }
                }
            },
        ));
    }
    if s.planner.mode == Mode::Landmark {
        items.push(item(Kind::Weather, "weather list".into(), |f| {
            f.u64(s.weather.len() as u64);
            for w in &s.weather {
                f.str(w);
            }
        }));
        items.push(item(Kind::Endpoints, "start and goal".into(), |f| {
            endpoint(f, &s.start);
            endpoint(f, &s.goal);
        }));
    }
    if let Some(t) = &s.terrain {
        let dem = std::fs::read(&t.dem)
            .map_err(|e| DemUnreadable(format!("{}: terrain.dem: {e}", t.dem.display())))?;
        let name = t
            .dem
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        items.push(item(
            Kind::Terrain,
            format!("terrain (DEM {name:?}, altitude_m, safety_height_m)"),
            |f| {
                f.bytes(&dem).f64(t.altitude_m).f64(t.safety_height_m);
            },
        ));
    }
    Ok(items)
}

/// The provenance records of `items`, for the network writer.
pub fn records(items: &[Item]) -> Vec<ProvenanceRecord> {
    items.iter().map(Item::record).collect()
}

/// How a scenario differs from what its network was built from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Mismatch {
    /// Single items (the vehicle, the clearance, ...) whose value differs from the build's.
    pub changed: Vec<String>,
    /// Items of the scenario the network was not built with (added or changed since).
    pub not_in_network: Vec<String>,
    /// Items the network was built with that the scenario no longer has (removed or
    /// changed), counted per kind.
    pub not_in_scenario: Vec<(Kind, usize)>,
    /// Records of a kind this version of the tool does not know.
    pub unknown_records: usize,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 6;
        let mut parts = Vec::new();
        if !self.changed.is_empty() {
            parts.push(format!(
                "{} differ{} from the build's",
                self.changed.join(", "),
                if self.changed.len() == 1 { "s" } else { "" }
            ));
        }
        if !self.not_in_network.is_empty() {
            let mut names: Vec<&str> = self
                .not_in_network
                .iter()
                .take(SHOWN)
                .map(String::as_str)
                .collect();
            let more = self.not_in_network.len().saturating_sub(SHOWN);
            let more = if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            };
            let list = {
                names.dedup();
                names.join(", ")
            };
            parts.push(format!(
                "the network was not built with {list}{more} (added or changed since the build)"
            ));
        }
        for &(kind, n) in &self.not_in_scenario {
            let (one, many) = kind.nouns();
            let what = if n == 1 {
                format!("1 {one}")
            } else {
                format!("{n} {many}")
            };
            parts.push(format!(
                "{what} of the build {} not in the scenario (removed or changed)",
                if n == 1 { "is" } else { "are" }
            ));
        }
        if self.unknown_records > 0 {
            parts.push(format!(
                "{} provenance records of a kind this skyroute does not know",
                self.unknown_records
            ));
        }
        f.write_str(&parts.join("; "))
    }
}

/// Compares the scenario's items with the network's provenance records, kind by kind, as
/// multisets (a no-fly zone moved within the file still matches; a landmark's index is in its
/// digest, so reordering landmarks does not). `Ok(())` when they are equal.
pub fn compare(items: &[Item], network: &Network) -> Result<(), Mismatch> {
    let mut stored: Vec<(u8, u64)> = (0..network.provenance_count())
        .filter_map(|i| network.provenance(i))
        .map(|r| (r.kind, r.digest))
        .collect();
    let mut unmatched: Vec<&Item> = Vec::new();
    for it in items {
        match stored
            .iter()
            .position(|&(k, d)| k == it.kind as u8 && d == it.digest)
        {
            Some(at) => {
                stored.swap_remove(at);
            }
            None => unmatched.push(it),
        }
    }
    // A single item unmatched on both sides is one that changed.
    let mut changed = Vec::new();
    let mut not_in_network = Vec::new();
    for it in unmatched {
        let other = stored.iter().position(|&(k, _)| k == it.kind as u8);
        match other {
            Some(at) if it.kind.is_single() => {
                stored.swap_remove(at);
                changed.push(it.label.clone());
            }
            _ => not_in_network.push(it.label.clone()),
        }
    }
    let mut not_in_scenario = Vec::new();
    let mut unknown_records = 0;
    for kind in Kind::ALL {
        let n = stored.iter().filter(|&&(k, _)| k == kind as u8).count();
        if n > 0 {
            not_in_scenario.push((kind, n));
        }
    }
    for &(k, _) in &stored {
        if Kind::from_code(k).is_none() {
            unknown_records += 1;
        }
    }
    if changed.is_empty()
        && not_in_network.is_empty()
        && not_in_scenario.is_empty()
        && unknown_records == 0
    {
        return Ok(());
    }
    Err(Mismatch {
        changed,
        not_in_network,
        not_in_scenario,
        unknown_records,
    })
}

/// Why a scenario cannot be planned on a network.
#[derive(Debug)]
pub enum BindingError {
    /// The network's mode is not the scenario's.
    Mode {
        /// The network's mode.
        network: &'static str,
        /// The scenario's `planner.mode`.
        scenario: &'static str,
    },
    /// The network records nothing of its scenario (written by a test or another tool).
    NoProvenance,
    /// The DEM could not be read for its digest.
    Dem(DemUnreadable),
    /// The scenario differs from what the network was built from.
    Differs(Mismatch),
}

impl fmt::Display for BindingError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BindingError::Mode { network, scenario } => write!(
                f,
                "planner.mode: the scenario is a {scenario} scenario, the network a {network} \
                 network"
            ),
            BindingError::NoProvenance => write!(
                f,
                "the network records nothing of the scenario it was built from, so it cannot \
                 be checked against this one; rebuild it with `skyroute build`"
            ),
            BindingError::Dem(e) => write!(f, "{e}"),
            BindingError::Differs(m) => write!(
                f,
                "the scenario does not match the network: {m}. Rebuild the network with \
                 `skyroute build`, or give an obstacle that appeared after the build as a \
                 `popup` feature or --popup"
            ),
        }
    }
}

impl std::error::Error for BindingError {}

/// The name of a network's mode, as `planner.mode` spells it.
pub fn network_mode_name(network: &Network) -> &'static str {
    network.mode().name()
}

/// Checks that `s` is the scenario `network` was built from: the same mode, then every digest
/// (see the module's documentation).
pub fn check_binding(s: &Scenario, network: &Network) -> Result<(), BindingError> {
    let mode = network_mode_name(network);
    if mode != s.planner.mode.as_str() {
        return Err(BindingError::Mode {
            network: mode,
            scenario: s.planner.mode.as_str(),
        });
    }
    if network.provenance_count() == 0 {
        return Err(BindingError::NoProvenance);
    }
    let items = scenario_items(s).map_err(BindingError::Dem)?;
    compare(&items, network).map_err(BindingError::Differs)
}

/// Whether `path` names the file the scenario's DEM is read from (for refusing to overwrite
/// an input).
pub fn dem_path(s: &Scenario) -> Option<&Path> {
    s.terrain.as_ref().map(|t| t.dem.as_path())
}
