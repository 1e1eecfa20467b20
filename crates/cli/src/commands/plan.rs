//! `swarmplan plan`: plan a scenario with one method, print the result, write `plan.json`,
//! `convergence.csv`, `run.json` (the typed [`RunArtifact`]) and `scenario.toml` into
//! `--out`.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_core::attempts::{run_attempts, Attempts, MAX_ATTEMPTS};
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, Termination};
use swarmplan_core::run::RunRequest;
use swarmplan_core::world::{flight_margin, World};
use swarmplan_experiment::workers;
use swarmplan_io::artifact::{ArtifactFiles, RunArtifact};
use swarmplan_io::plan_folder::PlanFolder;

use crate::render;
use crate::settings_args::SettingsArgs;
use crate::ScenarioArgs;

#[derive(Debug, Args)]
pub struct PlanArgs {
    #[command(flatten)]
    pub scenario: ScenarioArgs,
    /// Method: a preset or optimizer/encoding/init (help text: [`method_help`]).
    #[arg(
        long = "method",
        visible_alias = "algo",
        default_value = "swarmplan",
        help = method_help()
    )]
    pub method: Method,
    /// Replace the method's encoding: spherical, cartesian, angle.
    #[arg(long)]
    pub encoding: Option<EncodingKind>,
    /// Replace the method's initialisation: uniform, line, corridor (a threat-free corridor;
    /// docs/results.md, "Outside benchmark instances"), fan (half of the draws fan the fleet
    /// out; docs/results.md, "A fanned start"), route (the route layer's cheapest way by
    /// energy), band (the route layer's way in height, with its heights; docs/results.md,
    /// "The route layer in height"), line-corridor (line, then corridor from half the budget
    /// when still far from feasible; docs/results.md, "The route layer and the outside
    /// instances"), line-band (line, then band: swarmplan's).
    #[arg(long)]
    pub init: Option<InitKind>,
    /// Seed of the run (default: the scenario's `planning.seed`).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::parse_seed)]
    pub seed: Option<u64>,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Output folder for plan.json and convergence.csv.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Print one JSON object on stdout instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Skip the figures (top view, 3-D view, convergence, communication timeline).
    #[arg(long)]
    pub no_figures: bool,
    /// Also export the plan into --out: qgc-plan, wpl, geojson, kml, csv (comma-separated) or all.
    #[arg(long)]
    pub export: Option<String>,
    /// Geodetic origin LAT,LON[,ALT] for --export (overrides [geo] origin and the DEM's CRS).
    #[arg(long, allow_hyphen_values = true, requires = "export")]
    pub origin: Option<String>,
    /// Exit with status 3 (after writing every output) when the plan is infeasible.
    #[arg(long)]
    pub require_feasible: bool,
    /// Replace the plan already in --out (default: keep it and write to out-2, out-3, ...).
    #[arg(long)]
    pub force: bool,
    /// Stop after this many seconds, counted from the command's start (loading, the route
    /// layer's checks and the search), with the best plan so far (anytime planning; a run
    /// stopped by the clock is not reproducible, and says so).
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub time_limit: Option<f64>,
    /// Stop at the first feasible plan instead of improving it within the budget.
    #[arg(long)]
    pub until_feasible: bool,
    /// Run again from further seeds, up to this many runs in all, until a plan is feasible;
    /// keep the first feasible plan, or the least violating one. Each attempt spends the
    /// whole budget (more evaluations, not a better method; `--time-limit` bounds all of
    /// them together), and every attempt's seed is printed and stored in run.json.
    #[arg(long, default_value_t = 1, value_parser = parse_attempts, allow_negative_numbers = true)]
    pub attempts: usize,
    /// Worker threads evaluating a swarm (default 0: one per core, or `RAYON_NUM_THREADS`),
    /// at most one per core. The plan is the same bits for any number (docs/performance.md,
    /// "Parallel evaluation").
    #[arg(long, default_value_t = 0, value_parser = crate::parse_threads, allow_negative_numbers = true)]
    pub threads: usize,
    /// Search on the scenario with every hard geometric limit M metres tighter (UAV sizes,
    /// separation, terrain clearance, and the map box M m inside on each side), so that an
    /// aircraft straying up to M metres from the plan still keeps the scenario's limits
    /// (docs/flight.md, "A flight margin"). The plan is assessed, written and exported against
    /// the scenario as given; 0 (the default) searches on it as given.
    #[arg(
        long,
        value_name = "METRES",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub flight_margin: f64,
}

