//! `skyroute render`'s landmarks, graticule, label placement and terrain profile, end to end on
//! the repository's scenarios: the SVG is parsed and checked against the scenario and the
//! network it was drawn from.

mod common;

use common::{niendorf, ok, scenario, skyroute, TempDir};
use serde_json::Value;
use skyroute::network::elevation::ELEVATION_BLOCKED;
use skyroute::{Network, Vec2};

/// The attribute `name` of `n` as a number.
fn attr(n: &roxmltree::Node, name: &str) -> f64 {
    n.attribute(name)
        .unwrap_or_else(|| panic!("<{}> has no {name}", n.tag_name().name()))
        .parse()
        .unwrap()
}

/// The elements with `class` in the document.
fn with_class<'a>(doc: &'a roxmltree::Document, class: &str) -> Vec<roxmltree::Node<'a, 'a>> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some(class))
        .collect()
}

/// The text of every `<text>` element.
fn texts(doc: &roxmltree::Document) -> Vec<String> {
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").to_string())
        .collect()
}

/// Asserts that every `<text>`'s `x` and `y` lie within the SVG's width and height, and that
/// the map's labels (the bold ones with a white halo) lie wholly inside it, their width taken
/// as 0.55 of the font size per character.
fn assert_texts_inside(svg: &str, what: &str) {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let root = doc.root_element();
    let (w, h) = (attr(&root, "width"), attr(&root, "height"));
    let mut n = 0;
    for t in doc.descendants().filter(|n| n.has_tag_name("text")) {
        let (x, y) = (attr(&t, "x"), attr(&t, "y"));
        let s = t.text().unwrap_or("");
        assert!(
            (0.0..=w).contains(&x) && (0.0..=h).contains(&y),
            "{what}: <text> {s:?} at ({x}, {y}) outside the {w} x {h} canvas",
        );
        if t.attribute("stroke") == Some("#fff") {
            let size = attr(&t, "font-size");
            let width = 0.55 * size * s.chars().count() as f64;
            let left = match t.attribute("text-anchor") {
                Some("end") => x - width,
                Some("middle") => x - width / 2.0,
                _ => x,
            };
            assert!(
                left >= 0.0 && left + width <= w && y - size >= 0.0 && y <= h,
                "{what}: label {s:?} at ({x}, {y}) reaches past the {w} x {h} canvas"
            );
        }
        n += 1;
    }
    assert!(n > 10, "{what}: only {n} texts");
}

