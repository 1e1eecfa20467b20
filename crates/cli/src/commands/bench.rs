//! `swarmplan bench` (run an experiment: by default the paper's Tables 4-5) and
//! `swarmplan aggregate` (merge shard folders into one summary).

use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use swarmplan_core::method::Method;
use swarmplan_experiment::aggregate::aggregate;
use swarmplan_experiment::matrix::{equal_budget, BudgetPolicy, ExperimentSpec, ParamSet, Shard};
use swarmplan_experiment::record::RunRecord;
use swarmplan_experiment::runner::{run_experiment, RunnerOptions};
use swarmplan_experiment::suite::{suite, suite_names};
use swarmplan_experiment::summary::{csv, markdown, summarize_records, ExperimentSummary};
use swarmplan_experiment::workers;

use crate::settings_args::SettingsArgs;

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Experiment file (TOML: master_seed, runs, scenarios, methods, [[param_sets]],
    /// [budget], terrain); flags below override its fields.
    #[arg(long)]
    pub experiment: Option<PathBuf>,
    /// Scenarios, comma-separated (default: paper-case1,paper-case2).
    #[arg(long, value_delimiter = ',', conflicts_with = "suite")]
    pub scenarios: Option<Vec<String>>,
    /// A named suite of scenarios instead of --scenarios: paper, outside (the 28 outside
    /// benchmark instances), outside-dev (22 to tune on), outside-held (6 held out: to report
    /// a kept design only), each also as -delay (departure delays free) and -u1 (one UAV),
    /// generated-8, generated-12, generated-20 (20 generated instances each), generated (all
    /// 60).
    #[arg(long)]
    pub suite: Option<String>,
    /// Methods, comma-separated: presets or optimizer/encoding/init (default: the paper's
    /// six plus SPSO).
    #[arg(long = "methods", visible_alias = "algos", value_delimiter = ',')]
    pub methods: Option<Vec<Method>>,
    /// Runs per scenario and method (default 200).
    #[arg(long, allow_negative_numbers = true)]
    pub runs: Option<usize>,
    /// Master seed (default 1); every run's seed derives from it.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::parse_seed)]
    pub seed: Option<u64>,
    /// Worker threads (default 0: one per core, or `RAYON_NUM_THREADS`), at most one per core.
    #[arg(long, default_value_t = 0, value_parser = crate::parse_threads, allow_negative_numbers = true)]
    pub threads: usize,
    /// Output folder.
    #[arg(long, default_value = "out/bench")]
    pub out: PathBuf,
    /// Budgets: `equal` (every method the same evaluations: 38,700, DLS-SMPSO's paper mean,
    /// or --evaluations / --iterations) or `paper` (each method its paper setting: 200
    /// iterations for the paper's methods). Default: equal.
    #[arg(long, value_parser = ["equal", "paper"])]
    pub budget: Option<String>,
    /// Feasibility profile of every run: `strict` (default; every constraint hard) or
    /// `paper` (threats, terrain, turns and energy hard; the rest cost only).
    #[arg(long, value_parser = crate::parse_profile)]
    pub profile: Option<swarmplan_core::feasibility::FeasibilityProfile>,
    /// Budget and parameters (a --params file becomes the parameter set `custom`).
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// GeoTIFF or ESRI ASCII grid replacing every scenario's terrain.
    #[arg(long)]
    pub terrain: Option<PathBuf>,
    /// Run only slice K of N of the matrix (for clusters; merge with `aggregate`).
    #[arg(long)]
    pub shard: Option<String>,
    /// Continue an interrupted experiment in --out without repeating or losing a run.
    #[arg(long)]
    pub resume: bool,
}

#[derive(Debug, Args)]
pub struct AggregateArgs {
    /// Folders written by `bench` (e.g. one per shard).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Where to write summary.md, summary.csv and summary.json.
    #[arg(long, default_value = "out/aggregate")]
    pub out: PathBuf,
}

/// Whether any flag that defines the matrix (not how or where it runs) was given.
fn defines_matrix(args: &BenchArgs) -> bool {
    let st = &args.settings;
    args.experiment.is_some()
        || args.scenarios.is_some()
        || args.suite.is_some()
        || args.methods.is_some()
        || args.runs.is_some()
        || args.seed.is_some()
        || args.budget.is_some()
        || args.profile.is_some()
        || args.terrain.is_some()
        || st.iterations.is_some()
        || st.evaluations.is_some()
        || st.params.is_some()
        || st.population.is_some()
}

