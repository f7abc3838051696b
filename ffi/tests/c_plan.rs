//! The C program `tests/c/plan.c`, linked against this crate's static library, against the
//! same calls through the Rust API (`skyroute::Planner` with this library's capacities): the
//! two must print the same text, floats bit for bit (C's `%a` hex floats, which
//! [`hex_float`] writes as glibc does).
//!
//! Needs the compiled C program and a network image, so it is ignored by default;
//! `scripts/ffi-check.sh` builds both and runs it:
//!
//! ```text
//! SKYROUTE_FFI_PLAN=target/ffi/plan SKYROUTE_FFI_NETWORK=target/ffi/niendorf-urban.bin \
//!     cargo test --release -p skyroute-ffi --test c_plan -- --ignored
//! ```
//!
//! The query: from the pose of a vertex (the first of 0, 1, 2, … that gives a route) to the
//! position of the vertex farthest from it (free arrival heading), with a circular pop-up of
//! 100 m on the middle of the longest line of the route planned without it, so that it
//! changes the route.

use skyroute::planner::{Exit, PlanError, Violation};
use skyroute::{GeoError, Goal, Planner, Popup, Primitive, Query, RouteSummary, Search, Vec2};
use skyroute_ffi::{
    geo_status, load_status, plan_status, popup_status, CorePlanner, SrPlanner, SrStatus,
    SR_EXIT_NONE, SR_EXIT_OBSTACLE, SR_EXIT_POPUP,
};
use std::fmt::Write as _;
use std::mem::{align_of, size_of};
use std::process::Command;

/// Radius of the pop-up, metres.
const POPUP_RADIUS: f32 = 100.0;

/// `v` as C's `printf("%a", (double)v)` writes it with glibc: `0x1.8p+1`, `-0x1p-3`,
/// `0x0p+0` (an `f32` is a normal `f64`, so the leading digit is 1 unless `v` is zero).
fn hex_float(v: f32) -> String {
    hex_f64(v as f64)
}

fn status_line(out: &mut String, label: &str, status: SrStatus) {
    let name = status.name().to_str().expect("status names are ASCII");
    writeln!(out, "{label} status {name}").unwrap();
}

fn summary_lines(out: &mut String, s: &RouteSummary) {
    let h = hex_float;
    writeln!(
        out,
        "summary length {} arrival_heading {} primitives {} network_edges {}",
        h(s.length),
        h(s.arrival_heading),
        s.primitives,
        s.network_edges
    )
    .unwrap();
    let (kind, index, regions, length) = match s.exit {
        None => (SR_EXIT_NONE, 0, 0, 0.0),
        Some(Exit {
            violated,
            regions,
            length,
        }) => match violated {
            Violation::Obstacle(i) => (SR_EXIT_OBSTACLE, i, regions, length),
            Violation::Popup(id) => (SR_EXIT_POPUP, id as u32, regions, length),
        },
    };
    writeln!(
        out,
        "exit kind {kind} index {index} regions {regions} length {}",
        h(length)
    )
    .unwrap();
    let w = &s.work;
    writeln!(
        out,
        "work total {} vertex_scans {} dubins_solves {} collision_tests {} heap_steps {} \
         relaxations {} cells_visited {} threat_steps {}",
        w.total(),
        w.vertex_scans,
        w.dubins_solves,
        w.collision_tests,
        w.heap_steps,
        w.relaxations,
        w.cells_visited,
        w.threat_steps
    )
    .unwrap();
}

fn route_lines(out: &mut String, route: &[Primitive]) {
    let h = hex_float;
    status_line(out, "route", SrStatus::Ok);
    for (i, p) in route.iter().enumerate() {
        match p {
            Primitive::Line(s) => writeln!(
                out,
                "line {i} {} {} {} {}",
                h(s.start.x),
                h(s.start.y),
                h(s.end.x),
                h(s.end.y)
            ),
            Primitive::Arc(a) => writeln!(
                out,
                "arc {i} {} {} {} {} {}",
                h(a.centre.x),
                h(a.centre.y),
                h(a.radius),
                h(a.start_angle),
                h(a.sweep)
            ),
        }
        .unwrap();
    }
}

/// What `plan.c`'s `plan` prints for `result`.
fn plan_lines(
    out: &mut String,
    planner: &CorePlanner,
    label: &str,
    result: Result<RouteSummary, PlanError>,
) {
    match result {
        Ok(s) => {
            status_line(out, label, SrStatus::Ok);
            summary_lines(out, &s);
            route_lines(out, planner.route());
        }
        Err(e) => status_line(out, label, plan_status(&e)),
    }
}

/// The query and pop-up centre described in the module doc, from the first of vertices 0, 1,
/// 2, … whose query has a route, also with the pop-up.
fn choose_query(planner: &mut CorePlanner) -> (Query, Vec2) {
    let budget = planner.worst_case_work();
    for s in 0..planner.network().vertex_count().min(64) {
        let Some((query, popup)) = query_from(planner, s, budget) else {
            continue;
        };
        let blocks = planner.add_popup(Popup::Circle {
            centre: popup,
            radius: POPUP_RADIUS,
        });
        let with_popup = blocks.is_ok() && planner.plan(&query, budget).is_ok();
        if let Ok(added) = blocks {
            planner
                .remove_popup(added.id)
                .expect("the pop-up is removed");
        }
        if with_popup {
            return (query, popup);
        }
    }
    panic!("no query from the first 64 vertices has a route with and without the pop-up");
}

