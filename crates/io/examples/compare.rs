//! Every algorithm of the paper on both paper cases with paper settings (population 50,
//! 200 iterations), over a few seeds: mean cost per UAV, feasible share, evaluations and
//! seconds per run. A quick comparison for development; `swarmplan bench` is the full
//! experiment.
//!
//! Run: `cargo run --release -p swarmplan-io --example compare [SEEDS] [THREADS]`

use std::sync::Mutex;

use swarmplan_core::optim::{Algorithm, AlgorithmParams, Budget};
use swarmplan_core::run::{run, RunRequest};
use swarmplan_io::scenario::{build_world, load_spec};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let seeds: u64 = args.next().map_or(Ok(20), |s| s.parse())?;
    let threads: usize = args.next().map_or(Ok(2), |s| s.parse())?;
    println!("| case | algorithm | runs | FR (%) | mean cost/UAV | median cost/UAV | best | worst | mean evals | s/run |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for case in ["paper-case1", "paper-case2"] {
        let world = build_world(&load_spec(case)?, None)?;
        for alg in Algorithm::ALL {
            let results = Mutex::new(Vec::new());
            std::thread::scope(|s| {
                for t in 0..threads {
                    let (world, results) = (&world, &results);
                    s.spawn(move || {
                        for seed in (1..=seeds).filter(|k| (*k as usize) % threads == t) {
                            let req = RunRequest {
                                algorithm: alg,
                                encoding: None,
                                params: AlgorithmParams::default(),
                                budget: Budget::iterations(200),
                                seed,
                            };
                            let r = run(world, &req, &mut |_| {});
                            let row = (
                                r.assessment.per_uav_cost(),
                                r.assessment.feasible(),
                                r.outcome.evaluations,
                                r.seconds,
                            );
                            results.lock().expect("no thread panicked").push(row);
                        }
                    });
                }
            });
            let mut rows = results.into_inner()?;
            rows.sort_by(|a, b| a.0.total_cmp(&b.0));
            let n = rows.len() as f64;
            let mean = rows.iter().map(|r| r.0).sum::<f64>() / n;
            let feasible = rows.iter().filter(|r| r.1).count();
            let evals = rows.iter().map(|r| r.2 as f64).sum::<f64>() / n;
            let secs = rows.iter().map(|r| r.3).sum::<f64>() / n;
            println!(
                "| {case} | {alg} | {} | {:.0} | {mean:.1} | {:.1} | {:.1} | {:.1} | {evals:.0} | {secs:.2} |",
                rows.len(),
                100.0 * feasible as f64 / n,
                rows[rows.len() / 2].0,
                rows[0].0,
                rows[rows.len() - 1].0
            );
        }
    }
    Ok(())
}