/// Scenario and terrain files of a stored experiment are recorded relative to the folder
/// the bench was started in (they are part of each run's identity); from another folder
/// they are not found, which the load alone would say without the reason.
fn recorded_files_reachable(spec: &ExperimentSpec, stored: &Path) -> Result<()> {
    let files = spec
        .scenarios
        .iter()
        .filter(|s| !swarmplan_io::catalog::is_scenario_name(s))
        .chain(spec.terrain.as_ref());
    for f in files {
        anyhow::ensure!(
            Path::new(f).exists(),
            "{}: names the file {f}, which is not found from here; the paths of a bench's files are recorded relative to the folder it was started in: resume it from there",
            stored.display()
        );
    }
    Ok(())
}

fn experiment(args: &BenchArgs) -> Result<ExperimentSpec> {
    // `bench --resume --out DIR` alone continues the experiment the folder records; with
    // matrix flags, they must describe that same experiment (the runner compares).
    let stored = args.out.join("experiment.json");
    if args.resume && !defines_matrix(args) && stored.is_file() {
        let text = std::fs::read_to_string(&stored)
            .with_context(|| format!("{}: cannot read", stored.display()))?;
        let spec: ExperimentSpec = serde_json::from_str(&text)
            .map_err(|e| anyhow::anyhow!("{}: {e}", stored.display()))?;
        eprintln!(
            "bench: resuming the experiment recorded in {}",
            stored.display()
        );
        spec.validate()?;
        recorded_files_reachable(&spec, &stored)?;
        return Ok(spec);
    }
    if args.resume && !stored.is_file() {
        // A mistyped folder must not start the 2,800 runs of the defaults.
        anyhow::ensure!(
            defines_matrix(args),
            "--resume --out {}: nothing to resume there (no experiment.json); check the folder's name, or leave out --resume to start the experiment of the defaults",
            args.out.display()
        );
        // A new folder with the experiment in flags: say what starts.
        eprintln!(
            "bench: nothing to resume in {} (no experiment.json); starting the experiment the flags describe",
            args.out.display()
        );
    }
    let mut spec = match &args.experiment {
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .with_context(|| format!("{}: cannot read", p.display()))?;
            let spec = toml::from_str::<ExperimentSpec>(&text)
                .map_err(|e| anyhow::anyhow!("{}: {}", p.display(), e.to_string().trim_end()))?;
            relative_to(spec, p.parent().unwrap_or_else(|| Path::new("")))
        }
        None => ExperimentSpec::paper(1),
    };
    if let Some(s) = &args.scenarios {
        spec.scenarios.clone_from(s);
    }
    if let Some(name) = &args.suite {
        spec.scenarios = suite(name).ok_or_else(|| {
            anyhow::anyhow!("--suite: expected one of {}, got `{name}`", suite_names())
        })?;
    }
    if let Some(a) = &args.methods {
        spec.methods.clone_from(a);
    }
    if let Some(r) = args.runs {
        spec.runs = r;
    }
    if let Some(s) = args.seed {
        spec.master_seed = s;
    }
    let st = &args.settings;
    let fixed = st.iterations.is_some() || st.evaluations.is_some();
    match args.budget.as_deref() {
        Some("paper") if fixed => anyhow::bail!(
            "--budget paper gives each method its paper setting; it cannot be combined with --iterations or --evaluations"
        ),
        Some("paper") => spec.budget_policy = BudgetPolicy::Paper,
        Some(_) => spec.budget_policy = BudgetPolicy::Equal,
        None => {}
    }
    if fixed {
        spec.budget_policy = BudgetPolicy::Equal;
        spec.budget = st
            .run_settings(None, false)
            .budget(equal_budget())
            .map_err(|e| anyhow::anyhow!(e.as_flag()))?;
    }
    if st.params.is_some() || st.population.is_some() {
        let params = st
            .run_settings(None, false)
            .params()
            .map_err(|e| anyhow::anyhow!(e.as_flag()))?;
        let name = if st.params.is_some() {
            "custom"
        } else {
            "paper"
        };
        spec.param_sets = vec![ParamSet {
            name: name.into(),
            params,
        }];
    }
    if let Some(t) = &args.terrain {
        spec.terrain = Some(t.display().to_string());
    }
    if let Some(p) = args.profile {
        spec.profile = p;
    }
    spec.validate().map_err(|e| match &args.experiment {
        Some(p) => anyhow::anyhow!("{}: {e}", p.display()),
        None => e.into(),
    })?;
    // The file's own terrain is named as its field, not as a --terrain flag never given.
    if let (Some(p), None, Some(t)) = (&args.experiment, &args.terrain, &spec.terrain) {
        anyhow::ensure!(
            Path::new(t).is_file(),
            "{}: terrain: no file {t} (the path is relative to the experiment file's folder)",
            p.display()
        );
    }
    Ok(spec)
}

