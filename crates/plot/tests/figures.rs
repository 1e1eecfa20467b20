//! Every figure on the `tiny` scenario: each PNG decodes at the requested size, is not
//! blank and has text in its title band; each SVG is a complete SVG document of that size
//! with text in it. Failures name the file.

use std::collections::BTreeMap;
use std::path::Path;

use swarmplan_core::encoding::{build, EncodingKind};
use swarmplan_core::method::Method;
use swarmplan_core::optim::OptimizerParams;
use swarmplan_core::plan::Plan;
use swarmplan_core::world::World;
use swarmplan_experiment::record::RunRecord;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;
use swarmplan_plot::{
    bench_boxplots, comm_timeline, convergence_bench, convergence_run, performance_profile,
    top_view, view_3d, PerUav, PlotError, Target, Written,
};

fn tiny() -> World {
    let loaded = load_spec("tiny").expect("tiny is built in");
    build_world(&loaded, None).expect("tiny builds")
}

/// A decoded spherical vector spread over the bounds by the golden ratio (deterministic,
/// no RNG needed).
fn plan(world: &World) -> Plan {
    let enc = build(EncodingKind::Spherical, world);
    let x: Vec<f64> = enc
        .bounds()
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let f = ((k as f64 + 1.0) * 0.618_033_988_75).fract();
            b.lo + (b.hi - b.lo) * f
        })
        .collect();
    enc.decode(&x)
}

fn record(alg: Method, run: usize, cost: f64, feasible: bool) -> RunRecord {
    let convergence: Vec<f64> = (0..31)
        .map(|k| cost * (1.0 + 4.0 * (-(k as f64) / 6.0).exp()) + run as f64)
        .collect();
    RunRecord {
        scenario: "tiny".into(),
        param_set: "default".into(),
        method: alg,
        optimizer: alg.optimizer,
        encoding: alg.encoding,
        init: alg.init,
        run,
        master_seed: 1,
        seed: 100 + run as u64,
        params: OptimizerParams::default(),
        cost_total: cost * 2.0,
        cost_per_uav: cost,
        uav_costs: vec![cost, cost],
        terms: BTreeMap::new(),
        feasible,
        profile: swarmplan_core::feasibility::FeasibilityProfile::Strict,
        violations: BTreeMap::new(),
        soft_violations: BTreeMap::new(),
        evaluations: 1000,
        iterations: 30,
        seconds: 0.1,
        convergence,
        // Methods spend different evaluations per iteration.
        convergence_evaluations: (0..31)
            .map(|k| {
                50 + k
                    * (20
                        + 10 * u64::from(
                            alg.optimizer == swarmplan_core::optim::OptimizerKind::Pso,
                        ))
            })
            .collect(),
        convergence_iterations: Vec::new(),
        first_feasible_evaluations: None,
    }
}

fn records() -> Vec<RunRecord> {
    let mut out = Vec::new();
    for (a, alg) in ["dls-smpso", "spso", "pso"]
        .map(|m| Method::preset(m).expect("a preset"))
        .into_iter()
        .enumerate()
    {
        for run in 0..8 {
            let base = 1500.0 + 200.0 * a as f64 + 37.0 * ((run * 7) % 5) as f64;
            // One penalised run per algorithm, one infinite for PSO.
            let cost = match (a, run) {
                (2, 7) => f64::INFINITY,
                (_, 3) => base + 20_000.0,
                _ => base,
            };
            out.push(record(alg, run, cost, run % 3 != 0));
        }
    }
    out
}

fn check_png(path: &Path, size: (u32, u32)) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: does not decode: {e}", path.display()))
        .to_rgb8();
    assert_eq!(img.dimensions(), size, "{}", path.display());
    let luma: Vec<f64> = img
        .pixels()
        .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
        .collect();
    let mean = luma.iter().sum::<f64>() / luma.len() as f64;
    let var = luma.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / luma.len() as f64;
    assert!(
        var > 200.0,
        "{}: nearly blank (variance {var:.1})",
        path.display()
    );
    // The title is drawn: dark pixels in the top band.
    let band = (size.1 / 18) as usize;
    let dark = img
        .rows()
        .take(band)
        .flatten()
        .filter(|p| u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2]) < 300)
        .count();
    assert!(
        dark > 100,
        "{}: no title text ({dark} dark pixels)",
        path.display()
    );
}

