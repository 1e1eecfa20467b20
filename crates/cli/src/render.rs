//! Human-readable tables of an assessment (per-UAV figures, cost breakdown, violations).

use std::fmt::Write;

use swarmplan_core::cost::Assessment;
use swarmplan_core::world::World;

/// Per-UAV table, term breakdown, feasibility and violations.
#[must_use]
pub fn assessment(world: &World, a: &Assessment) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "scenario {}: {} UAVs", world.spec.name, a.per_uav.len());
    let _ = writeln!(
        s,
        "{:>4} {:>9} {:>8} {:>9} {:>9} {:>8} {:>10} {:>8} {:>10}",
        "uav",
        "length m",
        "speed",
        "arrive s",
        "energy J",
        "battery",
        "clear m",
        "outage s",
        "cost"
    );
    for (i, u) in a.per_uav.iter().enumerate() {
        let _ = writeln!(
            s,
            "{:>4} {:>9.1} {:>8.2} {:>9.1} {:>9.0} {:>7.0}% {:>10.1} {:>8.0} {:>10.1}",
            i,
            u.length_m,
            u.speed_mps,
            u.arrival_s,
            u.energy_j,
            100.0 * u.battery_ratio,
            u.min_clearance_m,
            u.outage_s,
            u.cost
        );
    }
    let _ = writeln!(s, "\ncost breakdown (weighted, all UAVs):");
    let t = a.term_totals();
    for (term, v) in t.iter() {
        let _ = writeln!(s, "  {:<14} {v:>12.2}", term.name());
    }
    let _ = writeln!(s, "  {:<14} {:>12.2}", "penalty", a.penalty);
    let _ = writeln!(s, "  {:<14} {:>12.2}", "total", a.total);
    let _ = writeln!(s, "  {:<14} {:>12.2}", "per UAV", a.per_uav_cost());
    let v = a.violations.as_deref().unwrap_or_default();
    let hard = v.iter().filter(|x| x.hard).count();
    let soft = v.len() - hard;
    let soft_note = if soft > 0 {
        format!("; {soft} soft, in the cost only (profile {})", a.profile)
    } else {
        String::new()
    };
    if hard == 0 {
        let _ = writeln!(s, "\nfeasible: yes{soft_note}");
    } else {
        let _ = writeln!(s, "\nfeasible: no ({hard} violations{soft_note})");
    }
    for x in v {
        let when = x.time.map(|t| format!(" t={t:.1}s")).unwrap_or_default();
        let _ = writeln!(
            s,
            "  {:<10} uav {}{}: {}{}",
            x.kind.name(),
            x.uav,
            when,
            x.detail,
            if x.hard { "" } else { " (soft)" }
        );
    }
    s
}