/// An experiment file's scenario files and terrain, which are relative to the file's folder
/// (as a scenario file's DEM is to the scenario), made relative to the current folder.
/// A file's path is the run's identity (its seeds, `experiment.json`), so it is spelt one
/// way however the experiment file was named (`e.toml`, `./e.toml`, its absolute path):
/// from the canonical paths of the file and the current folder (a file that does not exist
/// keeps the joined path, and its load says so).
fn relative_to(mut spec: ExperimentSpec, dir: &Path) -> ExperimentSpec {
    let cwd = std::env::current_dir().and_then(std::fs::canonicalize).ok();
    let resolve = |file: &str| {
        if Path::new(file).is_absolute() {
            return file.to_string();
        }
        let joined = dir.join(file);
        let from_cwd = std::fs::canonicalize(&joined)
            .ok()
            .zip(cwd.as_deref())
            .and_then(|(file, cwd)| pathdiff::diff_paths(file, cwd));
        from_cwd.unwrap_or(joined).display().to_string()
    };
    for s in &mut spec.scenarios {
        if !swarmplan_io::catalog::is_scenario_name(s) {
            *s = resolve(s);
        }
    }
    if let Some(t) = &mut spec.terrain {
        *t = resolve(t);
    }
    spec
}

/// Refuses two spellings of one scenario file (`sc/a.toml`, `./sc/a.toml`, a link to it):
/// the matrix refuses a name listed twice, but these are different names for the same
/// runs, each with its own seeds.
fn same_file_twice(scenarios: &[String]) -> Result<()> {
    let mut seen = std::collections::HashMap::new();
    for s in scenarios {
        if swarmplan_io::catalog::is_scenario_name(s) {
            continue;
        }
        if let Ok(file) = std::fs::canonicalize(s) {
            if let Some(first) = seen.insert(file, s) {
                anyhow::bail!(
                    "scenarios: `{s}` is the same file as `{first}`; list each scenario once"
                );
            }
        }
    }
    Ok(())
}

/// The budget of an experiment in words, e.g. `equal budgets: 38700 evaluations per run`.
fn describe_budget(spec: &ExperimentSpec) -> String {
    match spec.budget_policy {
        BudgetPolicy::Paper => {
            "paper budgets: each method its paper setting (200 iterations; swarmplan 38700 evaluations)".into()
        }
        BudgetPolicy::Equal => {
            let b = spec.budget;
            let parts: Vec<String> = [
                b.evaluations.map(|e| format!("{e} evaluations")),
                b.max_iterations().map(|i| format!("{i} iterations")),
            ]
            .into_iter()
            .flatten()
            .collect();
            format!("equal budgets: {} per run", parts.join(" or "))
        }
    }
}

/// Spacing of progress lines when stderr is not a terminal.
const LOG_EVERY: std::time::Duration = std::time::Duration::from_secs(30);

/// Counts behind the progress lines.
#[derive(Default)]
struct LogLines {
    done: u64,
    feasible: u64,
    next_line: std::time::Duration,
}

impl LogLines {
    fn record(&mut self, feasible: bool) {
        self.done += 1;
        self.feasible += u64::from(feasible);
    }
}