fn check_svg(path: &Path, size: (u32, u32)) {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: cannot read: {e}", path.display()));
    let head = text.trim_start();
    assert!(
        head.starts_with("<svg") || head.starts_with("<?xml"),
        "{}: not an SVG document",
        path.display()
    );
    assert!(
        text.trim_end().ends_with("</svg>"),
        "{}: unterminated",
        path.display()
    );
    assert!(
        text.contains(&format!("width=\"{}\"", size.0))
            && text.contains(&format!("height=\"{}\"", size.1)),
        "{}: wrong size",
        path.display()
    );
    assert!(text.contains("<text"), "{}: no text", path.display());
}

/// The relief is one embedded PNG covering the plotting area exactly: its pixel size has
/// the map's aspect ratio (one metre east = one metre north), and it is a valid data URL.
fn check_equal_aspect(svg: &Path, world: &World) {
    let text = std::fs::read_to_string(svg).expect("the SVG was written");
    let at = text
        .find("<image ")
        .expect("the relief is embedded as an image");
    let tag = &text[at..at + text[at..].find('>').expect("the tag ends")];
    let attr = |name: &str| -> f64 {
        let key = format!(" {name}=\"");
        let from = tag.find(&key).expect("the attribute is there") + key.len();
        tag[from..from + tag[from..].find('"').expect("the value ends")]
            .parse()
            .expect("a number")
    };
    let (w, h) = (attr("width"), attr("height"));
    let m = &world.spec().map;
    let aspect = (m.x[1] - m.x[0]) / (m.y[1] - m.y[0]);
    // One pixel of rounding on a few hundred.
    assert!(
        (w / h - aspect).abs() < 2.0 / h * aspect,
        "{}: relief {w} x {h} px, map aspect {aspect}",
        svg.display()
    );
    assert!(
        tag.contains("href=\"data:image/png;base64,"),
        "{}",
        svg.display()
    );
}

fn check(w: &Written, size: (u32, u32)) {
    check_png(&w.png, size);
    check_svg(&w.svg, size);
}

#[test]
fn every_figure_renders_on_the_tiny_scenario() {
    let dir = tempfile::tempdir().unwrap();
    let world = tiny();
    let plan = plan(&world);
    let title = "tiny: dls-smpso, seed 7";
    let size = Target::DEFAULT_SIZE;

    let top = top_view(&world, &plan, title, dir.path().join("top")).unwrap();
    check(&top, size);
    check_equal_aspect(&top.svg, &world);
    check(
        &view_3d(&world, &plan, title, dir.path().join("3d")).unwrap(),
        size,
    );
    check(
        &comm_timeline(&world, &plan, title, dir.path().join("comm")).unwrap(),
        size,
    );

    let trace: Vec<f64> = (0..41)
        .map(|k| 4000.0 * (-(k as f64) / 8.0).exp() + 900.0)
        .collect();
    let per_uav: Vec<Vec<f64>> = vec![
        trace.iter().map(|v| v * 0.45).collect(),
        trace.iter().map(|v| v * 0.55).collect(),
    ];
    check(
        &convergence_run(
            None,
            &trace,
            PerUav::Columns(&per_uav),
            title,
            dir.path().join("conv"),
        )
        .unwrap(),
        size,
    );
    // A trace that starts infeasible (infinite) and a smaller figure.
    let mut penalised = trace.clone();
    penalised[0] = f64::INFINITY;
    penalised[1] = f64::MAX;
    let small = Target::new(dir.path().join("conv_small")).with_size(800, 600);
    check(
        &convergence_run(None, &penalised, PerUav::None, title, small).unwrap(),
        (800, 600),
    );

    let recs = records();
    let conv = convergence_bench(&recs, "tiny", dir.path().join("bench_conv")).unwrap();
    check(&conv, size);
    // Over evaluations when the records carry them; over iterations for older records.
    assert!(std::fs::read_to_string(&conv.svg)
        .unwrap()
        .contains("\nevaluations\n"));
    let old: Vec<RunRecord> = recs
        .iter()
        .cloned()
        .map(|mut r| {
            r.convergence_evaluations.clear();
            r
        })
        .collect();
    let conv = convergence_bench(&old, "tiny", dir.path().join("bench_conv_old")).unwrap();
    assert!(std::fs::read_to_string(&conv.svg)
        .unwrap()
        .contains("iteration (0 = after"));
    check(
        &bench_boxplots(&recs, "tiny", dir.path().join("bench_box")).unwrap(),
        size,
    );
}

