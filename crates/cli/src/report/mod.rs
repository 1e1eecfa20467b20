//! `swarmplan report DIR`: one self-contained HTML file (no network: styles, script, data and
//! figures are inlined) with an interactive 3-D view of the plan, the cost breakdown, the
//! violations, the figures of the folder, and for a bench the summary tables.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use serde_json::json;
use swarmplan_core::cost::Assessment;
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;

const VIEWER_JS: &str = include_str!("viewer.js");
const STYLE_CSS: &str = include_str!("style.css");

/// Escapes text for HTML.
#[must_use]
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The JSON scene the viewer draws: a coarse terrain mesh over the map box, threats, ground
/// nodes and the paths with absolute altitudes.
#[must_use]
pub fn scene(world: &World, plan: &Plan) -> serde_json::Value {
    let m = &world.spec().map;
    let (nx, ny) = (64usize, 56usize);
    let (dx, dy) = (
        (m.x[1] - m.x[0]) / (nx - 1) as f64,
        (m.y[1] - m.y[0]) / (ny - 1) as f64,
    );
    let mut z = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            z.push(
                world
                    .terrain()
                    .height(m.x[0] + i as f64 * dx, m.y[0] + j as f64 * dy),
            );
        }
    }
    let (min, max) = z
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    // The line is what is flown (arcs through the corners under the strict profile); the
    // markers are the waypoints.
    let timed = TimedPlan::new(world, plan);
    let flown = TimedPlan::flown(world, plan);
    let paths: Vec<_> = timed
        .paths
        .iter()
        .zip(&flown.paths)
        .enumerate()
        .map(|(i, (p, f))| {
            json!({
                "name": format!("UAV {i}"),
                "color": swarmplan_plot::uav_colour_hex(i),
                "points": f.abs.iter().map(|a| [a.x, a.y, a.z]).collect::<Vec<_>>(),
                "waypoints": p.abs.iter().map(|a| [a.x, a.y, a.z]).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "box": {"x": m.x, "y": m.y},
        "terrain": {"nx": nx, "ny": ny, "x0": m.x[0], "y0": m.y[0], "dx": dx, "dy": dy, "z": z, "min": min, "max": max},
        "threats": world.spec().threats.iter().map(|t| json!({
            "x": t.x, "y": t.y, "r": t.r, "z": t.z, "ground": world.terrain().height(t.x, t.y),
        })).collect::<Vec<_>>(),
        "ground": world.ground_nodes_at(swarmplan_core::world::DEPARTURE).iter().map(|g| json!({
            "name": g.name, "x": g.position.x, "y": g.position.y, "z": g.position.z,
        })).collect::<Vec<_>>(),
        "paths": paths,
    })
}

/// Page head, styles and title.
fn head(title: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>\n{STYLE_CSS}</style>\n</head>\n<body>\n<h1>{}</h1>\n",
        escape(title),
        escape(title)
    )
}

/// The 3-D view block (canvas, toggles, data and script).
fn viewer(scene: &serde_json::Value) -> String {
    // `</` cannot close the script element early once escaped.
    let data = scene.to_string().replace("</", "<\\/");
    format!(
        "<section>\n<h2>3-D view</h2>\n<p class=\"hint\">Drag to rotate, scroll to zoom.</p>\n<div id=\"uav-toggles\"></div>\n<label>vertical exaggeration <input id=\"z-exaggeration\" type=\"range\" min=\"1\" max=\"5\" step=\"0.5\" value=\"1\"></label>\n<canvas id=\"view3d\" width=\"960\" height=\"640\"></canvas>\n<script id=\"scene\" type=\"application/json\">{data}</script>\n<script>\n{VIEWER_JS}</script>\n</section>\n"
    )
}

/// Inlines every SVG figure of `dir` (sorted by name).
fn figures(dir: &Path) -> Result<String> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .with_context(|| format!("{}: cannot list", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "svg"))
        .collect();
    names.sort();
    if names.is_empty() {
        return Ok(String::new());
    }
    let mut s = String::from("<section>\n<h2>Figures</h2>\n");
    for p in names {
        let svg =
            std::fs::read_to_string(&p).with_context(|| format!("{}: cannot read", p.display()))?;
        let body = svg.find("<svg").map_or(svg.as_str(), |i| &svg[i..]);
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "<figure>{body}<figcaption>{}</figcaption></figure>",
            escape(&name)
        );
    }
    s.push_str("</section>\n");
    Ok(s)
}