pub fn run_bench(args: &BenchArgs) -> Result<()> {
    let spec = experiment(args)?;
    same_file_twice(&spec.scenarios)?;
    // Scenarios no plan can satisfy are said once, before the runs start; a scenario that
    // does not load, or a bad --shard, is said before the folder is made.
    for name in &spec.scenarios {
        let loaded = swarmplan_io::catalog::load_spec(name)?;
        super::warn_unreachable(&loaded.origin, &loaded.spec);
    }
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?;
    crate::out_folder::bench_folder(&args.out)?;
    // Ctrl-C stops the process itself: the records written stay, `--resume` goes on.
    let cores = workers::cores();
    let asked = workers::Asked::from_count_or_env(args.threads);
    let threads = asked.threads(cores);
    if let Some(what) = asked.held(cores) {
        eprintln!("{}", super::threads_note(&what, cores));
    }
    let opts = RunnerOptions {
        threads,
        shard,
        resume: args.resume,
        cancel: swarmplan_core::optim::cancel::Cancel::NONE,
    };
    eprintln!(
        "bench: {} scenarios x {} methods x {} parameter sets x {} runs = {} runs, {}, profile {}, master seed {}, {} threads{}, into {}",
        spec.scenarios.len(),
        spec.methods.len(),
        spec.param_sets.len(),
        spec.runs,
        spec.size(),
        describe_budget(&spec),
        spec.profile,
        spec.master_seed,
        threads,
        shard.map_or(String::new(), |s| format!(", shard {}/{}", s.index, s.count)),
        args.out.display()
    );
    let terminal = std::io::stderr().is_terminal();
    let bar = if terminal {
        ProgressBar::new(0)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs  {per_sec}  ETA {eta}  {msg}")
            .expect("a valid template"),
    );
    let started = Instant::now();
    let mut start = |pending: usize| bar.set_length(pending as u64);
    // Off a terminal (a log file, a cluster job): a line every LOG_EVERY with the count,
    // the feasible share so far and an estimate of the time left.
    let log = std::sync::Mutex::new(LogLines::default());
    let done = |r: &RunRecord| {
        bar.set_message(format!("{} {} #{}", r.scenario, r.method, r.run));
        bar.inc(1);
        if !terminal {
            let mut log = log
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            log.record(r.feasible);
            let elapsed = started.elapsed();
            if elapsed >= log.next_line {
                log.next_line = elapsed + LOG_EVERY;
                let total = bar.length().unwrap_or(0);
                let left = total.saturating_sub(log.done) as f64;
                let eta = elapsed.as_secs_f64() / log.done.max(1) as f64 * left;
                eprintln!(
                    "bench: {}/{total} runs, {} feasible, {:.0} s elapsed, about {:.0} s left; last {} {} #{}",
                    log.done,
                    log.feasible,
                    elapsed.as_secs_f64(),
                    eta,
                    r.scenario,
                    r.method,
                    r.run
                );
            }
        }
    };
    if let Some(warning) = swarmplan_experiment::store::other_builds_warning(&args.out)? {
        eprintln!("warning: {warning}");
    }
    let outcome = run_experiment(&spec, &args.out, opts, &mut start, &done)?;
    bar.finish_and_clear();
    let secs = started.elapsed().as_secs_f64();
    eprintln!(
        "bench: {} runs in {secs:.1} s ({} already recorded); records in {}",
        outcome.executed,
        outcome.skipped,
        args.out.join("runs.jsonl").display()
    );
    if outcome.records.len() < spec.size() {
        eprintln!(
            "bench: {} of {} runs recorded in this folder; merge the shards with `swarmplan aggregate DIR...`",
            outcome.records.len(),
            spec.size()
        );
        return Ok(());
    }
    let summary = summarize_records(spec.master_seed, &outcome.records);
    write_summary(&args.out, &summary)?;
    for f in crate::figures::bench_figures(&args.out, &outcome.records)? {
        eprintln!("wrote {} (and .svg)", f.display());
    }
    Ok(())
}

pub fn run_aggregate(args: &AggregateArgs) -> Result<()> {
    // Read before the out folder is made, so a malformed builds.json or shards that do not
    // belong together leave nothing behind.
    let builds = swarmplan_experiment::store::ShardBuilds::of(&args.dirs)?;
    let (spec, records) = aggregate(&args.dirs)?;
    crate::out_folder::aggregate_folder(&args.out, &args.dirs)?;
    if let Some(warning) = builds.warning() {
        eprintln!("warning: {warning}");
    }
    let summary = summarize_records(spec.master_seed, &records);
    let text = serde_json::to_string_pretty(&spec)? + "\n";
    std::fs::write(args.out.join("experiment.json"), text)?;
    builds.write(&args.out)?;
    eprintln!(
        "aggregate: {} runs from {} folders",
        records.len(),
        args.dirs.len()
    );
    write_summary(&args.out, &summary)?;
    for f in crate::figures::bench_figures(&args.out, &records)? {
        eprintln!("wrote {} (and .svg)", f.display());
    }
    Ok(())
}

fn write_summary(dir: &Path, s: &ExperimentSummary) -> Result<()> {
    let md = markdown(s);
    let files = [
        ("summary.md", md.clone()),
        ("summary.csv", csv(s)),
        ("summary.json", serde_json::to_string_pretty(s)? + "\n"),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).with_context(|| format!("{}: cannot write", path.display()))?;
    }
    print!("{md}");
    eprintln!(
        "wrote {}/summary.md, summary.csv, summary.json",
        dir.display()
    );
    Ok(())
}
