#!/usr/bin/env python3
"""Python side of crates/io/tests/export.rs: reads swarmplan's mission exports with
independent libraries.

Usage: python3 export_check.py DIR

DIR holds the exports and expected.json, written by the Rust test:
  {"wpl": [{"file": "uav0.waypoints",
            "items": [[command, frame, lat, lon, alt], ...]}, ...],
   "geojson": {"file": "mission.geojson", "features": N}}

Checks:
- pymavlink's waypoint loader (mavwp.MAVWPLoader().load) reads every WPL file and finds the
  expected number of items, with the expected commands and frames, latitudes and longitudes
  within 1e-7 degrees and altitudes within 1e-6 m;
- the GeoJSON validates with the `geojson` package (is_valid, no errors()) and has the
  expected number of features, every position [lon, lat, alt] in range.

Exit status: 0 passed, 1 failed, 3 skipped (pymavlink or geojson not importable; the
message says which and why).
"""

import json
import math
import os
import sys

SKIPPED = 3
DEG_TOL = 1e-7
ALT_TOL = 1e-6


def check_wpl(directory, spec, mavwp):
    path = os.path.join(directory, spec["file"])
    loader = mavwp.MAVWPLoader()
    count = loader.load(path)
    expected = spec["items"]
    if count != len(expected):
        return [f"{spec['file']}: pymavlink read {count} items, expected {len(expected)}"]
    errors = []
    for k, (w, item) in enumerate(zip(loader.wpoints, expected)):
        command, frame, lat, lon, alt = item[:5]
        acceptance = item[5] if len(item) > 5 else None
        where = f"{spec['file']} item {k}"
        if w.command != command or w.frame != frame:
            errors.append(
                f"{where}: command {w.command} frame {w.frame}, expected {command} {frame}"
            )
        if abs(w.x - lat) > DEG_TOL or abs(w.y - lon) > DEG_TOL:
            errors.append(f"{where}: lat/lon {w.x}, {w.y}, expected {lat}, {lon}")
        if abs(w.z - alt) > ALT_TOL:
            errors.append(f"{where}: altitude {w.z}, expected {alt}")
        if acceptance is not None and abs(w.param2 - acceptance) > ALT_TOL:
            errors.append(f"{where}: acceptance radius {w.param2}, expected {acceptance}")
    return errors


def positions(geometry):
    kind = geometry["type"]
    c = geometry["coordinates"]
    if kind == "Point":
        return [c]
    if kind == "LineString":
        return c
    if kind == "Polygon":
        return [p for ring in c for p in ring]
    return []


def check_geojson(directory, spec, geojson):
    path = os.path.join(directory, spec["file"])
    with open(path, encoding="utf-8") as f:
        text = f.read()
    obj = geojson.loads(text)
    errors = []
    if not obj.is_valid:
        errors.append(f"{spec['file']}: geojson says invalid: {obj.errors()}")
    if obj.errors():
        errors.append(f"{spec['file']}: geojson errors: {obj.errors()}")
    if obj.get("type") != "FeatureCollection":
        errors.append(f"{spec['file']}: type {obj.get('type')}, expected FeatureCollection")
    raw = json.loads(text)  # full precision (geojson rounds coordinates)
    features = raw.get("features", [])
    if len(features) != spec["features"]:
        errors.append(f"{spec['file']}: {len(features)} features, expected {spec['features']}")
    for k, feat in enumerate(features):
        for p in positions(feat["geometry"]):
            lon, lat = p[0], p[1]
            if not (-180 <= lon <= 180 and -90 <= lat <= 90) or not all(
                math.isfinite(v) for v in p
            ):
                errors.append(f"{spec['file']} feature {k}: position {p} out of range")
        geom = geojson.GeoJSON.to_instance(feat["geometry"])
        if not geom.is_valid:
            errors.append(f"{spec['file']} feature {k}: {geom.errors()}")
    return errors


def main(argv):
    if len(argv) != 2:
        print(__doc__)
        return 1
    directory = argv[1]
    with open(os.path.join(directory, "expected.json"), encoding="utf-8") as f:
        expected = json.load(f)
    try:
        from pymavlink import mavwp
    except Exception as e:  # ImportError, or a broken install
        print(f"skipped: pymavlink is not importable ({e!r}); pip install pymavlink")
        return SKIPPED
    try:
        import geojson
    except Exception as e:
        print(f"skipped: geojson is not importable ({e!r}); pip install geojson")
        return SKIPPED
    errors = []
    for spec in expected["wpl"]:
        errors += check_wpl(directory, spec, mavwp)
    errors += check_geojson(directory, expected["geojson"], geojson)
    if errors:
        for e in errors:
            print("FAIL:", e)
        return 1
    n = sum(len(s["items"]) for s in expected["wpl"])
    print(
        f"ok: pymavlink read {len(expected['wpl'])} WPL files ({n} items) within "
        f"{DEG_TOL} deg; geojson {geojson.__version__} validated "
        f"{expected['geojson']['features']} features"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
