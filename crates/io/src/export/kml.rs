//! One KML 2.2 document for the fleet: a LineString per UAV (the path as flown: arcs of the
//! turning radius through the corners) with `altitudeMode` absolute
//! (KML's name for altitude above sea level), a Point for each start and for the goal, and
//! a Polygon per threat, extruded from the ground to its drawn height (`relativeToGround`).
//! Text is escaped for XML; the document's description states the altitude reference.

use std::fmt::Write as _;

use super::{num, Mission, ALTITUDE_REFERENCE};
use crate::geo::Geodetic;

/// Escapes the five XML special characters.
pub(crate) fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            c if c.is_control() && c != '\n' && c != '\t' => s.push(' '),
            c => s.push(c),
        }
    }
    s
}

fn coord(g: &Geodetic, alt: f64) -> String {
    format!("{},{},{}", num(g.lon_deg), num(g.lat_deg), num(alt))
}

/// KML colours (aabbggrr) of the first six UAVs.
const FIRST_COLOURS: [&str; 6] = [
    "ff0000ff", "ff00a5ff", "ff00ff00", "ffff0000", "ffff00ff", "ffffff00",
];

/// UAV `k`'s line colour: the six above, then hues a golden angle apart, so every UAV of a
/// large fleet has its own (UAV 6 used to repeat UAV 0's).
fn uav_colour(k: usize) -> String {
    if let Some(c) = FIRST_COLOURS.get(k) {
        return (*c).to_string();
    }
    let hue = (k as f64 * 0.618_033_988_749_895).fract() * 6.0;
    let x = 1.0 - (hue % 2.0 - 1.0).abs();
    let (r, g, b) = match hue as u8 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    // Truncation intended: channels in [0, 1] to bytes.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = |v: f64| (v * 255.0).round() as u8;
    format!("ff{:02x}{:02x}{:02x}", byte(b), byte(g), byte(r))
}

/// The KML text of a mission.
pub(crate) fn kml(m: &Mission) -> String {
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(s, r#"<kml xmlns="http://www.opengis.net/kml/2.2">"#);
    let _ = writeln!(s, "<Document>");
    let _ = writeln!(
        s,
        "<name>{}</name>",
        escape(&format!("swarmplan {}", m.scenario))
    );
    let _ = writeln!(s, "<description>{}</description>", escape(&m.header()));
    for p in &m.paths {
        let (k, c) = (p.uav, uav_colour(p.uav));
        let _ = writeln!(
            s,
            "<Style id=\"uav{k}\"><LineStyle><color>{c}</color><width>3</width></LineStyle></Style>"
        );
    }
    let _ = writeln!(
        s,
        "<Style id=\"threat\"><LineStyle><color>ff0000ff</color></LineStyle>\
         <PolyStyle><color>550000ff</color></PolyStyle></Style>"
    );
    for p in &m.paths {
        // The line is the path as flown and assessed (arcs through the corners).
        let coords: Vec<String> = p
            .flown
            .iter()
            .map(|pt| coord(&pt.geo, pt.geo.alt_m))
            .collect();
        let _ = writeln!(s, "<Placemark>");
        let _ = writeln!(s, "<name>uav {}</name>", p.uav);
        let _ = writeln!(
            s,
            "<description>{}</description>",
            escape(&format!(
                "flown path (turning radius {} m), speed {} m/s, length {:.1} m, arrival {:.1} s; {ALTITUDE_REFERENCE}",
                p.turn_radius_m,
                p.speed_mps,
                p.length_m,
                p.points[p.points.len() - 1].time_s
            ))
        );
        let _ = writeln!(s, "<styleUrl>#uav{}</styleUrl>", p.uav);
        let _ = writeln!(
            s,
            "<LineString><altitudeMode>absolute</altitudeMode><coordinates>{}</coordinates></LineString>",
            coords.join(" ")
        );
        let _ = writeln!(s, "</Placemark>");
        let st = &p.points[0];
        let _ = writeln!(
            s,
            "<Placemark><name>start uav {}</name><Point><altitudeMode>absolute</altitudeMode>\
             <coordinates>{}</coordinates></Point></Placemark>",
            p.uav,
            coord(&st.geo, st.geo.alt_m)
        );
    }
    let _ = writeln!(
        s,
        "<Placemark><name>goal (UGV0)</name><Point><altitudeMode>absolute</altitudeMode>\
         <coordinates>{}</coordinates></Point></Placemark>",
        coord(&m.goal, m.goal.alt_m)
    );
    for t in &m.threats {
        let ring: Vec<String> = t.ring.iter().map(|g| coord(g, t.draw_height_m)).collect();
        let _ = writeln!(s, "<Placemark>");
        let _ = writeln!(s, "<name>threat {}</name>", t.index);
        let _ = writeln!(
            s,
            "<description>{}</description>",
            escape(&format!(
                "vertical cylinder of radius {} m at local ({}, {}), unbounded in height; drawn \
                 from the ground to {} m above ground",
                t.r, t.x, t.y, t.draw_height_m
            ))
        );
        let _ = writeln!(s, "<styleUrl>#threat</styleUrl>");
        let _ = writeln!(
            s,
            "<Polygon><extrude>1</extrude><altitudeMode>relativeToGround</altitudeMode>\
             <outerBoundaryIs><LinearRing><coordinates>{}</coordinates></LinearRing>\
             </outerBoundaryIs></Polygon>",
            ring.join(" ")
        );
        let _ = writeln!(s, "</Placemark>");
    }
    let _ = writeln!(s, "</Document>");
    let _ = writeln!(s, "</kml>");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xml_text_is_escaped() {
        assert_eq!(
            escape(r#"a<b>&"c"'d'"#),
            "a&lt;b&gt;&amp;&quot;c&quot;&apos;d&apos;"
        );
        assert_eq!(escape("x\u{7}y"), "x y");
    }

    #[test]
    fn each_uav_of_a_large_fleet_has_its_own_colour() {
        let colours: Vec<String> = (0..100).map(uav_colour).collect();
        assert_eq!(colours[0], "ff0000ff");
        assert!(colours
            .iter()
            .all(|c| c.len() == 8 && c.bytes().all(|b| b.is_ascii_hexdigit())));
        for k in 0..12 {
            for j in 0..k {
                assert_ne!(colours[j], colours[k], "UAVs {j} and {k}");
            }
        }
    }
}