/// `--attempts`: 1 to [`MAX_ATTEMPTS`].
fn parse_attempts(s: &str) -> Result<usize, String> {
    let n: usize = s
        .parse()
        .map_err(|_| format!("expected a whole number from 1 to {MAX_ATTEMPTS}, got `{s}`"))?;
    if (1..=MAX_ATTEMPTS).contains(&n) {
        Ok(n)
    } else {
        Err(format!("expected 1 to {MAX_ATTEMPTS}, got {n}"))
    }
}

/// A run's progress on stderr: a bar on a terminal, otherwise a log line at the start, at the
/// first feasible plan and every 5 s.
struct ProgressBar {
    bar: Option<indicatif::ProgressBar>,
    started: std::time::Instant,
    last_line: std::time::Duration,
    feasible_seen: bool,
    uavs: usize,
    total: Option<u64>,
}

impl ProgressBar {
    fn new(budget: &Budget, uavs: usize, quiet: bool) -> Self {
        use std::io::IsTerminal as _;
        let total = budget.evaluations;
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let b = indicatif::ProgressBar::new(total.unwrap_or(0));
            b.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:30} {pos}/{len} evaluations  {elapsed}  {msg}",
                )
                .expect("a valid template"),
            );
            b
        });
        Self {
            bar,
            started: std::time::Instant::now(),
            last_line: std::time::Duration::ZERO,
            feasible_seen: false,
            uavs,
            total,
        }
    }

    fn update(&mut self, r: &swarmplan_core::optim::IterationRecord) {
        let state = if r.best_violation == 0.0 {
            "feasible".to_string()
        } else {
            format!("infeasible (violation {:.1})", r.best_violation)
        };
        let msg = format!(
            "iteration {}, best {:.1} per UAV, {state}",
            r.iteration,
            swarmplan_core::cost::cost_per_uav(r.best_cost, self.uavs)
        );
        let elapsed = self.started.elapsed();
        let first_feasible = r.best_violation == 0.0 && !self.feasible_seen;
        self.feasible_seen |= r.best_violation == 0.0;
        if let Some(bar) = &self.bar {
            bar.set_position(r.evaluations);
            bar.set_message(msg);
            if first_feasible {
                bar.println(format!(
                    "first feasible plan after {} evaluations ({:.1} s)",
                    r.evaluations,
                    elapsed.as_secs_f64()
                ));
            }
            return;
        }
        if first_feasible {
            eprintln!(
                "first feasible plan after {} evaluations ({:.1} s)",
                r.evaluations,
                elapsed.as_secs_f64()
            );
        }
        if r.iteration == 0 || elapsed - self.last_line >= std::time::Duration::from_secs(5) {
            self.last_line = elapsed;
            let of = self.total.map_or(String::new(), |t| format!(" of {t}"));
            eprintln!(
                "{:.1} s: {} evaluations{of}, {msg}",
                elapsed.as_secs_f64(),
                r.evaluations
            );
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Exit status of `plan --require-feasible` for an infeasible plan (2 is bad input).
pub const EXIT_INFEASIBLE: u8 = 3;

/// An infeasible outcome that exits with [`EXIT_INFEASIBLE`]: a plan under
/// `--require-feasible` (the outputs were written), or a scenario `scenario check` finds no
/// plan can satisfy. The text says which.
#[derive(Debug)]
pub struct Infeasible(pub String);

impl std::fmt::Display for Infeasible {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Infeasible {}

/// `--method`'s help, listing the presets from their one list.
fn method_help() -> String {
    format!(
        "Method: a preset ({}; swarmplan is the default) or optimizer/encoding/init (e.g. \
         pso/spherical/line; optimizers: {})",
        swarmplan_core::method::preset_names(),
        swarmplan_core::optim::OptimizerKind::names()
    )
}

/// What a plan run needs before it starts, every argument checked: a bad one leaves no
/// output folder behind.
struct Prepared {
    req: RunRequest,
    export: Option<crate::mission_export::PlannedExport>,
    pool: rayon::ThreadPool,
    /// A note when the thread count asked for was held to the cores.
    threads_note: Option<String>,
    folder: PlanFolder,
}

/// The files a finished run wrote, and its record.
struct Written {
    artifact: RunArtifact,
    plan: PathBuf,
    convergence: PathBuf,
    run: PathBuf,
    scenario: PathBuf,
    figures: Vec<PathBuf>,
}

pub fn run_command(args: &PlanArgs) -> Result<()> {
    // --time-limit counts from here: loading, the route layer's checks and the search.
    let began = std::time::Instant::now();
    let world = super::load_world(&args.scenario)?;
    let grown = flight_margin::grown_world(&world, args.flight_margin)
        .map_err(|e| anyhow::anyhow!("{e} (--flight-margin)"))?;
    let searched_on = grown.as_ref().unwrap_or(&world);
    let prepared = prepare(args, searched_on, began)?;
    if !args.json {
        eprintln!("{}", announcement(args, searched_on, &prepared.req));
    }
    if let Some(note) = &prepared.threads_note {
        eprintln!("{note}");
    }
    let mut attempts = run_with_progress(args, searched_on, &prepared);
    // With a margin the search's assessment is on the grown scenario; the plan is judged
    // against the scenario as given, and the margin's own verdict said beside it.
    let margin_verdict = grown
        .as_ref()
        .map(|_| attempts.result.judge_on(&world).verdict());
    let result = &attempts.result;
    if result.outcome.termination == Termination::TimeLimit {
        eprintln!(
            "stopped by --time-limit after {} evaluations: this run is not reproducible from its seed alone",
            result.outcome.evaluations
        );
    }
    let written = write_outputs(args, &world, &prepared, &attempts)?;
    let a = &result.assessment;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&written.artifact)?);
    } else {
        print_summary(args, &world, &attempts, &written);
    }
    if let Some(verdict) = margin_verdict {
        let m = args.flight_margin;
        let line = format!(
            "searched with a flight margin of {m} m (sizes, separation and clearance {m} m larger, the map box {m} m inside); with the margin: {verdict}; the scenario as given:"
        );
        if args.json {
            eprintln!("{line}");
        } else {
            println!("{line}");
        }
    }
    let line = a.verdict();
    // Under --time-limit the search in height (a second or so per start) is left out, so
    // that the explanation does not outlast the limit.
    let outcome =
        swarmplan_core::outcome::infeasible_outcome_searched(&world, a, args.time_limit.is_none());
    for l in std::iter::once(&line).chain(outcome.as_ref()) {
        if args.json {
            eprintln!("{l}");
        } else {
            println!("{l}");
        }
    }
    if args.require_feasible && !a.feasible() {
        return Err(Infeasible(format!("{line} (--require-feasible)")).into());
    }
    Ok(())
}

