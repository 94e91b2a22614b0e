#!/usr/bin/env python3
"""How sightline's cost grows (issue 20): CPU time against grid cells and
sensors for the S1 field, against grid cells and cooperating agents for the
roundabout at its nominal point.

Each workload is a bundled or bench scenario with one key changed; each is run
`--repeat` times and the median CPU time (user + system, every thread) printed
with the figure it should grow with, and the time per unit of that figure: a
constant column is linear growth. CPU time, not wall time: it does not depend
on the machine's other jobs as much.

    cargo build --release
    python3 bench/growth.py [--repeat 3]
"""

import argparse
import json
import statistics
import tempfile
from pathlib import Path

from targets import ROOT, SIGHTLINE, measure, roundabout_one_point


def cpu(scenario, folder, times):
    """The median CPU seconds of `sightline run scenario`, and its results.json."""
    out = folder / "out"
    runs = [measure([str(SIGHTLINE), "run", str(scenario), "--out", str(out)], ROOT)[1] for _ in range(times)]
    return statistics.median(runs), (out / "results.json").read_text()


def variant(text, folder, name, replacements):
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    path = folder / f"{name}.yaml"
    path.write_text(text)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        s1 = (ROOT / "bench" / "s1-one-gamma.yaml").read_text()
        print("S1 at one γ, Baseline + Proposed (bench/s1-one-gamma.yaml):\n")
        print("| cells | sensors | sources (cells × mean coverage) | CPU | ns per source |")
        print("|---:|---:|---:|---:|---:|")
        for cell, layout in [(1.0, 4), (0.5, 4), (0.25, 4), (0.5, 2), (0.5, 8)]:
            scenario = variant(s1, folder, "s1", [
                ("cell: 0.5 }", f"cell: {cell} }}"),
                ("rows: 4, cols: 4", f"rows: {layout}, cols: {layout}"),
            ])
            seconds, results = cpu(scenario, folder, args.repeat)
            cells = round(500 / cell) ** 2
            coverage = json.loads(results)["sweep"][0]["coverage"]["mean_sources"]
            sources = cells * coverage
            print(f"| {cells:,} | {layout * layout} | {sources / 1e6:.2f} M | {seconds:.3f} s | {seconds / sources * 1e9:.0f} |")

        rb = roundabout_one_point(folder).read_text()
        print("\nThe roundabout, one point, 30 s (scenarios/roundabout-six-agents.yaml without its sweeps):\n")
        print("| cells | cooperating vehicles | CPU | ms per simulated second |")
        print("|---:|---:|---:|---:|")
        for cell, penetration, cooperating in [(1.0, 1, 6), (0.5, 1, 6), (0.25, 1, 6), (0.5, 0, 1), (0.5, 0.4, 3)]:
            scenario = variant(rb, folder, "rb", [
                ("cell: 0.5 }", f"cell: {cell} }}"),
                ("penetration: 1 ", f"penetration: {penetration} "),
            ])
            seconds, _ = cpu(scenario, folder, args.repeat)
            cells = round(300 / cell) ** 2
            print(f"| {cells:,} | {cooperating} | {seconds:.3f} s | {seconds / 30 * 1000:.0f} |")


if __name__ == "__main__":
    main()
