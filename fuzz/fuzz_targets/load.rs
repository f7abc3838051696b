//! `Network::from_bytes` on arbitrary bytes (seeded with real images of every mode, see
//! `scripts/fuzz-smoke.sh`), as given and with the checksum re-fixed (so that mutations reach
//! the field checks instead of stopping at the CRC): it returns an error or a network whose
//! every accessor answers without panicking, which then loads into a planner of its mode and
//! plans one query within its budget.
#![no_main]

use libfuzzer_sys::fuzz_target;
use skyroute::network::format::Header;
use skyroute::network::{image_checksum, Mode};
use skyroute::planner::VoronoiStorage;
use skyroute::{Goal, Network, Planner, Pose, Query, Search};

type FuzzPlanner<'n> = Planner<'n, 8192, 16384, 4, 256>;

fuzz_target!(|data: &[u8]| {
    check(data);
    if data.len() >= Header::SIZE {
        let mut fixed = data.to_vec();
        let crc = image_checksum(&fixed);
        fixed[Header::CHECKED_SIZE..Header::SIZE].copy_from_slice(&crc.to_le_bytes());
        check(&fixed);
    }
});

fn check(data: &[u8]) {
    let Ok(net) = Network::from_bytes(data) else {
        return;
    };
    // Every accessor, over every index (and one past the end).
    for v in 0..=net.vertex_count() {
        let _ = net.vertex(v);
        let _ = net.out_edges(v);
    }
    for e in 0..=net.edge_count() {
        let _ = (
            net.edge(e),
            net.edge_path(e),
            net.edge_length(e),
            net.edge_cost_target(e),
        );
    }
    for o in 0..=net.obstacle_count() {
        let _ = net.obstacle(o);
    }
    for p in 0..=net.provenance_count() {
        let _ = net.provenance(p);
    }
    for t in 0..=net.threat_count() {
        let _ = net.threat(t);
    }
    let (lo, hi) = net.extent();
    let mut storage = Box::new(VoronoiStorage::new());
    let mut planner: Box<FuzzPlanner> = Box::new(Planner::new());
    let loaded = match net.mode() {
        Mode::Voronoi => planner.load_voronoi(data, &mut storage),
        Mode::Roadmap | Mode::Terrain | Mode::Landmark | Mode::Unknown(_) => planner.load(data),
    };
    if loaded.is_err() {
        return;
    }
    let query = Query {
        start: Pose::new(lo.x, lo.y, 0.3),
        goal: Goal {
            position: hi,
            heading: None,
        },
        search: Search::Dijkstra,
    };
    let budget = planner.worst_case_work();
    if let Ok(summary) = planner.plan(&query, budget) {
        assert!(summary.work.total() <= budget, "work over the budget");
    }
}