/// Checks every argument, makes the request and the worker pool, then settles the output
/// folder (last, so a bad argument leaves no `out-2`).
fn prepare(args: &PlanArgs, world: &World, began: std::time::Instant) -> Result<Prepared> {
    let resolved = args
        .settings
        .run_settings(args.time_limit, args.until_feasible)
        .resolve(args.method.optimizer.default_budget())
        .map_err(|e| anyhow::anyhow!(e.as_flag()))?;
    // Before the folder and the run: a bad --export is said at once.
    let export = args
        .export
        .as_deref()
        .map(|formats| {
            crate::mission_export::PlannedExport::prepare(
                &args.scenario.scenario,
                args.scenario.terrain.as_deref(),
                formats,
                args.origin.as_deref(),
            )
        })
        .transpose()?;
    let req = RunRequest {
        method: args.method.with(args.encoding, args.init),
        params: resolved.params,
        budget: swarmplan_core::optim::Budget {
            started: Some(began),
            ..resolved.budget
        },
        seed: args.seed.unwrap_or(world.spec().planning.seed),
    };
    let cores = workers::cores();
    let asked = workers::Asked::from_count_or_env(args.threads);
    let threads = asked.threads(cores);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .with_context(|| format!("cannot start {threads} worker threads"))?;
    let folder = PlanFolder::new(crate::out_folder::plan_folder(&args.out, args.force)?);
    Ok(Prepared {
        req,
        export,
        pool,
        threads_note: asked
            .held(cores)
            .map(|what| super::threads_note(&what, cores)),
        folder,
    })
}

