//! `swarmplan report`: the HTML of a plan folder opens in headless Chromium from a local
//! file with the network off, draws its 3-D view (a canvas of non-zero size on which the
//! viewer drew its primitives) and logs no script error. Skipped, saying so, without
//! Chromium (CI installs Debian's `chromium`; set SWARMPLAN_REQUIRE_CHROMIUM=1 to fail
//! instead of skipping).

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{plan_folder, swarmplan};

use std::path::Path;

use predicates::prelude::*;

fn chromium() -> Option<&'static str> {
    [
        "/usr/bin/chromium",
        "/usr/bin/chromium-browser",
        "/usr/bin/google-chrome",
    ]
    .into_iter()
    .find(|p| Path::new(p).exists())
}

#[test]
fn report_is_self_contained_and_names_what_it_shows() {
    let dir = tempfile::tempdir().unwrap();
    plan_folder(dir.path(), &[]);
    swarmplan().arg("report").arg(dir.path()).assert().success();
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    for needle in [
        "<canvas id=\"view3d\"",
        "Cost breakdown",
        "Per UAV",
        "Feasibility",
        "tiny",
        "seed",
    ] {
        assert!(html.contains(needle), "missing {needle}");
    }
    // Nothing is loaded from elsewhere (SVG namespaces are names, not loads).
    assert!(html.contains("<svg"), "the figures are inlined");
    for remote in [
        "src=\"http",
        "href=\"http",
        "url(http",
        "<script src",
        "<link ",
        "@import",
    ] {
        assert!(!html.contains(remote), "the report refers to {remote}");
    }
}

#[test]
fn report_out_never_replaces_a_file_that_is_not_a_report() {
    let dir = tempfile::tempdir().unwrap();
    plan_folder(dir.path(), &[]);
    let plan = std::fs::read(dir.path().join("plan.json")).unwrap();
    swarmplan()
        .arg("report")
        .arg(dir.path())
        .arg("--out")
        .arg(dir.path().join("plan.json"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "plan.json: expected a file ending in .html",
        ));
    assert_eq!(plan, std::fs::read(dir.path().join("plan.json")).unwrap());
    let other = dir.path().join("notes.html");
    std::fs::write(&other, "my notes").unwrap();
    swarmplan()
        .arg("report")
        .arg(dir.path())
        .arg("--out")
        .arg(&other)
        .assert()
        .code(2)
        .stderr(predicate::str::contains(
            "holds something other than an HTML page",
        ));
    assert_eq!(std::fs::read_to_string(&other).unwrap(), "my notes");
    // A report is replaced by the next one.
    for _ in 0..2 {
        swarmplan().arg("report").arg(dir.path()).assert().success();
    }
}

#[test]
fn report_without_inputs_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    swarmplan()
        .arg("report")
        .arg(dir.path())
        .assert()
        .code(2)
        .stderr(predicate::str::contains("neither plan.json nor summary.md"));
}

#[test]
fn headless_chromium_draws_the_3d_view_offline() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("SWARMPLAN_REQUIRE_CHROMIUM").is_none(),
            "Chromium is required but not installed"
        );
        eprintln!("skipped: no Chromium found (apt-get install chromium)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    plan_folder(dir.path(), &[]);
    swarmplan().arg("report").arg(dir.path()).assert().success();
    let profile = dir.path().join("profile");
    let url = format!("file://{}", dir.path().join("report.html").display());
    let out = std::process::Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            // Network off: every request would go to a closed local port.
            "--proxy-server=127.0.0.1:9",
            "--proxy-bypass-list=<-loopback>",
            "--enable-logging=stderr",
            "--v=0",
            "--virtual-time-budget=5000",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(&url)
        .output()
        .unwrap();
    let dom = String::from_utf8_lossy(&out.stdout);
    let log = String::from_utf8_lossy(&out.stderr);
    let canvas = dom
        .split("<canvas")
        .nth(1)
        .and_then(|s| s.split('>').next())
        .unwrap_or_else(|| panic!("no canvas in the rendered page; stderr: {log}"));
    let attr = |name: &str| -> f64 {
        canvas
            .split(&format!("{name}=\""))
            .nth(1)
            .and_then(|s| s.split('"').next())
            .and_then(|v| v.parse().ok())
            .unwrap_or(0.0)
    };
    assert!(attr("width") > 0.0 && attr("height") > 0.0, "{canvas}");
    assert!(
        attr("data-drawn") > 100.0,
        "the viewer drew nothing: {canvas}; stderr: {log}"
    );
    let body = dom
        .split("<body")
        .nth(1)
        .and_then(|s| s.split('>').next())
        .unwrap_or_default();
    assert!(!body.contains("data-errors"), "script errors: {body}");
    let console_errors: Vec<&str> = log
        .lines()
        .filter(|l| {
            l.contains("CONSOLE")
                && (l.contains("Uncaught") || l.contains("ERROR") || l.contains("error"))
        })
        .collect();
    assert!(console_errors.is_empty(), "{console_errors:?}");
}
