//! Landmark networks (format v4, mode 1) as bad input: each targeted damage of the landmark
//! sections gets its own `LoadError` (with a valid CRC, so the field checks decide); random
//! mutations never panic the loader or a planner using what it accepted; bad onboard calls
//! (unknown weather or landmark, NaN or out-of-range qualities, a full override table) are
//! refused with an error and change nothing.

use host_tests::damage::{check_offset_rules_refused, find_unique, fix_crc, OffsetTable};
use host_tests::{cases, scenarios, Rng};
use skyroute::network::format::{Header, ProvenanceRecord};
use skyroute::network::Section;
use skyroute::planner::{Goal, PlanError, Popup, Query, Search};
use skyroute::{LoadError, Network, Planner, Vec2};

type Lp<'n> = Planner<'n, 256, 4096, 4, 256>;

/// A landmark network: babel-I-bridged as the ground tool builds it (built once per process
/// and shared by the tests here and in `landmark_plan` and `network_images`).
fn network() -> Vec<u8> {
    scenarios::built("babel-I-bridged").bytes.clone()
}

/// Where the landmark record starts: found by its leading counts and nominal speed (10
/// landmarks, 12 directions, 2 weathers, 30 m/s), which the test asserts occur exactly once.
fn landmark_record_at(bytes: &[u8]) -> usize {
    let mut key = Vec::new();
    for x in [10u32, 12, 2] {
        key.extend_from_slice(&x.to_le_bytes());
    }
    key.extend_from_slice(&30.0f32.to_le_bytes());
    find_unique(bytes, &key)
}

fn put_f32(bytes: &mut [u8], at: usize, x: f32) {
    bytes[at..at + 4].copy_from_slice(&x.to_le_bytes());
}

fn get_f32(bytes: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

#[test]
fn each_landmark_damage_has_its_own_error() {
    let good = network();
    let net = Network::from_bytes(&good).expect("the undamaged image loads");
    let l = *net.landmark().unwrap();
    let rec = landmark_record_at(&good);
    let landmarks = rec + 56;
    let rosettes = landmarks + 12 * l.landmark_count as usize;
    // The distinct elements come last but for the provenance records that close every body,
    // in the order the chains first use them: element 0 and 1 start edge 0's chain.
    let provenance = ProvenanceRecord::SIZE * net.provenance_count() as usize;
    let elements = good.len() - provenance - 16 * l.element_count as usize;
    let damaged = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut b = good.clone();
        f(&mut b);
        fix_crc(&mut b);
        Network::from_bytes(&b).map(|_| ()).unwrap_err()
    };

    let e = damaged(&|b| put_f32(b, rosettes + 4 * 5, 1.5));
    assert!(
        matches!(e, LoadError::QualityOutOfRange { index: 5 }),
        "{e:?}"
    );
    let e = damaged(&|b| put_f32(b, rosettes + 4 * 7, f32::NAN));
    assert!(
        matches!(e, LoadError::QualityOutOfRange { index: 7 }),
        "{e:?}"
    );
    let e = damaged(&|b| put_f32(b, landmarks + 8, f32::NAN));
    assert!(matches!(e, LoadError::NonFinite { .. }), "{e:?}");
    // The nominal speed NaN: the landmark record's numbers are refused.
    let e = damaged(&|b| put_f32(b, rec + 12, f32::NAN));
    assert!(matches!(e, LoadError::InvalidParameter { .. }), "{e:?}");
    // One more weather than the tables hold: the section sizes no longer add up.
    let e = damaged(&|b| b[rec + 8..rec + 12].copy_from_slice(&3u32.to_le_bytes()));
    assert!(
        matches!(
            e,
            LoadError::BodyLengthMismatch { .. } | LoadError::Truncated { .. }
        ),
        "{e:?}"
    );
    // Element 1 (inside edge 0's chain) 1 % too fast.
    let e = damaged(&|b| {
        let at = elements + 16 + 8;
        let (vx, vy) = (get_f32(b, at), get_f32(b, at + 4));
        put_f32(b, at, vx * 1.01);
        put_f32(b, at + 4, vy * 1.01);
    });
    assert!(
        matches!(e, LoadError::ElementSpeed { element: 1, .. }),
        "{e:?}"
    );
    // Edge 0's first element moved 5 m: it no longer starts at its source vertex.
    let e = damaged(&|b| {
        let x = get_f32(b, elements);
        put_f32(b, elements, x + 5.0);
    });
    assert!(
        matches!(e, LoadError::ChainMissesVertex { edge: 0, .. }),
        "{e:?}"
    );
    // Element 1 moved onto element 0: no piece joins them.
    let e = damaged(&|b| {
        let (x, y) = (get_f32(b, elements), get_f32(b, elements + 4));
        put_f32(b, elements + 16, x);
        put_f32(b, elements + 20, y);
    });
    assert!(
        matches!(
            e,
            LoadError::CoincidentElements {
                edge: 0,
                element: 1
            } | LoadError::ChainShorterThanChords { .. }
        ),
        "{e:?}"
    );
    // Without a fixed CRC any of these is a checksum error.
    let mut b = good.clone();
    put_f32(&mut b, rosettes, 0.5);
    assert!(matches!(
        Network::from_bytes(&b),
        Err(LoadError::ChecksumMismatch { .. })
    ));
    // Cut anywhere: refused, never a panic.
    for cut in [
        0,
        1,
        Header::SIZE - 1,
        Header::SIZE,
        rec,
        elements,
        good.len() - 1,
    ] {
        assert!(Network::from_bytes(&good[..cut]).is_err(), "cut at {cut}");
    }
}

