//! Cross-check of `swarmplan_experiment::stats` against scipy.
//!
//! The unit tests check hand-computed cases, which share the author's reading of each
//! formula; this test compares with an implementation written elsewhere. It writes fixed
//! data sets (ties, unequal sizes, `+inf`, small and large 2x2 tables, a Friedman design
//! with ties) to a temporary JSON file, runs `python3 tests/scipy_crosscheck.py INPUT`,
//! which answers with scipy's results (numpy for summaries, statsmodels or the written-out
//! formula for Holm, scipy plus exact rational arithmetic for Fisher), and compares: 1e-9
//! relative, or a tiny absolute difference for values near 0.
//!
//! Without `python3` or scipy the test prints why it is skipped and passes, so a bare
//! machine can still run `cargo test`; CI installs scipy and sets
//! `SWARMPLAN_REQUIRE_SCIPY=1`, which turns the skip into a failure. Run with
//! `--nocapture` to see the largest difference found for each quantity.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use serde_json::{json, Value};
use swarmplan_experiment::stats::{self, json_f64};

/// Relative tolerance of every comparison.
const RELATIVE: f64 = 1e-9;
/// Absolute tolerance for statistics near 0 (a Friedman statistic of a balanced design).
const ABSOLUTE_STATISTIC: f64 = 1e-12;
/// Absolute tolerance for p-values near 0 (a Fisher p-value below 1e-300 underflows).
const ABSOLUTE_P: f64 = 1e-15;

/// Deterministic values without a dev-dependency on an RNG crate (splitmix64).
struct Sequence(u64);

impl Sequence {
    fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `n` values in `[offset, offset + scale)`, rounded to `decimals` to make ties.
    fn values(&mut self, n: usize, offset: f64, scale: f64, decimals: i32) -> Vec<f64> {
        let factor = 10f64.powi(decimals);
        (0..n)
            .map(|_| ((offset + scale * self.next_unit()) * factor).round() / factor)
            .collect()
    }
}

struct DataSets {
    summary: Vec<Vec<f64>>,
    rank_sum: Vec<(Vec<f64>, Vec<f64>)>,
    holm: Vec<Vec<f64>>,
    fisher: Vec<[u64; 4]>,
    friedman: Vec<Vec<Vec<f64>>>,
}

