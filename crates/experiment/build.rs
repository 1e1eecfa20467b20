//! Names the build in `SWARMPLAN_BUILD` (the git commit, or the crate version outside a git
//! checkout), so that a bench folder can record which builds wrote its runs.

use std::process::Command;

fn git(args: &[&str]) -> Option<String> {
    let out = Command::new("git").args(args).output().ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    let text = text.trim();
    (out.status.success() && !text.is_empty()).then(|| text.to_owned())
}

fn main() {
    let id = git(&["rev-parse", "--short=12", "HEAD"])
        .unwrap_or_else(|| format!("v{}", env!("CARGO_PKG_VERSION")));
    println!("cargo:rustc-env=SWARMPLAN_BUILD={id}");
    // A commit or a checkout moves HEAD's log; rebuild then so the id follows.
    if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        println!("cargo:rerun-if-changed={dir}/logs/HEAD");
        println!("cargo:rerun-if-changed={dir}/HEAD");
    }
    println!("cargo:rerun-if-changed=build.rs");
}