/// Loads `bytes` and, when accepted, plans in every weather with a pop-up and a lost landmark.
/// The query from the landmark network's stored start to its stored goal (any arrival heading).
fn stored_query(net: &Network) -> Option<Query> {
    let l = net.landmark()?;
    let (start, goal) = (net.vertex(l.start_vertex)?, net.vertex(l.goal_vertex)?);
    Some(Query {
        start,
        goal: Goal {
            position: goal.position,
            heading: None,
        },
        search: Search::Dijkstra,
    })
}

fn load_and_use(bytes: &[u8], rng: &mut Rng) -> Result<(), LoadError> {
    let mut planner: Box<Lp<'_>> = Box::new(Planner::new());
    planner.load(bytes)?;
    let net = *planner.network();
    let Some(l) = net.landmark().copied() else {
        return Ok(());
    };
    let _ = planner.add_popup(Popup::Circle {
        centre: Vec2::new(
            rng.range_f32(-20_000.0, 20_000.0),
            rng.range_f32(-4000.0, 4000.0),
        ),
        radius: 500.0,
    });
    let _ = planner.update_rosette(rng.below(12) as u32, &[0.0; 12]);
    for w in 0..l.weather_count.min(4) {
        let _ = planner.set_weather(w);
        if let Some(q) = stored_query(&net) {
            if planner.plan(&q, planner.worst_case_work()).is_ok() {
                for &e in planner.route_edges() {
                    for k in 0..net.chain_piece_count(e) {
                        let _ = net.chain_piece(e, k);
                    }
                }
            }
        }
    }
    Ok(())
}

/// A landmark's overflight vertices stand on its site within the position tolerance
/// 10⁻⁴·max(|x|, |y|) + 1 cm (rounding, not placement): the site nearest the origin moved east
/// by 99 % of its tolerance still loads, by 101 % is refused, naming its first direction's
/// vertex.
#[test]
fn a_site_within_the_position_tolerance_of_its_vertices_loads_and_one_beyond_is_refused() {
    let good = network();
    let net = Network::from_bytes(&good).unwrap();
    let l = *net.landmark().unwrap();
    let sites = landmark_record_at(&good) + 56;
    let site = |i: u32| {
        let at = sites + 12 * i as usize;
        (at, get_f32(&good, at), get_f32(&good, at + 4))
    };
    let size = |(_, x, y): (usize, f32, f32)| x.abs().max(y.abs());
    let i = (0..l.landmark_count)
        .min_by(|&a, &b| size(site(a)).total_cmp(&size(site(b))))
        .unwrap();
    let (at, x, y) = site(i);
    for k in 0..l.directions {
        let v = i * l.directions + k;
        assert_eq!(
            net.vertex(v).unwrap().position,
            Vec2::new(x, y),
            "vertex {v}"
        );
    }
    let tolerance = 1e-4 * x.abs().max(y.abs()) + 0.01;
    // Between 2 cm and 0.99 m, so that the cases tell the centimetre term, the relative term
    // and a metre apart.
    assert!(
        tolerance > 0.02 && tolerance < 0.99,
        "tolerance {tolerance} m"
    );
    let moved = |fraction: f32| {
        let mut b = good.clone();
        put_f32(&mut b, at, x + fraction * tolerance);
        fix_crc(&mut b);
        Network::from_bytes(&b).map(|_| ())
    };
    assert_eq!(moved(0.99), Ok(()));
    assert_eq!(
        moved(1.01),
        Err(LoadError::VertexOffLandmark {
            vertex: i * l.directions
        })
    );
}

