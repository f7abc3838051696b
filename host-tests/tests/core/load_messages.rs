//! The loader's error messages: each names every number its error carries, no two read the
//! same, and only an image older than the build is told to rebuild.

use skyroute::network::{LoadError, Parameter, Section};

/// Every [`LoadError`], its numbers all distinct (so that a message naming the wrong field
/// shows), with the words of its message that name them.
fn every_error() -> Vec<(LoadError, Vec<&'static str>)> {
    use LoadError::*;
    let s = Section::ChainElements;
    vec![
        (
            Truncated {
                needed: 101,
                available: 102,
            },
            vec!["101", "102"],
        ),
        (TrailingBytes { extra: 103 }, vec!["103"]),
        (
            BadMagic {
                found: [0xab, 0xcd, 0xef, 0x12],
            },
            vec!["ab", "cd", "ef", "12"],
        ),
        (
            UnsupportedVersion {
                found: 104,
                supported: 105,
            },
            vec!["104", "105"],
        ),
        (UnknownMode { mode: 106 }, vec!["106"]),
        (
            TooManyVertices {
                count: 107,
                capacity: 108,
            },
            vec!["107", "108", "vertices"],
        ),
        (
            TooManyEdges {
                count: 109,
                capacity: 110,
            },
            vec!["109", "110", "edges"],
        ),
        (CountsTooLarge, vec!["counts"]),
        (
            BodyLengthMismatch {
                declared: 111,
                expected: 112,
            },
            vec!["111", "112"],
        ),
        (
            ChecksumMismatch {
                stored: 0x71,
                computed: 0x72,
            },
            vec!["0x00000071", "0x00000072"],
        ),
        (
            InvalidParameter {
                parameter: Parameter::GridCell,
            },
            vec!["GridCell"],
        ),
        (
            Malformed {
                section: s,
                index: 113,
            },
            vec!["ChainElements", "113", "malformed"],
        ),
        (
            NonFinite {
                section: s,
                index: 114,
            },
            vec!["ChainElements", "114", "NaN"],
        ),
        (
            BadPopupAlternatives {
                section: s,
                index: 115,
            },
            vec!["ChainElements", "115", "domain"],
        ),
        (
            BadOffsets {
                section: s,
                index: 116,
            },
            vec!["ChainElements", "116", "offset"],
        ),
        (
            IndexOutOfRange {
                section: s,
                index: 117,
                value: 118,
                limit: 119,
            },
            vec!["ChainElements", "117", "118", "119"],
        ),
        (BadCellList { cell: 120 }, vec!["120"]),
        (
            WordCannotJoin {
                edge: 121,
                word: 122,
            },
            vec!["121", "122"],
        ),
        (NegativeValue { edge: 123 }, vec!["123", "negative"]),
        (
            UnknownGeometry {
                edge: 124,
                code: 125,
            },
            vec!["124", "125"],
        ),
        (
            EdgeMissesTarget {
                edge: 126,
                miss_mm: 127,
            },
            vec!["126", "127 mm"],
        ),
        (CostBelowLength { edge: 128 }, vec!["128", "length"]),
        (
            BadAltitude {
                section: s,
                index: 129,
            },
            vec!["ChainElements", "129", "altitude"],
        ),
        (EdgeTooSteep { edge: 130 }, vec!["130", "climbs"]),
        (BadObstacle { obstacle: 131 }, vec!["obstacle 131"]),
        (GridTooSmall { vertex: 132 }, vec!["vertex 132"]),
        (
            TooManySearchStates {
                needed: 133,
                capacity: 134,
            },
            vec!["133", "134"],
        ),
        (
            EdgeOutsideTerrain { edge: 135 },
            vec!["edge 135", "elevation"],
        ),
        (
            EdgeElevationUnderstated {
                edge: 136,
                stored: 137,
                computed: 138,
            },
            vec!["136", "137", "138"],
        ),
        (
            LandmarkVertexCount {
                vertices: 139,
                expected: 140,
            },
            vec!["139", "140"],
        ),
        (
            EndpointVertexMismatch {
                stored: 141,
                expected: 142,
            },
            vec!["141", "142"],
        ),
        (VertexOffLandmark { vertex: 143 }, vec!["143", "landmark"]),
        (QualityOutOfRange { index: 144 }, vec!["144", "quality"]),
        (
            ElementSpeed {
                element: 145,
                speed_mm_s: 146,
            },
            vec!["145", "146 mm/s"],
        ),
        (
            ChainTooShort {
                edge: 147,
                elements: 148,
            },
            vec!["147", "148"],
        ),
        (
            CoincidentElements {
                edge: 149,
                element: 150,
            },
            vec!["149", "150"],
        ),
        (
            ChainMissesVertex {
                edge: 151,
                vertex: 152,
                miss_mm: 153,
            },
            vec!["151", "152", "153 mm"],
        ),
        (
            ChainShorterThanChords { edge: 154 },
            vec!["154", "polyline"],
        ),
        (EdgeOutsideGrid { edge: 155 }, vec!["edge 155", "grid"]),
        (BadThreat { threat: 156 }, vec!["threat 156"]),
        (
            ThreatSitesRefused {
                threats: 157,
                refused: 158,
            },
            vec!["157", "158"],
        ),
        (NeedsVoronoiStorage, vec!["load_voronoi"]),
        (NotVoronoi { mode: 159 }, vec!["159", "Planner::load"]),
        (
            VoronoiMismatch {
                stored: (160, 161),
                built: (162, 163),
            },
            vec!["160", "161", "162", "163"],
        ),
    ]
}

/// Checks that each error's message holds its words and reads unlike every message in `seen`
/// (to which it is added).
pub(crate) fn assert_messages_name_and_differ<E: core::fmt::Debug + core::fmt::Display>(
    errors: &[(E, Vec<&'static str>)],
    seen: &mut std::collections::HashSet<String>,
) {
    for (e, words) in errors {
        let message = e.to_string();
        for w in words {
            assert!(message.contains(w), "{e:?}: {message:?} lacks {w:?}");
        }
        assert!(seen.insert(message.clone()), "{e:?}: {message:?} twice");
    }
}

#[test]
fn every_load_error_names_its_numbers_and_reads_unlike_the_others() {
    assert_messages_name_and_differ(&every_error(), &mut std::collections::HashSet::new());
}

#[test]
fn only_an_older_image_is_told_to_rebuild() {
    let version = |found| {
        LoadError::UnsupportedVersion {
            found,
            supported: 5,
        }
        .to_string()
    };
    assert!(version(4).contains("rebuild"), "{}", version(4));
    assert!(!version(5).contains("rebuild"), "{}", version(5));
    assert!(!version(6).contains("rebuild"), "{}", version(6));
}