/// How many vertices each of the SVG's polylines has.
fn polyline_vertices(svg: &str) -> Vec<usize> {
    polyline_points(svg).iter().map(Vec::len).collect()
}

#[test]
fn a_long_trace_is_drawn_with_a_few_vertices_per_pixel_column() {
    let dir = tempfile::tempdir().unwrap();
    // 300,000 iterations: infeasible (infinite) at first, then a staircase with wiggles
    // per UAV, as a run under --time-limit makes.
    let n = 300_000;
    let trace: Vec<f64> = (0..n)
        .map(|k| {
            if k < 1_000 {
                f64::INFINITY
            } else {
                900.0 + 4000.0 / (1.0 + (k / 997) as f64)
            }
        })
        .collect();
    let per_uav: Vec<Vec<f64>> = (0..3)
        .map(|u| {
            trace
                .iter()
                .enumerate()
                .map(|(k, v)| v / 3.0 + ((k * (u + 3)) % 17) as f64)
                .collect()
        })
        .collect();
    let w = convergence_run(
        None,
        &trace,
        PerUav::Columns(&per_uav),
        "long",
        dir.path().join("long"),
    )
    .unwrap();
    check(&w, Target::DEFAULT_SIZE);
    let svg = std::fs::read_to_string(&w.svg).unwrap();
    let width = Target::DEFAULT_SIZE.0 as usize;
    let lines = polyline_vertices(&svg);
    // Four series; each run at most M4's four vertices per pixel column of the figure.
    let long: Vec<usize> = lines.iter().copied().filter(|&v| v > 100).collect();
    assert_eq!(long.len(), 4, "{lines:?}");
    assert!(long.iter().all(|&v| v <= 4 * width), "{long:?}");
    assert!(svg.len() < 1_000_000, "{} bytes", svg.len());
    assert_eq!(svg.matches("(final ").count(), 4);

    // An ordinary length is drawn whole: one vertex per iteration.
    let short: Vec<f64> = trace[..3_905].iter().map(|v| v.min(1e9)).collect();
    let w = convergence_run(
        None,
        &short,
        PerUav::None,
        "short",
        dir.path().join("short"),
    )
    .unwrap();
    let lines = polyline_vertices(&std::fs::read_to_string(&w.svg).unwrap());
    assert!(lines.contains(&3_905), "{lines:?}");
}

/// The polylines' vertices of an SVG, as (x, y) pixel pairs (plotters writes
/// `points="x,y x,y ..."` in whole pixels).
fn polyline_points(svg: &str) -> Vec<Vec<(i64, i64)>> {
    svg.split("<polyline")
        .skip(1)
        .filter_map(|p| {
            let start = p.find("points=\"")? + 8;
            let end = start + p[start..].find('"')?;
            Some(
                p[start..end]
                    .split_whitespace()
                    .filter_map(|xy| {
                        let (x, y) = xy.split_once(',')?;
                        Some((x.parse().ok()?, y.parse().ok()?))
                    })
                    .collect(),
            )
        })
        .collect()
}

