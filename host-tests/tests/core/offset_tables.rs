//! The loader's offset-table checks (`validate_offsets`): an offset table must start at 0,
//! never decrease and end at its section's total. Each rule is broken on its own in the edge
//! offsets and in the grid's cell offsets of a valid synthetic image (checksum re-fixed), and
//! each is refused as `BadOffsets` at the offending index. (The landmark chain offsets get the
//! same damages in `modes::landmark_load`, which has a landmark image built.)

use host_tests::damage::{check_offset_rules_refused, leb128, OffsetTable};
use host_tests::world::world;
use skyroute::network::format::{
    EdgeRecord, Header, ObstacleRecord, PointRecord, U32Record, VertexRecord,
};
use skyroute::network::Section;
use skyroute::Network;

#[test]
fn edge_offsets_must_start_at_zero_never_decrease_and_end_at_the_edge_count() {
    let w = world(2, 600.0, 60.0, 40.0, 3);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let h = *net.header();
    let table = OffsetTable {
        section: Section::EdgeOffsets,
        at: Header::SIZE + h.vertex_count as usize * VertexRecord::SIZE,
        count: h.vertex_count,
        total: h.edge_count,
    };
    for v in 0..=h.vertex_count {
        let expected = if v < h.vertex_count {
            net.out_edges(v).start
        } else {
            h.edge_count
        };
        assert_eq!(
            table.offset(&w.bytes, v),
            expected,
            "the table is where we think"
        );
    }
    check_offset_rules_refused(&w.bytes, &table);
}

#[test]
fn cell_offsets_must_start_at_zero_never_decrease_and_end_at_the_list_bytes() {
    let w = world(2, 600.0, 60.0, 40.0, 3);
    let net = Network::from_bytes(&w.bytes).unwrap();
    let h = *net.header();
    let (v, e) = (h.vertex_count as usize, h.edge_count as usize);
    let cells = h.grid_nx * h.grid_ny;
    let table = OffsetTable {
        section: Section::CellOffsets,
        at: Header::SIZE
            + v * VertexRecord::SIZE
            + (v + 1) * U32Record::SIZE
            + e * EdgeRecord::SIZE
            + h.obstacle_count as usize * ObstacleRecord::SIZE
            + h.obstacle_point_count as usize * PointRecord::SIZE,
        count: cells,
        total: h.grid_list_bytes,
    };
    // Each cell's list is as long as its offsets say: the edges it decodes to take those bytes.
    let lists = table.at + (cells as usize + 1) * U32Record::SIZE;
    for c in 0..cells {
        let (x, y) = (c % h.grid_nx, c / h.grid_nx);
        let (start, end) = (table.offset(&w.bytes, c), table.offset(&w.bytes, c + 1));
        let mut bytes = Vec::new();
        let mut previous: Option<u32> = None;
        for e in net.cell_edges(x, y) {
            let delta = previous.map_or(e, |p| e - p - 1);
            leb128(delta, &mut bytes);
            previous = Some(e);
        }
        assert_eq!(
            &w.bytes[lists + start as usize..lists + end as usize],
            &bytes[..],
            "the table is where we think"
        );
    }
    check_offset_rules_refused(&w.bytes, &table);
}
