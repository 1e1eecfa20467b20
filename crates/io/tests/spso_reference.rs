//! Cross-check against the SPSO reference code: every vector of
//! `shared/data/spso/cost-vectors.json` (computed by SPSO's own `SphericalToCart` and
//! `MyCost` in GNU Octave on its DEM) is decoded with the spherical encoding in SPSO's
//! convention and costed with the `spso-mycost` objective preset; waypoints and each term must match to 1e-9
//! relative, `Inf` where the reference says `Inf`. Skipped, saying so, when the files are
//! absent (they live in the CI's `shared/` folder, not in the repository).

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_core::cost::assess_as_searched;
use swarmplan_core::cost::TermId;
use swarmplan_core::encoding::{build, EncodingKind};
use swarmplan_io::reference_data::reference_files;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

fn num(v: &serde_json::Value) -> f64 {
    let s = v
        .as_str()
        .expect("numbers are strings in cost-vectors.json");
    match s {
        "Inf" => f64::INFINITY,
        "-Inf" => f64::NEG_INFINITY,
        _ => s.parse().expect("a number"),
    }
}

fn nums(v: &serde_json::Value) -> Vec<f64> {
    v.as_array().expect("an array").iter().map(num).collect()
}

fn close(got: f64, want: f64, what: &str) {
    if want.is_infinite() {
        assert_eq!(got, want, "{what}: got {got}, want {want}");
    } else {
        let tol = 1e-9 * want.abs().max(1.0);
        assert!(
            (got - want).abs() <= tol,
            "{what}: got {got:.17}, want {want:.17}"
        );
    }
}

#[test]
fn matches_spso_mycost_on_every_reference_vector() {
    let Some(files) =
        reference_files(&["spso/ChrismasTerrain.tif", "spso/cost-vectors.json"]).unwrap()
    else {
        return;
    };
    let (tif, vectors) = (files[0].clone(), files[1].clone());
    let data: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(&vectors).unwrap()).unwrap();
    assert_eq!(data.len(), 40);
    let mut worlds = std::collections::HashMap::new();
    let mut infinite = 0;
    for (idx, v) in data.iter().enumerate() {
        let case = v["case"].as_str().unwrap();
        let world = worlds.entry(case.to_string()).or_insert_with(|| {
            let loaded = load_spec(&format!("spso-{case}")).unwrap();
            build_world(&loaded, Some(&tif)).unwrap()
        });
        let enc = build(EncodingKind::Spherical, world);
        let x: Vec<f64> = [nums(&v["r"]), nums(&v["psi"]), nums(&v["phi"])].concat();
        let plan = enc.decode(&x);
        let w = &plan.uavs[0].waypoints;
        for (k, ((xr, yr), zr)) in nums(&v["x"])
            .iter()
            .zip(nums(&v["y"]))
            .zip(nums(&v["z"]))
            .enumerate()
        {
            close(w[k + 1].x, *xr, &format!("vector {idx} node {k} x"));
            close(w[k + 1].y, yr, &format!("vector {idx} node {k} y"));
            close(w[k + 1].z, zr, &format!("vector {idx} node {k} z"));
        }
        let a = assess_as_searched(world, &plan);
        let t = a.per_uav[0].raw;
        close(
            t[TermId::Length],
            num(&v["J1_length"]),
            &format!("vector {idx} J1"),
        );
        close(
            t[TermId::Threat],
            num(&v["J2_threat"]),
            &format!("vector {idx} J2"),
        );
        close(
            t[TermId::Altitude],
            num(&v["J3_altitude"]),
            &format!("vector {idx} J3"),
        );
        close(
            t[TermId::Smoothness],
            num(&v["J4_smoothness"]),
            &format!("vector {idx} J4"),
        );
        close(a.total, num(&v["cost"]), &format!("vector {idx} cost"));
        if a.total.is_infinite() {
            infinite += 1;
        }
    }
    // Both kinds are present: the random vectors collide, the near-best ones do not.
    assert!(infinite > 0 && infinite < data.len(), "{infinite} infinite");
}
