#!/usr/bin/env python3
"""Issue 20's whole-process targets, measured side by side in one run.

Runs each workload `--repeat` times (the release build of sightline, and the
numpy reference of S1 where there is one) and prints a Markdown table of the
median wall time, CPU time (user + system, all threads) and peak resident
memory, with the machine's load average before and after: wall times taken
while other jobs load the machine measure the machine, not the program (CPU
time is steadier). Results go to stdout; the programs' own output to a
temporary folder.

    cargo build --release
    python3 -m venv target/bench-python && target/bench-python/bin/pip install -r bench/requirements.txt
    python3 bench/targets.py [--repeat 5] [--only s1,table,roundabout,urban,falsify]

(numpy runs in target/bench-python when it exists, else in this Python.)

The targets (docs/performance.md): S1 one gamma <= 0.12 s wall on 2 cores, the
5-gamma table <= 0.5 s, CPU <= 1/4 of numpy's, <= 50 MB; the roundabout >= 100x
real time per point; the urban junction >= 1000x real time per run; falsify >=
50 evaluations per second.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SIGHTLINE = ROOT / "target" / "release" / "sightline"
NUMPY = Path(__file__).resolve().parent / "numpy_s1.py"


def measure(command, cwd):
    """Runs `command`; returns (wall s, CPU s, peak KB, stdout)."""
    start = time.perf_counter()
    process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    stdout = process.stdout.read()
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - start
    code = os.waitstatus_to_exitcode(status)
    if code not in (0, 1):
        sys.exit(f"{' '.join(map(str, command))} exited {code}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss, stdout


def repeat(command, cwd, times):
    """Runs `command` `times` times: (median wall s, median CPU s, largest peak KB, last stdout)."""
    runs = [measure(command, cwd) for _ in range(times)]
    median = lambda i: statistics.median(r[i] for r in runs)
    return median(0), median(1), max(r[2] for r in runs), runs[-1][3]


def roundabout_one_point(folder):
    """The bundled roundabout at its nominal point (six cooperating vehicles,
    the modelled radio), without its sweeps: cut from the bundled file so it
    cannot drift from it."""
    text = (ROOT / "scenarios" / "roundabout-six-agents.yaml").read_text()
    text = text[: text.index("\nsweeps:")] + (
        "\nrequirements:\n  - id: RB-MASS-01\n    text: Every fused cell holds a valid probability.\n"
        "    check: { invariant: mass_function }\n"
    )
    path = folder / "roundabout-one-point.yaml"
    path.write_text(text)
    return path


def urban_safe(folder):
    """urban-falsify.yaml with a receiver sensitivity range where nothing breaks,
    so that falsify runs all its cases (docs/performance.md, Falsification)."""
    text = (ROOT / "scenarios" / "urban-falsify.yaml").read_text()
    text = text.replace("sensitivity_dbm: [-100, -60]", "sensitivity_dbm: [-100, -80]")
    path = folder / "urban-safe.yaml"
    path.write_text(text)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--only", default="s1,table,roundabout,urban,falsify")
    venv = ROOT / "target" / "bench-python" / "bin" / "python"
    parser.add_argument("--python", default=str(venv) if venv.exists() else sys.executable,
                        help="a Python with numpy (bench/requirements.txt); target/bench-python's if it exists")
    args = parser.parse_args()
    only = set(args.only.split(","))
    if not SIGHTLINE.exists():
        sys.exit(f"{SIGHTLINE} is missing: cargo build --release")
    rows = []
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        out = lambda name: ["--out", str(folder / name)]

        def sightline(*arguments):
            return [str(SIGHTLINE), *map(str, arguments)]

        def s1(workload, scenario, gammas, wall_target):
            ours = repeat(sightline("run", scenario, *out(scenario.stem)), ROOT, args.repeat)
            numpy = repeat([args.python, NUMPY, "--gamma", *gammas], ROOT, args.repeat)
            share = ours[1] / numpy[1]
            rows.append((workload, "sightline", *ours[:3], f"CPU {share:.2f} × numpy's",
                         f"≤ {wall_target} s wall, CPU ≤ 0.25 × numpy's, ≤ 50 MB",
                         ours[0] <= wall_target and share <= 0.25 and ours[2] <= 50 * 1024))
            rows.append((workload, "numpy", *numpy[:3], "", "", None))

        if "s1" in only:
            s1("S1, one γ, Baseline + Proposed", Path("bench/s1-one-gamma.yaml"), ["10"], 0.12)
        if "table" in only:
            s1("S1, five γ, Baseline + Proposed", Path("bench/s1-table.yaml"), ["6", "8", "10", "12", "14"], 0.5)
        if "roundabout" in only:
            scenario = roundabout_one_point(folder)
            wall, cpu, peak, _ = repeat(sightline("run", scenario, *out("rb")), ROOT, args.repeat)
            note = f"{30 / wall:.0f}× real time ({30 / cpu:.0f} s simulated per CPU s)"
            rows.append(("roundabout, one point, 30 s", "sightline", wall, cpu, peak, note, "≥ 100× real time", 30 / wall >= 100))
        if "urban" in only:
            # 6 configurations × 5 pooled runs × 120 s.
            command = sightline("run", "scenarios/urban-rsu-semantic.yaml", *out("urban"))
            wall, cpu, peak, _ = repeat(command, ROOT, args.repeat)
            runs = 30
            note = f"{120 * runs / wall:.0f}× real time ({120 * runs / cpu:.0f} s simulated per CPU s)"
            target = ("≥ 1000× real time", 120 * runs / wall >= 1000)
            rows.append(("urban junction, 30 runs × 120 s", "sightline", wall, cpu, peak, note, *target))
        if "falsify" in only:
            scenario = urban_safe(folder)
            command = sightline("falsify", scenario, "--cases", "200", *out("falsify"))
            wall, cpu, peak, stdout = repeat(command, ROOT, args.repeat)
            simulations = int(re.search(r"\((\d+) simulations", stdout).group(1))
            note = f"{simulations / wall:.0f} evaluations/s ({simulations} simulations; {simulations / cpu:.0f} per CPU s)"
            target = ("≥ 50 evaluations/s", simulations / wall >= 50)
            rows.append(("falsify, urban junction, 200 cases", "sightline", wall, cpu, peak, note, *target))
    load_after = os.getloadavg()

    print(f"load average (1, 5, 15 min): before {load_before[0]:.2f} {load_before[1]:.2f} {load_before[2]:.2f}, "
          f"after {load_after[0]:.2f} {load_after[1]:.2f} {load_after[2]:.2f}; medians of {args.repeat} runs\n")
    print("| workload | program | wall | CPU | peak memory | | target | met |")
    print("|---|---|---|---|---|---|---|---|")
    for workload, program, wall, cpu, peak, note, target, met in rows:
        verdict = "" if met is None else ("yes" if met else "**no**")
        print(f"| {workload} | {program} | {wall:.3f} s | {cpu:.3f} s | {peak / 1024:.0f} MB | {note} | {target} | {verdict} |")


if __name__ == "__main__":
    main()