/// The line `plan` says before it starts: what it plans, with which method, seed and budget.
fn announcement(args: &PlanArgs, world: &World, req: &RunRequest) -> String {
    format!(
        "planning {} with {} ({} on the {} encoding, {} init; seed {}, budget {} iterations / {} evaluations, population {}{})",
        world.spec().name,
        req.method,
        req.method.optimizer,
        req.method.encoding,
        req.method.init,
        req.seed,
        req.budget
            .max_iterations()
            .map_or("any".into(), |m| m.to_string()),
        req.budget
            .evaluations
            .map_or("any".into(), |m| m.to_string()),
        req.params.population(req.method.optimizer),
        if args.attempts > 1 {
            format!("; up to {} attempts", args.attempts)
        } else {
            String::new()
        }
    )
}

/// Runs the attempts on the worker pool with a progress bar (one per attempt), saying each
/// attempt's outcome when there are several.
fn run_with_progress(args: &PlanArgs, world: &World, prepared: &Prepared) -> Attempts {
    let req = &prepared.req;
    // A mutex, not a cell: the run goes to the worker pool.
    let progress =
        std::sync::Mutex::new(ProgressBar::new(&req.budget, world.uav_count(), args.json));
    let progress = || {
        progress
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    };
    let mut current = 1;
    let of = args.attempts;
    let run = || {
        run_attempts(
            world,
            req,
            args.attempts,
            &mut |attempt, r| {
                let mut p = progress();
                if attempt != current {
                    *p = ProgressBar::new(&req.budget, world.uav_count(), args.json);
                    current = attempt;
                }
                p.update(r);
            },
            &mut |a| {
                if of > 1 && !args.json {
                    progress().finish();
                    let verdict = if a.feasible {
                        "feasible".to_string()
                    } else {
                        format!("INFEASIBLE ({} violations)", a.violations)
                    };
                    eprintln!(
                        "attempt {} of {of}, seed {}: {verdict} after {} evaluations, {:.1} s",
                        a.attempt, a.seed, a.evaluations, a.seconds
                    );
                }
            },
        )
    };
    let attempts = prepared.pool.install(run);
    progress().finish();
    attempts
}

/// Writes the plan folder (plan, convergence, exports, run record, scenario, figures).
fn write_outputs(
    args: &PlanArgs,
    world: &World,
    prepared: &Prepared,
    attempts: &Attempts,
) -> Result<Written> {
    let (result, uav_trace) = (&attempts.result, &attempts.uav_trace);
    let folder = &prepared.folder;
    let plan = folder.write_plan(world, &result.plan)?;
    let convergence =
        folder.write_convergence(world.uav_count(), &result.outcome.trace, uav_trace)?;
    let mut files = ArtifactFiles {
        plan: plan.display().to_string(),
        convergence: convergence.display().to_string(),
        exports: Vec::new(),
    };
    if let Some(export) = &prepared.export {
        files.exports = export
            .write(world, &result.plan, folder.dir())?
            .iter()
            .map(|p| p.display().to_string())
            .collect();
    }
    let req = &prepared.req;
    let mut artifact = RunArtifact::new(world, result, req.budget, req.params, files);
    artifact.flight_margin = args.flight_margin;
    if args.attempts > 1 {
        artifact.attempts.clone_from(&attempts.records);
    }
    let run = folder.write_run(&artifact)?;
    let scenario = folder.write_scenario(world.spec())?;
    let figures = if args.no_figures {
        Vec::new()
    } else {
        let trace: Vec<f64> = result.outcome.trace.iter().map(|r| r.best_cost).collect();
        let iterations: Vec<usize> = result.outcome.trace.iter().map(|r| r.iteration).collect();
        crate::figures::plan_figures(
            folder.dir(),
            world,
            &result.plan,
            Some(&iterations),
            &trace,
            swarmplan_plot::PerUav::Rows(uav_trace),
            &crate::figures::plan_title(&world.spec().name, &artifact),
        )?
    };
    Ok(Written {
        artifact,
        plan,
        convergence,
        run,
        scenario,
        figures,
    })
}