/// The landmarks' names in a scenario file, in file order.
fn landmark_names(path: &str) -> Vec<String> {
    let s: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    s["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["properties"]["kind"] == "landmark")
        .map(|f| f["properties"]["name"].as_str().unwrap().to_string())
        .collect()
}

/// Numbers of an SVG path's `d` as `(x, y)` pairs (lines only: `M` and `L`).
fn path_points(d: &str) -> Vec<(f64, f64)> {
    let nums: Vec<f64> = d
        .split(['M', 'L', ' '])
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    nums.chunks(2).map(|c| (c[0], c[1])).collect()
}

/// Builds `sc` into `dir`, plans it and renders the route to SVG; returns the network's and the
/// route file's paths and the SVG's text.
fn build_plan_render(dir: &TempDir, sc: &str, stem: &str) -> (String, String, String) {
    let net = dir.file(&format!("{stem}.bin"));
    let (route, svg) = (dir.file("r.json"), dir.file(&format!("{stem}.svg")));
    ok(skyroute(&["build", sc, "-o", &net]), "build");
    ok(
        skyroute(&["plan", &net, "--scenario", sc, "-o", &route]),
        "plan",
    );
    ok(
        skyroute(&[
            "render",
            &net,
            "--route",
            &route,
            "--scenario",
            sc,
            "-o",
            &svg,
        ]),
        "render",
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    (net, route, text)
}

#[test]
fn a_landmark_network_shows_named_landmarks_its_chains_and_a_graticule() {
    let dir = TempDir::new("render-landmarks");
    let sc = scenario("landmark-figure4.geojson");
    let (net, _, text) = build_plan_render(&dir, &sc, "f4");
    let doc = roxmltree::Document::parse(&text).unwrap();
    let all = texts(&doc);
    let names = landmark_names(&sc);
    assert_eq!(names, ["A", "B", "C", "K"]);
    for name in &names {
        assert!(all.iter().any(|t| t == name), "no label {name:?}: {all:?}");
    }
    // One triangle per landmark on the map, one in the legend.
    let symbols = with_class(&doc, "landmark");
    assert_eq!(symbols.len(), names.len() + 1);
    assert!(all.iter().any(|t| t == "landmark, with its name"));

    // The edges are the Hermite chains: they pass through every landmark's overflights.
    let edges = with_class(&doc, "edges");
    assert_eq!(edges.len(), 1);
    let pts = path_points(edges[0].attribute("d").unwrap());
    let bytes = std::fs::read(&net).unwrap();
    let n = Network::from_bytes(&bytes).unwrap();
    assert!(pts.len() > 10 * n.edge_count() as usize, "{}", pts.len());
    // The landmarks' pixels, from their symbols (the triangle's apex is 8 px above).
    let at: Vec<(f64, f64)> = symbols
        .iter()
        .take(names.len())
        .map(|s| {
            let d = s.attribute("d").unwrap();
            let apex = path_points(&d[..d.find('H').unwrap()])[0];
            (apex.0, apex.1 + 8.0)
        })
        .collect();
    let nearest = |(x, y): (f64, f64)| {
        pts.iter()
            .map(|p| (p.0 - x).hypot(p.1 - y))
            .fold(f64::INFINITY, f64::min)
    };
    for &p in &at {
        assert!(
            nearest(p) < 2.0,
            "no chain within 2 px of the landmark at {p:?}"
        );
    }
    // The view, from landmarks A and C: x_px = a + k x, y_px = b - k y.
    let site = |i: u32| n.landmark_site(i).unwrap().0;
    let (sa, sc) = (site(0), site(2));
    let k = (at[2].0 - at[0].0) / (sc.x - sa.x) as f64;
    let (a, b) = (at[0].0 - k * sa.x as f64, at[0].1 + k * sa.y as f64);
    // The middle of the first piece of every edge's chain lies on the drawn edges (the
    // polyline's points are at most about 50 m, under 3 px, apart).
    for e in 0..n.edge_count() {
        let Some(seg) = n.chain_piece(e, 0) else {
            continue;
        };
        let q = seg.position(0.5 * seg.t_max()).unwrap();
        let p = (a + k * q.x as f64, b - k * q.y as f64);
        assert!(
            nearest(p) < 2.0,
            "edge {e}: its chain's point {q:?} is not drawn"
        );
    }

    // The graticule: meridians and parallels, labelled in degrees and minutes, in the legend.
    let lines = with_class(&doc, "graticule");
    assert!(lines.len() >= 4, "{} graticule lines", lines.len());
    for l in &lines {
        assert!(l.has_tag_name("polyline"));
        assert!(l.attribute("points").unwrap().split(' ').count() > 10);
    }
    let dm = |t: &str, hemi: char| {
        t.ends_with(hemi) && t.contains('°') && t.contains('′') && !t.contains(' ')
    };
    assert!(all.iter().filter(|t| dm(t, 'E')).count() >= 3, "{all:?}");
    assert!(all.iter().any(|t| dm(t, 'N')), "{all:?}");
    assert!(
        all.iter()
            .any(|t| t.starts_with("graticule (lon/lat), every ")),
        "{all:?}"
    );
    assert_texts_inside(&text, "landmark-figure4");
}

#[test]
fn labels_stay_inside_the_canvas_when_the_area_cuts_through_them() {
    let dir = TempDir::new("render-labels");
    let net = dir.file("n.bin");
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    // Windows that leave out the pop-up (centre (-214, 284) m, radius 150 m) just below its
    // label, and that hold the goal Q (1316, -320) m, heading east, just right of the left
    // edge, where its label would reach past the picture's left edge.
    for (k, area) in ["-600,-300,300,200", "1305,-700,1800,150"]
        .into_iter()
        .enumerate()
    {
        let svg = dir.file(&format!("n{k}.svg"));
        ok(
            skyroute(&[
                "render",
                &net,
                "--scenario",
                &niendorf(),
                "--popup",
                "11.6275,48.0960,150",
                &format!("--area={area}"),
                "--width",
                "500",
                "-o",
                &svg,
            ]),
            "render",
        );
        assert_texts_inside(&std::fs::read_to_string(&svg).unwrap(), area);
    }
}

/// Where a route's primitives come nearest `p`, metres.
fn distance_to_route(prims: &[skyroute::Primitive], p: Vec2) -> f32 {
    prims
        .iter()
        .map(|q| skyroute::geometry::predicates::primitive_point_distance(q, p))
        .fold(f32::INFINITY, f32::min)
}

#[test]
fn a_terrain_route_has_a_profile_of_the_network_elevations_under_it() {
    let dir = TempDir::new("render-profile");
    let sc = scenario("medeiros-jacksboro.geojson");
    let (net, route, text) = build_plan_render(&dir, &sc, "jb");
    let doc = roxmltree::Document::parse(&text).unwrap();
    let all = texts(&doc);
    for entry in [
        "profile: terrain under the route",
        "profile: route altitude / less safety height",
    ] {
        assert!(all.iter().any(|t| t == entry), "no legend entry {entry:?}");
    }
    assert!(all.iter().any(|t| t.contains("elevation (m)")));
    assert!(all.iter().any(|t| t.ends_with(" m") && t.starts_with('7')));

    let bytes = std::fs::read(&net).unwrap();
    let n = Network::from_bytes(&bytes).unwrap();
    let t = *n.terrain().unwrap();
    let (grid, coding) = (n.terrain_grid().unwrap(), n.elevation_coding().unwrap());
    let r = skyroute_prep::render::read_route(std::path::Path::new(&route)).unwrap();
    assert_eq!(r.altitude_m, Some(t.altitude_m as f64));
    let prims: Vec<_> = r.legs.iter().flat_map(|l| l.primitives.clone()).collect();
    let alt = with_class(&doc, "profile-altitude");
    assert_eq!(attr(&alt[0], "data-altitude-m"), t.altitude_m as f64);
    let safety = with_class(&doc, "profile-safety");
    assert_eq!(
        attr(&safety[0], "data-altitude-m"),
        (t.altitude_m - t.safety_height_m) as f64
    );

    let terrain = with_class(&doc, "profile-terrain");
    assert_eq!(terrain.len(), 1);
    let samples: Vec<(f64, f32, f32, Option<f32>)> = terrain[0]
        .attribute("data-samples")
        .unwrap()
        .split(' ')
        .map(|s| {
            let f: Vec<&str> = s.split(':').collect();
            (
                f[0].parse().unwrap(),
                f[1].parse().unwrap(),
                f[2].parse().unwrap(),
                f[3].parse().ok(),
            )
        })
        .collect();
    // Every half cell along the whole route.
    let length = r.length_m();
    assert!(samples.len() as f64 >= length / (0.5 * grid.cell as f64));
    assert!((samples.last().unwrap().0 - length).abs() < 1.0);
    let mut checked = 0;
    for &(_, x, y, e) in &samples {
        let p = Vec2::new(x, y);
        assert!(
            distance_to_route(&prims, p) < 0.2,
            "({x}, {y}) off the route"
        );
        // The sample's point is rounded to 0.1 m: skip those that could be in the next cell.
        let u = (x - grid.origin.x) / grid.cell;
        let v = (y - grid.origin.y) / grid.cell;
        let margin = 0.1 / grid.cell;
        if (u - u.round()).abs() < margin || (v - v.round()).abs() < margin {
            continue;
        }
        let (c, row) = grid.cell_of(p).unwrap();
        let code = n.elevation_code(c, row);
        let expected = (code != ELEVATION_BLOCKED).then(|| coding.upper_bound(code));
        match (e, expected) {
            (Some(e), Some(x)) => assert!((e - x).abs() < 0.01, "{e} against {x}"),
            (e, x) => assert_eq!(e, x),
        }
        // The route flies clear of the terrain.
        if let Some(e) = e {
            assert!(e < t.altitude_m - t.safety_height_m);
        }
        checked += 1;
    }
    assert!(
        checked * 10 >= samples.len() * 9,
        "{checked} of {}",
        samples.len()
    );
    assert_texts_inside(&text, "medeiros-jacksboro");
}

#[test]
fn a_network_without_terrain_has_no_profile() {
    let dir = TempDir::new("render-no-profile");
    let sc = scenario("landmark-figure4.geojson");
    let (net, svg) = (dir.file("f4.bin"), dir.file("f4.svg"));
    ok(skyroute(&["build", &sc, "-o", &net]), "build");
    ok(skyroute(&["render", &net, "-o", &svg]), "render");
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    assert!(with_class(&doc, "profile").is_empty());
    // Without the scenario the landmarks are numbered.
    let all = texts(&doc);
    for name in ["L1", "L2", "L3", "L4"] {
        assert!(all.iter().any(|t| t == name), "no label {name:?}");
    }
}