#[test]
fn a_thinned_trace_is_drawn_at_its_iterations() {
    // A long run keeps every 4th iteration and its last (`swarmplan_core::optim::thinned`):
    // drawn at those iteration numbers, the line spans the axis of the whole run and its
    // vertices stand where the full trace's do.
    let dir = tempfile::tempdir().unwrap();
    let n = 2_001;
    let full: Vec<f64> = (0..n)
        .map(|k| 100.0 + 900.0 / (1.0 + (k / 50) as f64))
        .collect();
    let iterations: Vec<usize> = (0..n).filter(|k| k % 4 == 0 || *k == n - 1).collect();
    let thinned: Vec<f64> = iterations.iter().map(|&k| full[k]).collect();
    // One UAV's line too, from `plan`'s rows.
    let rows = |ks: &mut dyn Iterator<Item = usize>| -> Vec<std::sync::Arc<[f64]>> {
        ks.map(|k| std::sync::Arc::from(vec![full[k] / 2.0 + (k % 7) as f64]))
            .collect()
    };
    let (full_rows, thinned_rows) = (rows(&mut (0..n)), rows(&mut iterations.iter().copied()));
    let a = convergence_run(
        None,
        &full,
        PerUav::Rows(&full_rows),
        "t",
        dir.path().join("full"),
    )
    .unwrap();
    let b = convergence_run(
        Some(&iterations),
        &thinned,
        PerUav::Rows(&thinned_rows),
        "t",
        dir.path().join("thinned"),
    )
    .unwrap();
    let lines = |svg: &std::path::Path, len: usize| -> Vec<Vec<(i64, i64)>> {
        polyline_points(&std::fs::read_to_string(svg).unwrap())
            .into_iter()
            .filter(|l| l.len() == len)
            .collect()
    };
    let (a, b) = (lines(&a.svg, n), lines(&b.svg, iterations.len()));
    assert_eq!((a.len(), b.len()), (2, 2), "the UAV's line and the total");
    for (a, b) in a.iter().zip(&b) {
        assert_eq!((a.first(), a.last()), (b.first(), b.last()));
        for (k, p) in iterations.iter().zip(b) {
            assert_eq!(a[*k], *p, "iteration {k}");
        }
    }
    // Fewer iteration numbers than costs: an error, not a panic.
    let e = convergence_run(
        Some(&iterations[..10]),
        &thinned,
        PerUav::None,
        "t",
        dir.path().join("short"),
    )
    .unwrap_err();
    assert!(e.to_string().contains("iteration numbers"), "{e}");
}

#[test]
fn per_uav_rows_draw_as_the_same_columns() {
    // `plan` hands over one row per iteration, shared while the best stands; `plot` reads
    // columns from convergence.csv. Both must draw the same figure.
    let dir = tempfile::tempdir().unwrap();
    let columns: Vec<Vec<f64>> = (0..3)
        .map(|u| {
            (0..50)
                .map(|k| 1000.0 / (1.0 + (k / (u + 2)) as f64) + u as f64)
                .collect()
        })
        .collect();
    let mut rows: Vec<std::sync::Arc<[f64]>> = Vec::new();
    for k in 0..50 {
        let row: Vec<f64> = columns.iter().map(|c| c[k]).collect();
        match rows.last() {
            Some(last) if **last == *row => rows.push(last.clone()),
            _ => rows.push(row.into()),
        }
    }
    let trace: Vec<f64> = (0..50)
        .map(|k| columns.iter().map(|c| c[k]).sum())
        .collect();
    let a = convergence_run(
        None,
        &trace,
        PerUav::Columns(&columns),
        "t",
        dir.path().join("a"),
    )
    .unwrap();
    let b = convergence_run(None, &trace, PerUav::Rows(&rows), "t", dir.path().join("b")).unwrap();
    assert_eq!(
        std::fs::read(&a.svg).unwrap(),
        std::fs::read(&b.svg).unwrap()
    );
    assert_eq!(
        std::fs::read(&a.png).unwrap(),
        std::fs::read(&b.png).unwrap()
    );
}