/// What `plan` prints for a person: the assessment, the run, the attempts, the pace and
/// departures when free, and the files written.
fn print_summary(args: &PlanArgs, world: &World, attempts: &Attempts, written: &Written) {
    let result = &attempts.result;
    let a = &result.assessment;
    print!("{}", render::assessment(world, a));
    println!(
        "\nmethod {} ({} on the {} encoding, {} init), seed {}: {} evaluations, {} iterations, {:.3} s",
        result.method,
        result.method.optimizer,
        result.method.encoding,
        result.method.init,
        result.seed,
        result.outcome.evaluations,
        result.outcome.iterations,
        result.seconds
    );
    if args.attempts > 1 {
        let evaluations: u64 = attempts.records.iter().map(|a| a.evaluations).sum();
        let why = if a.feasible() {
            "the first feasible one"
        } else {
            "none feasible: the one of least violation measure, then cost"
        };
        let repeat = if result.outcome.termination == Termination::TimeLimit {
            "stopped by the clock, so its seed alone does not repeat it".to_owned()
        } else {
            format!("`--seed {}` repeats it alone", result.seed)
        };
        println!(
            "kept attempt {} of {} (--attempts {}; {why}), {evaluations} evaluations in all; {repeat}",
            attempts.chosen(),
            attempts.records.len(),
            args.attempts,
        );
    }
    let timing = &world.spec().timing;
    if timing.pace_is_free() {
        println!(
            "pace {:.3} (chosen in timing.pace [{}, {}]; 1 = nearest cruise)",
            result.plan.pace, timing.pace[0], timing.pace[1]
        );
    }
    if world.slots().any() {
        let timed = swarmplan_core::timing::TimedPlan::flown(world, &result.plan);
        let line = |u: usize| {
            let p = &timed.paths[u];
            format!("uav {u} {:.1}-{:.1} s", p.launch, p.arrival)
        };
        // A long fleet: the first two and the last, the rest in plan.json's times.
        let n = timed.paths.len();
        let shown = if n <= 8 {
            (0..n).map(line).collect::<Vec<_>>().join(", ")
        } else {
            format!(
                "{}, {}, ..., {} (every UAV's times in plan.json)",
                line(0),
                line(1),
                line(n - 1)
            )
        };
        println!(
            "take-off and landing (launch slots {} s, recovery slots {} s apart): {shown}",
            timing.launch_interval, timing.recovery_interval,
        );
    }
    if timing.delay_is_free() {
        let timed = swarmplan_core::timing::TimedPlan::flown(world, &result.plan);
        let departures: Vec<String> = timed
            .paths
            .iter()
            .enumerate()
            .map(|(u, p)| format!("uav {u} {:.1} s", p.depart))
            .collect();
        println!(
            "departures (each UAV hovers at its start until then; delays up to {:.0} % of the arrival time): {}",
            100.0 * timing.max_delay,
            departures.join(", ")
        );
    }
    println!(
        "wrote {}, {}, {} and {}",
        written.plan.display(),
        written.convergence.display(),
        written.run.display(),
        written.scenario.display()
    );
    for f in &written.figures {
        println!("wrote {} (and .svg)", f.display());
    }
    for f in &written.artifact.files.exports {
        println!("wrote {f}");
    }
}
