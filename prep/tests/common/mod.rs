//! Helpers shared by the CLI tests: running the binary, reading its output, temporary folders
//! and the repository's scenarios.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn skyroute(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skyroute"))
        .args(args)
        .output()
        .expect("run skyroute")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn ok(o: Output, what: &str) -> Output {
    assert!(
        o.status.success(),
        "{what} failed: {}\n{}",
        stdout(&o),
        stderr(&o)
    );
    o
}

/// A fresh directory under the system's temporary directory, removed when dropped.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(name: &str) -> Self {
        let p = std::env::temp_dir().join(format!("skyroute-cli-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        TempDir(p)
    }
    pub fn file(&self, name: &str) -> String {
        self.0.join(name).display().to_string()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A scenario of the repository's `scenarios/` folder, by file name.
pub fn scenario(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenarios")
        .join(name)
        .display()
        .to_string()
}

pub fn niendorf() -> String {
    scenario("niendorf-urban.geojson")
}

/// The process's exit code (-1 when a signal ended it).
pub fn code(o: &Output) -> i32 {
    o.status.code().unwrap_or(-1)
}

/// The single line of a failure's stderr.
pub fn one_line_error(o: &Output) -> String {
    assert!(
        !o.status.success(),
        "expected a failure, got success: {}",
        stdout(o)
    );
    let e = stderr(o);
    let lines: Vec<&str> = e.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "expected one line of error, got {e:?}");
    assert!(lines[0].starts_with("skyroute: "), "{e:?}");
    lines[0].to_string()
}