#[test]
fn a_performance_profile_counts_the_instances_each_method_wins() {
    let dir = tempfile::tempdir().unwrap();
    let mut recs = records();
    // A second instance on which the order is reversed: PSO cheapest, DLS-SMPSO dearest.
    let second: Vec<RunRecord> = recs
        .iter()
        .cloned()
        .map(|mut r| {
            r.scenario = "tiny-2".into();
            if r.cost_per_uav.is_finite() {
                r.cost_per_uav = 5000.0 - r.cost_per_uav;
            }
            r
        })
        .collect();
    recs.extend(second);
    let w = performance_profile(&recs, dir.path().join("profile")).unwrap();
    check(&w, Target::DEFAULT_SIZE);
    let svg = std::fs::read_to_string(&w.svg).unwrap();
    assert!(svg.contains("over 2 instances"), "title");
    assert!(svg.contains("dls-smpso (best on 1 of 2)"), "legend");
    assert!(svg.contains("spso (best on 0 of 2)"), "legend");
    assert!(svg.contains("pso (best on 1 of 2)"), "legend");
    // One instance is not a profile.
    let one: Vec<RunRecord> = recs.into_iter().filter(|r| r.scenario == "tiny").collect();
    let e = performance_profile(&one, dir.path().join("one")).unwrap_err();
    assert!(matches!(e, PlotError::NoData { .. }), "{e}");
}

#[test]
fn a_straight_plan_and_nested_folders_work() {
    let dir = tempfile::tempdir().unwrap();
    let world = tiny();
    let starts: Vec<_> = (0..world.uav_count()).map(|i| world.start(i)).collect();
    let plan = Plan::straight(&starts, world.goal_at(swarmplan_core::world::DEPARTURE), 4);
    let w = top_view(&world, &plan, "straight", dir.path().join("a/b/top.v1")).unwrap();
    assert!(w.png.ends_with("top.v1.png") && w.svg.ends_with("top.v1.svg"));
    check(&w, Target::DEFAULT_SIZE);
}

#[test]
fn failures_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let recs = records();
    let e = bench_boxplots(&recs, "no-such-scenario", dir.path().join("x")).unwrap_err();
    assert!(matches!(e, PlotError::NoData { .. }));
    assert!(e.to_string().contains("x.png"), "{e}");

    let e = convergence_run(
        None,
        &[f64::INFINITY],
        PerUav::None,
        "t",
        dir.path().join("inf"),
    )
    .unwrap_err();
    assert!(e.to_string().contains("inf.png"), "{e}");

    // A file where the folder should be.
    let blocker = dir.path().join("file");
    std::fs::write(&blocker, b"not a folder").unwrap();
    let world = tiny();
    let plan = plan(&world);
    let e = top_view(&world, &plan, "t", blocker.join("top")).unwrap_err();
    assert!(matches!(e, PlotError::Folder { .. }), "{e}");
    assert!(e.to_string().contains("top.png"), "{e}");

    let e = view_3d(
        &world,
        &plan,
        "t",
        Target::new(dir.path().join("s")).with_size(50, 50),
    )
    .unwrap_err();
    assert!(matches!(e, PlotError::TooSmall { .. }), "{e}");
}

#[test]
fn a_uav_that_waits_at_its_start_is_labelled_there() {
    let dir = tempfile::tempdir().unwrap();
    let world = tiny();
    let mut p = plan(&world);
    p.delays = vec![0.0; p.uavs.len()];
    p.delays[1] = 0.2;
    let w = top_view(&world, &p, "t", dir.path().join("top")).unwrap();
    let svg = std::fs::read_to_string(&w.svg).unwrap();
    assert!(svg.contains("UAV 1 waits"), "no hover label");
    assert!(!svg.contains("UAV 0 waits"), "a UAV without delay labelled");
    let w = top_view(&world, &plan(&world), "t", dir.path().join("plain")).unwrap();
    assert!(!std::fs::read_to_string(&w.svg).unwrap().contains("waits"));
    // The 3-D view says it in its legend.
    let w = view_3d(&world, &p, "t", dir.path().join("3d")).unwrap();
    let svg = std::fs::read_to_string(&w.svg).unwrap();
    assert!(svg.contains("UAV 1 waits") && !svg.contains("UAV 0 waits"));
}

