"""Make more instances from the outside generator, in the shared folder's format.

Why: the 22 development instances of ../shared/data/outside are too few to tell a planner
that generalises from one tuned to them (docs/results.md, "Fresh instances"). This draws
further instances from the same generator, the instance generator of Shehadeh & Kudela's
UAV path-planning benchmark (arXiv 2501.14503) as packaged in MetaBox v2, exactly as the
shared folder's README says its instances were made: ``createmodel`` on a 900 x 900 map,
the roughness drawn as the dataset code draws it (r in [-200, 400], rr in [100, 900]), the
first half with 15 threats and the second with 30, from ``numpy.random.RandomState(STATE)``.
With ``--state 11 --count 24`` it writes outside-4..27 of the shared folder again, byte for
byte in the JSON and to the hundredth of a metre in the terrain (checked by
``--check-shared``).

The generator is optional tooling, not a dependency of swarmplan:

    python3 -m pip install --no-deps metaevobox==2.0.2 && python3 -m pip install numpy scipy
    python3 python/examples/outside_instances.py --state 13 --out /tmp/fresh13
    SWARMPLAN_SHARED=/tmp/fresh13 swarmplan bench --suite outside --methods swarmplan --runs 3

The folder gets ``data/outside/outside-K.json`` and ``outside-K.asc.gz`` for K = 0..count-1
and a README saying how they were made, so that ``outside-K`` (and every suite of them)
names these instances while ``SWARMPLAN_SHARED`` points there. Only the package's own module
``metaevobox/environment/problem/SOO/UAV/utils.py`` is loaded (by path: the package's
``__init__`` imports torch, which the generator does not need).
"""

import argparse
import gzip
import importlib.util
import json
import pathlib
import sys

import numpy as np

MAP_SIZE = 900


def load_generator():
    """The generator module of metaevobox 2.0.2, loaded without the package's __init__."""
    spec = importlib.util.find_spec("metaevobox")
    if spec is None or not spec.submodule_search_locations:
        sys.exit(
            "metaevobox is not installed: python3 -m pip install --no-deps metaevobox==2.0.2 "
            "(and numpy, scipy)"
        )
    root = pathlib.Path(list(spec.submodule_search_locations)[0])
    path = root / "environment" / "problem" / "SOO" / "UAV" / "utils.py"
    module_spec = importlib.util.spec_from_file_location("metaevobox_uav_utils", path)
    module = importlib.util.module_from_spec(module_spec)
    module_spec.loader.exec_module(module)
    return module


def draw(generator, state, count):
    """The instances of one random state, in the dataset code's order."""
    rng = np.random.RandomState(state)
    for index in range(count):
        threats = 15 if index < 0.5 * count else 30
        yield generator.createmodel(
            map_size=MAP_SIZE,
            r=rng.rand() * 600 - 200,
            rr=rng.rand() * 800 + 100,
            num_threats=threats,
            rng=rng,
        )


def instance_json(model):
    return {
        "threats_x_y_height_r": [[float(v) for v in row] for row in model["threats"]],
        "start": [float(v) for v in model["start"].ravel()],
        "goal": [float(v) for v in model["end"].ravel()],
        "map": [int(model["MAPSIZE_X"]), int(model["MAPSIZE_Y"])],
    }


def terrain_rows(model):
    """ESRI ASCII rows: file row k holds y = k + 1 (the `spso-pixels` frame), negatives 0."""
    heights = np.maximum(model["H"], 0.0)
    for row in heights:
        yield " ".join(f"{h:.2f}" for h in row)


def write(model, folder, name):
    (folder / f"{name}.json").write_text(json.dumps(instance_json(model), indent=1) + "\n")
    ny, nx = model["H"].shape
    header = f"ncols {nx}\nnrows {ny}\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n"
    with gzip.open(folder / f"{name}.asc.gz", "wt") as out:
        out.write(header)
        for row in terrain_rows(model):
            out.write(row + "\n")


def check_shared(generator, shared):
    """outside-4..27 of the shared folder are RandomState 11's 24 instances."""
    worst = 0.0
    for k, model in enumerate(draw(generator, 11, 24), start=4):
        name = f"outside-{k}"
        stored = json.loads((shared / f"{name}.json").read_text())
        if stored != instance_json(model):
            sys.exit(f"{name}: threats, start or goal differ from RandomState 11's draw")
        with gzip.open(shared / f"{name}.asc.gz", "rt") as f:
            grid = np.loadtxt(f, skiprows=6)
        worst = max(worst, float(np.abs(grid - np.maximum(model["H"], 0.0)).max()))
        print(f"{name}: same instance (terrain within {worst:.3f} m so far)", flush=True)
    if worst > 0.005 + 1e-9:
        sys.exit(f"terrain differs by up to {worst} m")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--state", type=int, default=13, help="numpy RandomState (default 13)")
    parser.add_argument("--count", type=int, default=28, help="instances (default 28)")
    parser.add_argument("--out", type=pathlib.Path, help="folder to write (data/outside inside)")
    parser.add_argument(
        "--check-shared",
        type=pathlib.Path,
        help="instead, check that this folder's outside-4..27 are RandomState 11's draw",
    )
    args = parser.parse_args()
    if args.check_shared is None and args.out is None:
        parser.error("--out is required (or --check-shared)")
    if args.count < 1:
        parser.error("--count must be at least 1")
    generator = load_generator()
    if args.check_shared:
        check_shared(generator, args.check_shared)
        return
    folder = args.out / "data" / "outside"
    folder.mkdir(parents=True, exist_ok=True)
    for k, model in enumerate(draw(generator, args.state, args.count)):
        write(model, folder, f"outside-{k}")
        print(f"wrote {folder}/outside-{k}.json and .asc.gz", flush=True)
    half = (args.count + 1) // 2
    (folder / "README.md").write_text(
        f"# Outside instances, RandomState {args.state}\n\n"
        f"Made by python/examples/outside_instances.py --state {args.state} --count "
        f"{args.count}: metaevobox 2.0.2 `createmodel`, 900 x 900 map, roughness drawn as "
        f"the dataset code draws it; outside-0..{half - 1} with 15 threats, the rest with "
        "30. Terrain heights below zero set to 0, rows as the shared folder's README says.\n"
    )


if __name__ == "__main__":
    main()