/// Per-UAV table, cost breakdown and violations.
fn assessment_tables(a: &Assessment) -> String {
    let mut s = String::from("<section>\n<h2>Per UAV</h2>\n<table>\n<tr><th>UAV</th><th>length m</th><th>speed m/s</th><th>arrival s</th><th>energy J</th><th>battery</th><th>min clearance m</th><th>out of contact s</th><th>cost</th></tr>\n");
    for (i, u) in a.per_uav.iter().enumerate() {
        let _ = writeln!(
            s,
            "<tr><td>{i}</td><td>{:.1}</td><td>{:.2}</td><td>{:.1}</td><td>{:.0}</td><td>{:.0}%</td><td>{:.1}</td><td>{:.0}</td><td>{:.1}</td></tr>",
            u.length_m, u.speed_mps, u.arrival_s, u.energy_j, 100.0 * u.battery_ratio, u.min_clearance_m, u.outage_s, u.cost
        );
    }
    s.push_str("</table>\n<h2>Cost breakdown</h2>\n<table>\n<tr><th>term</th><th>weighted, all UAVs</th></tr>\n");
    for (term, v) in a.term_totals().iter() {
        let _ = writeln!(s, "<tr><td>{}</td><td>{v:.2}</td></tr>", term.name());
    }
    let _ = writeln!(
        s,
        "<tr><td>penalty</td><td>{:.2}</td></tr>\n<tr><th>total</th><th>{:.2}</th></tr>\n<tr><th>per UAV</th><th>{:.2}</th></tr>\n</table>",
        a.penalty,
        a.total,
        a.per_uav_cost()
    );
    let v = a.violations.as_deref().unwrap_or_default();
    if v.is_empty() {
        s.push_str(
            "<h2>Feasibility</h2>\n<p class=\"ok\">Feasible: no constraint is violated.</p>\n",
        );
    } else {
        let _ = writeln!(s, "<h2>Feasibility</h2>\n<p class=\"bad\">Infeasible: {} violations.</p>\n<table>\n<tr><th>kind</th><th>UAV</th><th>time s</th><th>amount</th><th>detail</th></tr>", v.len());
        for x in v {
            let _ = writeln!(
                s,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.2}</td><td>{}</td></tr>",
                x.kind.name(),
                x.uav,
                x.time.map_or(String::from("-"), |t| format!("{t:.1}")),
                x.amount,
                escape(&x.detail)
            );
        }
        s.push_str("</table>\n");
    }
    s.push_str("</section>\n");
    s
}

/// Turns the Markdown of `summary.md` (headings, paragraphs, pipe tables) into HTML.
#[must_use]
pub fn markdown_to_html(md: &str) -> String {
    let mut out = String::new();
    let mut in_table = false;
    for line in md.lines() {
        let l = line.trim();
        if l.starts_with('|') {
            let cells: Vec<&str> = l.trim_matches('|').split('|').map(str::trim).collect();
            if cells
                .iter()
                .all(|c| c.chars().all(|ch| ch == '-' || ch == ':') && !c.is_empty())
            {
                continue;
            }
            let tag = if in_table { "td" } else { "th" };
            if !in_table {
                out.push_str("<table>\n");
                in_table = true;
            }
            out.push_str("<tr>");
            for c in cells {
                let _ = write!(out, "<{tag}>{}</{tag}>", escape(c).replace('`', ""));
            }
            out.push_str("</tr>\n");
            continue;
        }
        if in_table {
            out.push_str("</table>\n");
            in_table = false;
        }
        if let Some(h) = l.strip_prefix("## ") {
            let _ = writeln!(out, "<h2>{}</h2>", escape(h).replace('`', ""));
        } else if let Some(h) = l.strip_prefix("# ") {
            let _ = writeln!(out, "<h2>{}</h2>", escape(h));
        } else if !l.is_empty() {
            let _ = writeln!(out, "<p>{}</p>", escape(l).replace('`', ""));
        }
    }
    if in_table {
        out.push_str("</table>\n");
    }
    out
}

/// The report of a `plan` folder.
pub fn plan_report(
    dir: &Path,
    world: &World,
    plan: &Plan,
    a: &Assessment,
    subtitle: &str,
) -> Result<String> {
    let mut html = head(&format!("swarmplan: {}", world.spec().name));
    let _ = writeln!(html, "<p class=\"sub\">{}</p>", escape(subtitle));
    html.push_str(&viewer(&scene(world, plan)));
    html.push_str(&assessment_tables(a));
    html.push_str(&figures(dir)?);
    html.push_str("</body>\n</html>\n");
    Ok(html)
}

/// The report of a `bench` folder.
pub fn bench_report(dir: &Path, summary_md: &str) -> Result<String> {
    let mut html = head("swarmplan: experiment");
    html.push_str("<section>\n");
    html.push_str(&markdown_to_html(summary_md));
    html.push_str("</section>\n");
    html.push_str(&figures(dir)?);
    html.push_str("</body>\n</html>\n");
    Ok(html)
}
