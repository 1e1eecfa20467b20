//! Helpers shared by the CLI integration tests.

#![allow(dead_code, clippy::unwrap_used)] // each test binary uses a subset

use std::path::Path;

use assert_cmd::Command;

/// The `swarmplan` binary under test.
pub fn swarmplan() -> Command {
    Command::cargo_bin("swarmplan").unwrap()
}

/// A quick `plan` of the `tiny` scenario into `dir`, with `extra` flags.
pub fn plan_folder(dir: &Path, extra: &[&str]) {
    swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--iterations",
            "10",
            "--population",
            "10",
            "--out",
        ])
        .arg(dir)
        .args(extra)
        .assert()
        .success();
}