/// From vertex `s`'s pose to the vertex farthest from it, and the middle of the longest line
/// of its route, if it has one.
fn query_from(planner: &mut CorePlanner, s: u32, budget: u64) -> Option<(Query, Vec2)> {
    let network = planner.network();
    let start = network.vertex(s)?;
    let goal = (0..network.vertex_count())
        .filter_map(|v| network.vertex(v))
        .max_by(|a, b| {
            let da = a.position.distance(start.position);
            let db = b.position.distance(start.position);
            da.total_cmp(&db)
        })?;
    let query = Query {
        start,
        goal: Goal {
            position: goal.position,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    planner.plan(&query, budget).ok()?;
    let longest = planner
        .route()
        .iter()
        .filter_map(|p| match p {
            Primitive::Line(s) => Some(*s),
            Primitive::Arc(_) => None,
        })
        .max_by(|a, b| a.length().total_cmp(&b.length()))?;
    Some((query, (longest.start + longest.end) * 0.5))
}

/// The text `plan.c` prints, computed through the Rust API.
fn expected(image: &'static [u8], query: &Query, popup: Vec2) -> String {
    let mut out = String::new();
    let mut planner: Box<CorePlanner> = Box::new(Planner::new());
    let p = &mut *planner;
    writeln!(
        out,
        "planner size {} align {}",
        size_of::<SrPlanner>(),
        align_of::<SrPlanner>()
    )
    .unwrap();
    status_line(&mut out, "init misaligned", SrStatus::MemoryMisaligned);
    status_line(&mut out, "init too small", SrStatus::MemoryTooSmall);
    status_line(&mut out, "init", SrStatus::Ok);
    status_line(&mut out, "load null", SrStatus::NullPointer);
    let truncated = p.load(&image[..10]).expect_err("10 bytes are no network");
    status_line(&mut out, "load truncated", load_status(&truncated));
    p.load(image).expect("the network loads");
    status_line(&mut out, "load", SrStatus::Ok);
    status_line(&mut out, "counts", SrStatus::Ok);
    let n = p.network();
    writeln!(
        out,
        "network vertices {} edges {}",
        n.vertex_count(),
        n.edge_count()
    )
    .unwrap();
    let budget = p.worst_case_work();
    status_line(&mut out, "worst case work", SrStatus::Ok);
    status_line(&mut out, "worst case popup work", SrStatus::Ok);
    let popup_work = p.worst_case_popup_work();
    writeln!(out, "worst_case_work {budget} popup {popup_work}").unwrap();

    let r = p.plan(query, budget);
    plan_lines(&mut out, p, "plan clear", r);
    let zero = p.add_popup(Popup::Circle {
        centre: popup,
        radius: 0.0,
    });
    status_line(
        &mut out,
        "popup zero radius",
        popup_status(&zero.expect_err("a zero radius is refused")),
    );
    let added = p.add_popup(Popup::Circle {
        centre: popup,
        radius: POPUP_RADIUS,
    });
    let id = added.expect("the pop-up is added").id;
    status_line(&mut out, "popup", SrStatus::Ok);
    writeln!(out, "popup id {id}").unwrap();
    let r = p.plan(query, budget);
    plan_lines(&mut out, p, "plan popup", r);
    let a_star = Query {
        search: Search::AStar,
        ..*query
    };
    let r = p.plan(&a_star, budget);
    plan_lines(&mut out, p, "plan popup a-star", r);
    let r = p.plan(query, 1000);
    plan_lines(&mut out, p, "plan small budget", r);
    let inside = Query {
        goal: Goal {
            position: popup,
            heading: None,
        },
        ..*query
    };
    let r = p.plan(&inside, budget);
    plan_lines(&mut out, p, "plan goal in popup", r);
    status_line(&mut out, "plan bad search", SrStatus::InvalidArgument);
    status_line(&mut out, "plan null query", SrStatus::NullPointer);
    status_line(&mut out, "plan null planner", SrStatus::NullPointer);
    let unknown = p.remove_popup(9).expect_err("no pop-up has id 9");
    status_line(&mut out, "remove unknown", popup_status(&unknown));
    p.remove_popup(id).expect("the pop-up is removed");
    status_line(&mut out, "remove popups", SrStatus::Ok);
    let r = p.plan(query, budget);
    plan_lines(&mut out, p, "plan cleared", r);
    geo_lines(&mut out, p, query, budget);
    writeln!(out, "failures 0").unwrap();
    out
}

/// The start through latitude and longitude and back, the plan from the converted pose, and the
/// conversions refused. The Rust side calls the core's `LocalFrame` that `sr_local_to_geo` and
/// `sr_geo_to_local` wrap, so this checks the wrappers (argument order, struct layout, status
/// mapping); the projection itself is checked against PROJ in `host-tests/tests/core/geo.rs`.
fn geo_lines(out: &mut String, p: &mut CorePlanner, query: &Query, budget: u64) {
    status_line(out, "geo null planner", SrStatus::NullPointer);
    let frame = p.network().local_frame();
    let (lon, lat) = frame
        .lon_lat(query.start.position)
        .expect("the start is in the frame");
    let compass = frame.compass_deg(&query.start).expect("a finite heading");
    status_line(out, "local to geo", SrStatus::Ok);
    let h = hex_f64;
    writeln!(
        out,
        "geo lon {} lat {} compass {}",
        h(lon),
        h(lat),
        h(compass)
    )
    .unwrap();
    let back = frame.pose(lon, lat, compass).expect("back to the frame");
    status_line(out, "geo to local", SrStatus::Ok);
    let f = hex_float;
    writeln!(
        out,
        "local x {} y {} heading {}",
        f(back.position.x),
        f(back.position.y),
        f(back.heading)
    )
    .unwrap();
    let from_geo = Query {
        start: back,
        ..*query
    };
    let r = p.plan(&from_geo, budget);
    plan_lines(out, p, "plan from geo", r);
    let refused = |r: Result<skyroute::Pose, GeoError>| geo_status(&r.expect_err("refused"));
    status_line(out, "geo latitude 91", refused(frame.pose(lon, 91.0, 0.0)));
    status_line(
        out,
        "geo heading nan",
        refused(frame.pose(lon, lat, f64::NAN)),
    );
    status_line(
        out,
        "geo far east",
        refused(frame.pose(lon + 90.0, lat, 0.0)),
    );
    status_line(out, "geo null out", SrStatus::NullPointer);
}

/// `d` as C's `printf("%a", d)` writes it with glibc: `0x1.8p+1`, `-0x1p-3`, `0x0p+0`, `nan`,
/// `inf` (normal values; every `f32` is a normal `f64`).
fn hex_f64(d: f64) -> String {
    let sign = if d.is_sign_negative() { "-" } else { "" };
    if d.is_nan() {
        return format!("{sign}nan");
    }
    if d.is_infinite() {
        return format!("{sign}inf");
    }
    if d == 0.0 {
        return format!("{sign}0x0p+0");
    }
    let bits = d.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let mut digits = format!("{:013x}", bits & ((1u64 << 52) - 1));
    while digits.ends_with('0') {
        digits.pop();
    }
    let fraction = if digits.is_empty() {
        String::new()
    } else {
        format!(".{digits}")
    };
    format!("{sign}0x1{fraction}p{exponent:+}")
}

fn env_path(name: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| {
        panic!("{name} is not set: run scripts/ffi-check.sh, which builds and sets it")
    })
}

#[test]
#[ignore = "needs the compiled C program and a network: scripts/ffi-check.sh"]
fn c_program_prints_what_the_rust_api_computes() {
    let program = env_path("SKYROUTE_FFI_PLAN");
    let network = env_path("SKYROUTE_FFI_NETWORK");
    let image: &'static [u8] = std::fs::read(&network).expect("network").leak();

    let mut chooser: Box<CorePlanner> = Box::new(Planner::new());
    chooser.load(image).expect("the network loads");
    let (query, popup) = choose_query(&mut chooser);
    let args = [
        query.start.position.x,
        query.start.position.y,
        query.start.heading,
        query.goal.position.x,
        query.goal.position.y,
        popup.x,
        popup.y,
        POPUP_RADIUS,
    ];
    let output = Command::new(&program)
        .arg(&network)
        .args(args.iter().map(|v| hex_float(*v)))
        .output()
        .expect("the C program runs");
    let c_text = String::from_utf8(output.stdout).expect("the C program prints text");
    println!("{c_text}");
    assert!(
        output.status.success(),
        "the C program failed ({}): {}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );

    let rust_text = expected(image, &query, popup);
    for (i, (c, r)) in c_text.lines().zip(rust_text.lines()).enumerate() {
        assert_eq!(c, r, "line {} differs: C first, Rust second", i + 1);
    }
    assert_eq!(
        c_text.lines().count(),
        rust_text.lines().count(),
        "the C program and the Rust API print different numbers of lines"
    );
    assert!(
        c_text.contains("plan popup status SR_STATUS_OK"),
        "the query with the pop-up has no route"
    );
}

#[test]
fn hex_floats_are_written_as_glibc_writes_them() {
    assert_eq!(hex_float(1.0), "0x1p+0");
    assert_eq!(hex_float(3.0), "0x1.8p+1");
    assert_eq!(hex_float(-0.125), "-0x1p-3");
    assert_eq!(hex_float(0.1), "0x1.99999ap-4");
    assert_eq!(hex_float(0.0), "0x0p+0");
    assert_eq!(hex_float(-0.0), "-0x0p+0");
    assert_eq!(hex_float(f32::MIN_POSITIVE / 2.0), "0x1p-127");
    assert_eq!(hex_f64(1.0), "0x1p+0");
    assert_eq!(hex_f64(0.1), "0x1.999999999999ap-4");
    assert_eq!(hex_f64(-11.5), "-0x1.7p+3");
}