#[test]
fn an_infeasible_plan_has_its_violations_marked() {
    let dir = tempfile::tempdir().unwrap();
    let world = tiny();
    let plan = plan(&world);
    let violations = swarmplan_core::feasibility::check(&world, &plan);
    assert!(
        violations
            .iter()
            .any(|v| v.kind != swarmplan_core::feasibility::ViolationKind::Comm),
        "the golden-ratio plan should break something besides contact: {violations:?}"
    );
    for (name, w) in [
        (
            "top",
            top_view(&world, &plan, "t", dir.path().join("top")).unwrap(),
        ),
        (
            "3d",
            view_3d(&world, &plan, "t", dir.path().join("3d")).unwrap(),
        ),
    ] {
        // The signal yellow of the violation marks (style::VIOLATION) is on the picture.
        let img = image::open(&w.png).unwrap().to_rgb8();
        let yellow = img.pixels().filter(|p| p.0 == [255, 214, 0]).count();
        assert!(yellow > 50, "{name}: {yellow} violation-yellow pixels");
        let svg = std::fs::read_to_string(&w.svg).unwrap();
        assert!(
            svg.contains("violation (kind)"),
            "{name}: legend entry missing"
        );
    }
}

#[test]
fn where_no_ground_link_exists_is_hatched_when_a_uav_is_out_of_contact() {
    let dir = tempfile::tempdir().unwrap();
    // `tiny` with a fixed range and both UAVs on the straight line to UGV0.
    let world = |range: f64| {
        let mut loaded = load_spec("tiny").unwrap();
        let c = &mut loaded.spec.communication;
        c.requirement = swarmplan_core::world::spec::CommRequirement::Relay;
        c.range = range;
        c.shadowing_sigma_db = 0.0;
        build_world(&loaded, None).unwrap()
    };
    let straight = |w: &World| Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: (0..2)
            .map(|i| swarmplan_core::plan::Path {
                waypoints: vec![w.start(i), w.goal_at(swarmplan_core::world::DEPARTURE)],
            })
            .collect(),
    };
    // The stripes' colour (style::DEAD_HATCH), and the legend entry.
    let hatched = |name: &str, range: f64| {
        let w = world(range);
        let out = top_view(&w, &straight(&w), "t", dir.path().join(name)).unwrap();
        let img = image::open(&out.png).unwrap().to_rgb8();
        let stripes = img.pixels().filter(|p| p.0 == [70, 70, 80]).count();
        let svg = std::fs::read_to_string(&out.svg).unwrap();
        (stripes, svg.contains("no ground link at 80 m AGL"))
    };
    // 100 m of range: out of contact mid-way, and most of the map out of any ground link.
    let (stripes, legend) = hatched("short", 100.0);
    assert!(
        stripes > 5000 && legend,
        "{stripes} stripe pixels, legend {legend}"
    );
    // In range everywhere: nothing hatched, no legend entry.
    assert_eq!(hatched("long", 2000.0), (0, false));
}

#[test]
fn the_communication_timeline_shows_when_a_uav_waits_at_its_start() {
    let dir = tempfile::tempdir().unwrap();
    let world = tiny();
    let mut p = plan(&world);
    p.delays = vec![0.0; p.uavs.len()];
    p.delays[1] = 0.2;
    // The bar's grey (style::WAITING), and its legend entry, only with a delay.
    let waiting = |name: &str, p: &Plan| {
        let w = comm_timeline(&world, p, "t", dir.path().join(name)).unwrap();
        let img = image::open(&w.png).unwrap().to_rgb8();
        let grey = img.pixels().filter(|q| q.0 == [110, 110, 110]).count();
        let svg = std::fs::read_to_string(&w.svg).unwrap();
        (grey, svg.contains("waiting at its start"))
    };
    let (grey, legend) = waiting("delayed", &p);
    assert!(grey > 1000 && legend, "{grey} bar pixels, legend {legend}");
    // (A few pixels of that grey come from anti-aliased text.)
    let (grey, legend) = waiting("plain", &plan(&world));
    assert!(grey < 100 && !legend, "{grey} bar pixels, legend {legend}");
}