fn data_sets() -> DataSets {
    let inf = f64::INFINITY;
    let mut seq = Sequence(20_240_601);
    let summary = vec![
        vec![3.2, 1.5, 2.7, 9.1, 4.4],
        vec![1.0],
        vec![2.0, 2.0, 5.0, 1e6, -3.5, 0.001],
        vec![1.0, inf, 2.5, 3.0],
        vec![inf, 4.0],
        vec![1e8 + 0.1, 1e8 + 0.2, 1e8 + 0.3, 1e8 + 0.7],
        seq.values(30, 100.0, 50.0, 6),
    ];
    let rank_sum = vec![
        (
            vec![0.8, 3.1, 2.4, 5.9, 1.7],
            vec![4.2, 6.6, 3.9, 7.5, 2.0, 8.8, 5.1, 9.3],
        ),
        (
            vec![1.0, 2.0, 2.0, 3.0, 5.0, 5.0],
            vec![2.0, 3.0, 3.0, 4.0, 6.0],
        ),
        (
            vec![1.2, inf, 3.4, inf, 0.5],
            vec![2.2, 2.3, 4.1, 0.9, inf, 1.7, 5.5],
        ),
        (vec![4.0, 4.0, 4.0], vec![4.0, 4.0]),
        (vec![1.0], vec![2.0]),
        (vec![1.0, 4.0], vec![2.0, 3.0]),
        // Small samples without ties: the exact distribution (n = 3 is where the normal
        // approximation is furthest off).
        (vec![1.5, 2.5, 0.5], vec![3.5, 4.5, 5.5]),
        (seq.values(7, 0.0, 1.0, 6), seq.values(9, 0.5, 1.0, 6)),
        (seq.values(20, 0.0, 1.0, 6), seq.values(20, 0.6, 1.0, 6)),
        (seq.values(30, 10.0, 5.0, 1), seq.values(25, 11.0, 5.0, 1)),
        // Far apart: p near 1e-17 tests the tail of the normal approximation.
        (seq.values(50, 0.0, 1.0, 6), seq.values(50, 1.0, 1.0, 6)),
    ];
    // Holm over the rank-sum p-values, as a results table would use it, and fixed lists.
    let rank_sum_p = rank_sum
        .iter()
        .map(|(x, y)| stats::rank_sum(x, y).unwrap().p_value);
    let holm = vec![
        rank_sum_p.collect(),
        vec![0.01, 0.04, 0.03, 0.005, 0.2],
        vec![0.5, 0.6, 0.01, 0.01],
        vec![0.3, 0.4, 0.9],
        vec![1e-20, 0.049, 0.0125, 1.0, 0.0, 0.0251],
        vec![0.02],
    ];
    let fisher = vec![
        [3, 1, 1, 3],
        [8, 2, 1, 5],
        [1, 9, 11, 3],
        [0, 0, 3, 4],
        [10, 0, 0, 10],
        [25, 5, 12, 18],
        [0, 20, 15, 5],
        [7, 12, 0, 0],
        [1200, 800, 950, 1100],
        [1500, 1520, 1480, 1510],
        [1000, 1050, 1050, 1000],
        [2000, 2100, 2100, 2000],
        [3000, 10, 10, 3000],
    ];
    let ties_design = vec![
        vec![3.1, 2.0, 2.0, 4.5],
        vec![1.0, 1.0, 1.0, 2.0],
        vec![5.0, 2.5, 3.5, inf],
        vec![2.2, 1.1, 3.3, 3.3],
        vec![7.0, 7.0, 6.0, 8.0],
        vec![inf, 0.5, inf, 0.7],
    ];
    let random_design = (0..20).map(|_| seq.values(5, 0.0, 3.0, 0)).collect();
    let friedman = vec![
        ties_design,
        random_design,
        vec![vec![1.0, 2.0, 3.0]; 4],
        vec![
            vec![1.0, 2.0, 3.0],
            vec![2.0, 3.0, 1.0],
            vec![3.0, 1.0, 2.0],
        ],
        // Every block all ties: scipy says NaN, `friedman` says 0 and p = 1.
        vec![vec![2.0, 2.0, 2.0]; 3],
    ];
    DataSets {
        summary,
        rank_sum,
        holm,
        fisher,
        friedman,
    }
}

fn num(v: f64) -> Value {
    json_f64::non_finite_name(v).map_or_else(|| json!(v), |name| json!(name))
}

fn nums(v: &[f64]) -> Value {
    Value::Array(v.iter().map(|&x| num(x)).collect())
}