/// The chain offsets (edge `e` owns the chain index list's entries
/// `offsets[e] .. offsets[e + 1]`) must start at 0, never decrease and end at the list's
/// length: each rule broken on its own is refused as `BadOffsets` at the offending index (the
/// same damages as the edge and cell offsets get in `core::offset_tables`).
#[test]
fn chain_offsets_must_start_at_zero_never_decrease_and_end_at_the_index_count() {
    let good = network();
    let net = Network::from_bytes(&good).expect("the undamaged image loads");
    let l = *net.landmark().unwrap();
    let rosettes = landmark_record_at(&good) + 56 + 12 * l.landmark_count as usize;
    let table = OffsetTable {
        section: Section::ChainOffsets,
        at: rosettes + 4 * (l.landmark_count * l.weather_count * l.directions) as usize,
        count: net.edge_count(),
        total: l.chain_index_count,
    };
    for e in 0..net.edge_count() {
        assert_eq!(
            table.offset(&good, e),
            net.chain_elements(e).start,
            "the table is where we think"
        );
    }
    check_offset_rules_refused(&good, &table);
}

#[test]
fn random_landmark_mutations_never_panic() {
    let good = network();
    let rec = landmark_record_at(&good);
    let mut rng = Rng(4);
    let (mut accepted, mut rejected) = (0u32, 0u32);
    let n = cases(200, 2000) as u32;
    for case in 0..n {
        let mut b = good.clone();
        for _ in 0..1 + rng.below(3) {
            // Two thirds of the hits in the landmark sections (record, sites, rosettes, chain
            // offsets, elements), the rest anywhere.
            let at = if rng.below(3) < 2 {
                rec + rng.below((good.len() - rec) as u64) as usize
            } else {
                rng.below(good.len() as u64) as usize
            };
            match rng.below(3) {
                0 => b[at] ^= 1 << rng.below(8),
                1 => b[at] = rng.next_u64() as u8,
                _ => b[at] = 0xFF,
            }
        }
        if case % 2 == 0 {
            fix_crc(&mut b);
        }
        match load_and_use(&b, &mut rng) {
            Ok(()) => accepted += 1,
            Err(_) => rejected += 1,
        }
    }
    println!("landmark mutations: {accepted} accepted, {rejected} rejected, no panic");
    assert!(rejected > n / 4, "damage is noticed");
}

#[test]
fn bad_onboard_calls_are_refused_and_change_nothing() {
    let good = network();
    let mut planner: Box<Lp<'_>> = Box::new(Planner::new());
    planner.load(&good).unwrap();
    let net = *planner.network();
    let l = *net.landmark().unwrap();
    let q = Query {
        start: net.vertex(l.start_vertex).unwrap(),
        goal: Goal {
            position: net.vertex(l.goal_vertex).unwrap().position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let before = planner.plan(&q, planner.worst_case_work()).unwrap().length;
    assert!(matches!(
        planner.set_weather(2),
        Err(PlanError::UnknownWeather {
            weather: 2,
            count: 2
        })
    ));
    assert_eq!(planner.weather(), 0);
    assert!(matches!(
        planner.update_rosette(10, &[0.0; 12]),
        Err(PlanError::UnknownLandmark { .. })
    ));
    for bad in [[f32::NAN; 12], [1.5; 12], [-0.1; 12]] {
        assert!(matches!(
            planner.update_rosette(0, &bad),
            Err(PlanError::InvalidRosette { .. })
        ));
    }
    assert!(matches!(
        planner.update_rosette(0, &[0.5; 11]),
        Err(PlanError::InvalidRosette { .. })
    ));
    assert!(!planner.clear_rosette(0), "nothing was stored");
    assert_eq!(
        planner.plan(&q, planner.worst_case_work()).unwrap().length,
        before
    );
    // The override table holds 8 landmarks; the 9th is refused, the 8 stay.
    for lm in 0..8 {
        planner.update_rosette(lm, &[1.0; 12]).unwrap();
    }
    assert!(matches!(
        planner.update_rosette(8, &[0.0; 12]),
        Err(PlanError::RosetteTableFull { capacity: 8 })
    ));
    assert_eq!(
        planner.plan(&q, planner.worst_case_work()).unwrap().length,
        before,
        "all-1 overrides equal babel-I-bridged's nominal rosettes"
    );
}

#[test]
fn post_processing_refuses_a_landmark_route_and_keeps_it() {
    let bytes = network();
    let mut p: Box<Lp<'_>> = Box::new(Planner::new());
    p.load(&bytes).unwrap();
    let q = stored_query(p.network()).unwrap();
    p.plan(&q, p.worst_case_work()).unwrap();
    let (edges, summary) = (p.route_edges().to_vec(), *p.route_summary().unwrap());
    assert!(summary.length > 0.0);
    assert_eq!(p.shortcut(u64::MAX), Err(PlanError::NotDubinsRoute));
    assert_eq!(p.shortcut_best(u64::MAX), Err(PlanError::NotDubinsRoute));
    assert_eq!(
        p.smooth_headings(9, u64::MAX),
        Err(PlanError::NotDubinsRoute)
    );
    assert_eq!(p.route_edges(), &edges[..]);
    assert_eq!(
        p.route_summary(),
        Some(&summary),
        "the summary keeps its length"
    );
}
