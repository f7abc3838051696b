//! `skyroute plan` with a pop-up over the start: the first leg begins with the exit, says so
//! on the command line, and records it in the route file; the other legs have none.

mod common;

use common::{niendorf, ok, skyroute, stdout, TempDir};
use serde_json::Value;

#[test]
fn a_popup_over_the_start_is_left_first_and_reported() {
    let dir = TempDir::new("drift-exit");
    let net = dir.file("niendorf.bin");
    ok(skyroute(&["build", &niendorf(), "-o", &net]), "build");
    let route = dir.file("route.json");
    // A 60 m disc centred on the urban scenario's start P.
    let o = ok(
        skyroute(&[
            "plan",
            &net,
            "--scenario",
            &niendorf(),
            "--popup",
            "11.64794475,48.0918477,60",
            "-o",
            &route,
        ]),
        "plan",
    );
    let out = stdout(&o);
    assert!(
        out.contains(
            "P lies inside or within the clearance of --popup #1: the leg first leaves by a"
        ),
        "{out}"
    );
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&route).unwrap()).unwrap();
    let legs = v["legs"].as_array().unwrap();
    let exit = &legs[0]["exit"];
    assert_eq!(exit["region"]["popup"], 0);
    assert_eq!(exit["regions"], 1);
    // From the disc's centre every direction leaves it after its radius plus the scenario's
    // clearance (7 m), so the shortest exit is straight ahead: 60 + 7 + the 1 m margin.
    let length = exit["length_m"].as_f64().unwrap();
    assert!((length - 68.0).abs() < 0.01, "{length}");
    assert!(legs[1..].iter().all(|l| l["exit"].is_null()));
}