fn to_json(d: &DataSets) -> Value {
    json!({
        "summary": d.summary.iter().map(|v| nums(v)).collect::<Vec<_>>(),
        "rank_sum": d.rank_sum.iter().map(|(x, y)| json!({"x": nums(x), "y": nums(y)}))
            .collect::<Vec<_>>(),
        "holm": d.holm.iter().map(|v| nums(v)).collect::<Vec<_>>(),
        "fisher": d.fisher,
        "friedman": d.friedman.iter()
            .map(|blocks| blocks.iter().map(|b| nums(b)).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
    })
}

fn read(v: &Value) -> f64 {
    json_f64::deserialize(v).unwrap_or_else(|e| panic!("not a number: {v}: {e}"))
}

#[derive(Clone, Copy)]
enum Kind {
    Statistic,
    PValue,
}

/// Comparisons made so far: the largest relative difference per quantity, and failures.
#[derive(Default)]
struct Report {
    worst: BTreeMap<&'static str, (f64, String)>,
    failures: Vec<String>,
    compared: usize,
}

impl Report {
    fn check(&mut self, quantity: &'static str, case: String, ours: f64, scipy: f64, kind: Kind) {
        self.compared += 1;
        let (relative, ok) = if ours.is_finite() && scipy.is_finite() {
            let diff = (ours - scipy).abs();
            let scale = ours.abs().max(scipy.abs());
            let relative = if diff == 0.0 { 0.0 } else { diff / scale };
            let absolute = match kind {
                Kind::Statistic => ABSOLUTE_STATISTIC,
                Kind::PValue => ABSOLUTE_P,
            };
            (relative, relative <= RELATIVE || diff <= absolute)
        } else {
            let same = ours.total_cmp(&scipy).is_eq() || (ours.is_nan() && scipy.is_nan());
            (if same { 0.0 } else { f64::INFINITY }, same)
        };
        let entry = self.worst.entry(quantity).or_insert((-1.0, String::new()));
        if relative > entry.0 {
            *entry = (relative, format!("{case}: ours {ours:e}, scipy {scipy:e}"));
        }
        if !ok {
            self.failures
                .push(format!("{quantity} {case}: ours {ours:e}, scipy {scipy:e}"));
        }
    }

    fn fail(&mut self, message: String) {
        self.failures.push(message);
    }
}

/// Why the cross-check cannot run here, or `None` when python3 imports scipy.
fn missing_python() -> Option<String> {
    match Command::new("python3")
        .args(["-c", "import scipy, numpy"])
        .output()
    {
        Err(e) => Some(format!("python3 could not be started ({e})")),
        Ok(o) if !o.status.success() => {
            let stderr = String::from_utf8_lossy(&o.stderr);
            let last = stderr.lines().last().unwrap_or("no message").to_owned();
            Some(format!("python3 cannot import scipy and numpy ({last})"))
        }
        Ok(_) => None,
    }
}

fn run_scipy(input: &Value) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("input.json");
    std::fs::write(&path, serde_json::to_vec(input).unwrap()).unwrap();
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scipy_crosscheck.py");
    let output = Command::new("python3")
        .arg(&script)
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{} failed: {}",
        script.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

fn compare_summaries(d: &DataSets, scipy: &Value, report: &mut Report) {
    for (i, values) in d.summary.iter().enumerate() {
        let ours = stats::summarize(values).unwrap();
        let theirs = &scipy["summary"][i];
        let case = format!("summary[{i}]");
        assert_eq!(theirs["n"].as_u64(), Some(ours.n as u64), "{case}");
        for (name, value) in [
            ("summary.mean", ours.mean),
            ("summary.median", ours.median),
            ("summary.min", ours.min),
            ("summary.max", ours.max),
        ] {
            let field = name.trim_start_matches("summary.");
            report.check(
                name,
                case.clone(),
                value,
                read(&theirs[field]),
                Kind::Statistic,
            );
        }
        let std = read(&theirs["std"]);
        if std.is_nan() && values.iter().any(|v| v.is_infinite()) {
            // Documented departure: numpy's std of data holding inf is NaN, ours is inf.
            if ours.std != f64::INFINITY {
                report.fail(format!(
                    "{case}: std with inf should be inf, got {}",
                    ours.std
                ));
            }
        } else {
            report.check("summary.std", case, ours.std, std, Kind::Statistic);
        }
    }
}

fn compare_rank_sums(d: &DataSets, scipy: &Value, report: &mut Report) {
    for (i, (x, y)) in d.rank_sum.iter().enumerate() {
        let ours = stats::rank_sum(x, y).unwrap();
        let theirs = &scipy["rank_sum"][i];
        let case = format!("rank_sum[{i}] (n = {}, {})", x.len(), y.len());
        report.check(
            "rank_sum.u",
            case.clone(),
            ours.u,
            read(&theirs["u"]),
            Kind::Statistic,
        );
        // scipy answers both ways; ours must match the one it says it used.
        let field = match ours.method {
            stats::RankSumMethod::Exact => "p_exact",
            stats::RankSumMethod::Normal => "p_value",
        };
        let p = read(&theirs[field]);
        report.check(
            "rank_sum.p_value",
            format!("{case} {}", ours.method.name()),
            ours.p_value,
            p,
            Kind::PValue,
        );
    }
}

fn compare_holm(d: &DataSets, scipy: &Value, report: &mut Report) {
    for (i, p) in d.holm.iter().enumerate() {
        let ours = stats::holm(p);
        let theirs = scipy["holm"][i].as_array().unwrap();
        assert_eq!(ours.len(), theirs.len());
        for (j, (a, b)) in ours.iter().zip(theirs).enumerate() {
            report.check("holm", format!("holm[{i}][{j}]"), *a, read(b), Kind::PValue);
        }
    }
}

fn compare_fisher(d: &DataSets, scipy: &Value, report: &mut Report) {
    for (i, &[a, b, c, e]) in d.fisher.iter().enumerate() {
        let ours = stats::fisher_exact(a, b, c, e);
        let theirs = &scipy["fisher"][i];
        let case = format!("fisher[[{a}, {b}], [{c}, {e}]]");
        let p = read(&theirs["p_value"]);
        report.check(
            "fisher.p_value (scipy)",
            case.clone(),
            ours,
            p,
            Kind::PValue,
        );
        let exact = read(&theirs["exact"]);
        report.check(
            "fisher.p_value (exact rational)",
            case,
            ours,
            exact,
            Kind::PValue,
        );
    }
}

fn compare_friedman(d: &DataSets, scipy: &Value, report: &mut Report) {
    for (i, blocks) in d.friedman.iter().enumerate() {
        let ours = stats::friedman(blocks).unwrap();
        let theirs = &scipy["friedman"][i];
        let k = blocks[0].len();
        let case = format!("friedman[{i}] (n = {}, k = {k})", blocks.len());
        assert_eq!(ours.df, k - 1);
        let statistic = read(&theirs["statistic"]);
        if statistic.is_nan() {
            // Documented departure: all ties, scipy's 0/0 is NaN; ours is 0 with p = 1.
            if (ours.statistic, ours.p_value) != (0.0, 1.0) {
                report.fail(format!("{case}: all ties should give (0, 1), got {ours:?}"));
            }
        } else {
            report.check(
                "friedman.statistic",
                case.clone(),
                ours.statistic,
                statistic,
                Kind::Statistic,
            );
            let p = read(&theirs["p_value"]);
            report.check(
                "friedman.p_value",
                case.clone(),
                ours.p_value,
                p,
                Kind::PValue,
            );
        }
        let ranks = theirs["mean_ranks"].as_array().unwrap();
        for (j, (a, b)) in ours.mean_ranks.iter().zip(ranks).enumerate() {
            report.check(
                "friedman.mean_ranks",
                format!("{case}[{j}]"),
                *a,
                read(b),
                Kind::Statistic,
            );
        }
    }
}

#[test]
fn statistics_match_scipy() {
    if let Some(reason) = missing_python() {
        assert!(
            std::env::var_os("SWARMPLAN_REQUIRE_SCIPY").is_none(),
            "SWARMPLAN_REQUIRE_SCIPY is set but {reason}"
        );
        println!("scipy cross-check skipped: {reason}; `pip install scipy` to run it");
        return;
    }
    let d = data_sets();
    let scipy = run_scipy(&to_json(&d));
    let mut report = Report::default();
    compare_summaries(&d, &scipy, &mut report);
    compare_rank_sums(&d, &scipy, &mut report);
    compare_holm(&d, &scipy, &mut report);
    compare_fisher(&d, &scipy, &mut report);
    compare_friedman(&d, &scipy, &mut report);
    println!(
        "scipy cross-check: {} comparisons against scipy {}, numpy {} (Holm: {})",
        report.compared,
        scipy["versions"]["scipy"],
        scipy["versions"]["numpy"],
        scipy["holm_source"]
    );
    for (quantity, (relative, case)) in &report.worst {
        println!("  {quantity:<32} largest relative difference {relative:.1e} at {case}");
    }
    assert!(
        report.failures.is_empty(),
        "differences from scipy:\n{}",
        report.failures.join("\n")
    );
}
