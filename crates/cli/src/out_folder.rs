//! Where a command's results go, settled before any work starts.
//!
//! A plan run can take minutes; finding out afterwards that `--out` names a file, or
//! silently replacing the plan a previous run left there, loses work. So `plan` checks its
//! folder first: a file or an unwritable place is an error (exit 2) before planning; a
//! folder that already holds a plan is kept, and the new plan goes to the first free
//! numbered sibling (`out-2`, `out-3`, ...), said on stderr, unless `--force` asks to
//! replace it; then every file the old plan's run wrote (records, figures, exports, the
//! report) is removed first, so that no old figure or mission file is taken for the new
//! plan's, and nothing else in the folder is touched. Plan and bench folders are never
//! mixed: `plan` refuses a folder with `runs.jsonl`, `bench` one with `plan.json`.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};

/// What a folder already holds.
fn holds(dir: &Path, file: &str) -> bool {
    dir.join(file).exists()
}

/// Fails unless `dir` can be created and written (checked by creating and removing a file).
pub fn ensure_writable(dir: &Path, flag: &str) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!("{flag} {}: is a file, expected a folder", dir.display());
    }
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{flag} {}: cannot create the folder", dir.display()))?;
    tempfile::tempfile_in(dir)
        .with_context(|| format!("{flag} {}: cannot write in the folder", dir.display()))?;
    Ok(())
}

/// The folder `plan` writes to: `out` itself, or its first free numbered sibling when `out`
/// holds a plan and `force` is off.
pub fn plan_folder(out: &Path, force: bool) -> Result<PathBuf> {
    if out.is_dir() && holds(out, "runs.jsonl") {
        bail!(
            "--out {}: holds a bench (runs.jsonl); plan into another folder",
            out.display()
        );
    }
    let chosen = if out.is_dir() && holds(out, "plan.json") && !force {
        let next = (2..)
            .map(|k| numbered(out, k))
            .find(|p| !p.exists())
            .expect("some numbered folder is free");
        eprintln!(
            "{} holds a plan already; writing this one to {} (--force replaces it)",
            out.display(),
            next.display()
        );
        next
    } else {
        if force && out.is_dir() && holds(out, "plan.json") {
            clear_previous_plan(out)?;
        }
        out.to_path_buf()
    };
    ensure_writable(&chosen, "--out")?;
    Ok(chosen)
}

/// Whether `name` is a file that `plan` (or `report` on its folder) writes.
fn written_by_a_plan(name: &str) -> bool {
    let figure = name
        .strip_suffix(".png")
        .or_else(|| name.strip_suffix(".svg"))
        .is_some_and(|stem| crate::figures::PLAN_FIGURES.contains(&stem));
    figure
        || matches!(
            name,
            "plan.json" | "convergence.csv" | "run.json" | "scenario.toml" | "report.html"
        )
        || swarmplan_io::export::is_mission_file(name)
}

/// Removes the files of the plan `dir` holds (`--force`), saying how many.
fn clear_previous_plan(dir: &Path) -> Result<()> {
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("--out {}: cannot list", dir.display()))?;
    let mut removed = 0;
    for entry in entries {
        let entry = entry.with_context(|| format!("--out {}: cannot list", dir.display()))?;
        let name = entry.file_name();
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && name.to_str().is_some_and(written_by_a_plan) {
            let path = entry.path();
            std::fs::remove_file(&path)
                .with_context(|| format!("--force: cannot remove {}", path.display()))?;
            removed += 1;
        }
    }
    eprintln!(
        "--force: removed the {removed} files of the plan {} held",
        dir.display()
    );
    Ok(())
}

/// Refuses a bench into a plan folder.
pub fn bench_folder(out: &Path) -> Result<()> {
    swarmplan_experiment::store::check_not_a_plan_folder(out).context("--out")?;
    ensure_writable(out, "--out")
}

/// The folder `aggregate` writes its summary to: not a plan folder, not one of the shards
/// it reads (their summaries would be replaced), and not a folder with run records of its
/// own (its experiment.json would no longer describe them).
pub fn aggregate_folder(out: &Path, shards: &[PathBuf]) -> Result<()> {
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if let Some(shard) = shards.iter().find(|d| same(out, d)) {
        bail!(
            "--out {}: is one of the folders aggregated ({}); write the summary to a new folder",
            out.display(),
            shard.display()
        );
    }
    if out.is_dir() && holds(out, "runs.jsonl") {
        bail!(
            "--out {}: holds run records (runs.jsonl) of its own; write the summary to a new folder",
            out.display()
        );
    }
    bench_folder(out)
}

fn numbered(out: &Path, k: usize) -> PathBuf {
    let name = out
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    out.with_file_name(format!("{name}-{k}"))
}
