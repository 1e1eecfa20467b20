//! Where the shared reference data is (the SPSO terrain and cost vectors, the outside
//! benchmark instances), for tests, benchmarks and examples.
//!
//! The data lives outside the repository (`shared/data` beside the checkout, or the
//! folder `SWARMPLAN_SHARED` names) and is never committed. It is found when the program
//! runs, never by a path of the machine that built it: an installed binary, a test and a
//! run from any folder of the checkout all look the same way ([`shared_dir`]). A test that needs it skips
//! with a message on a developer's machine without it, but must not pass by skipping where
//! the data is expected: when `CI` or `SWARMPLAN_REQUIRE_SHARED` is set, a missing file is
//! an error.

use std::path::{Path, PathBuf};

/// The shared folder: `$SWARMPLAN_SHARED` when set; else the first folder named `shared`
/// that holds a `data` folder and sits in the current directory or one of its ancestors,
/// then in the running program's folder or one of its ancestors (so `../shared` beside a
/// checkout is found from anywhere in the checkout, and from its `target/release`); else
/// `shared` in the current directory (whose absence the caller reports).
#[must_use]
pub fn shared_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("SWARMPLAN_SHARED") {
        return PathBuf::from(dir);
    }
    let program_dir = std::env::current_exe()
        .ok()
        .and_then(|e| e.parent().map(Path::to_path_buf));
    std::env::current_dir()
        .ok()
        .into_iter()
        .chain(program_dir)
        .find_map(|root| shared_among_ancestors(&root))
        .unwrap_or_else(|| PathBuf::from("shared"))
}

/// The first `A/shared` with a `data` folder, A being `start` or one of its ancestors.
fn shared_among_ancestors(start: &Path) -> Option<PathBuf> {
    start
        .ancestors()
        .map(|a| a.join("shared"))
        .find(|s| s.join("data").is_dir())
}

/// True when reference data must be present (CI, or `SWARMPLAN_REQUIRE_SHARED`).
#[must_use]
pub fn required() -> bool {
    std::env::var_os("SWARMPLAN_REQUIRE_SHARED").is_some()
        || std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0")
}

/// `shared_dir()/data/<relative>` when every one of `relatives` exists: `Ok(Some(first))`.
/// When one is missing: `Ok(None)` after printing why (a skip), or `Err` naming the missing
/// file when the data is [`required`].
pub fn reference_files(relatives: &[&str]) -> Result<Option<Vec<PathBuf>>, String> {
    reference_files_in(&shared_dir(), required(), relatives)
}

/// [`reference_files`] under `shared`, with `required` given.
pub fn reference_files_in(
    shared: &Path,
    required: bool,
    relatives: &[&str],
) -> Result<Option<Vec<PathBuf>>, String> {
    let data = shared.join("data");
    let paths: Vec<PathBuf> = relatives.iter().map(|r| data.join(r)).collect();
    if let Some(missing) = paths.iter().find(|p| !p.exists()) {
        let message = format!(
            "{} not found (set SWARMPLAN_SHARED to the shared folder)",
            missing.display()
        );
        if required {
            return Err(format!("reference data required here (CI): {message}"));
        }
        eprintln!("skipped: {message}");
        return Ok(None);
    }
    Ok(Some(paths))
}

/// [`reference_files`] for one file.
pub fn reference_file(relative: &str) -> Result<Option<PathBuf>, String> {
    Ok(reference_files(&[relative])?.map(|mut v| v.remove(0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_data_skips_on_a_laptop_and_fails_in_ci() {
        let nowhere = Path::new("/nonexistent/shared");
        assert_eq!(
            reference_files_in(nowhere, false, &["spso/ChrismasTerrain.tif"]),
            Ok(None)
        );
        let e =
            reference_files_in(nowhere, true, &["spso/ChrismasTerrain.tif"]).expect_err("required");
        assert!(
            e.contains("/nonexistent/shared/data/spso/ChrismasTerrain.tif"),
            "{e}"
        );
        let here = Path::new(env!("CARGO_MANIFEST_DIR"));
        let found = reference_files_in(here, true, &[]).expect("nothing to find");
        assert_eq!(found, Some(Vec::new()));
    }
}
