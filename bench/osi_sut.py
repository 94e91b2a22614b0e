#!/usr/bin/env python3
"""What the protocol of a system under test costs (issue 21), whole process.

Runs the bundled roundabout's first point (its sweeps and requirements left
out: 300 steps, the 360 000-cell grid) `--repeat` times each way with the
release build: alone, and with `examples/osi-sut/echo.py`, a system that
answers every step with an empty osi3.SensorData, serving the ego's lidar.
The system's own CPU time is measured by GNU time around it (the system runs
on the critical path: the world waits for its answer). Prints the medians
and the protocol's share: (with − alone − the system's own CPU) / alone.

    cargo build --release -p sightline
    PATH=$PWD/target/osi-python/bin:$PATH python3 bench/osi_sut.py [--repeat 5]

(the PATH gives the example the Python with osi-python that ci/tools.sh installs)
"""

import argparse
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SIGHTLINE = ROOT / "target" / "release" / "sightline"
SYSTEM = """system_under_test:
  command: [/usr/bin/time, -f, "%U %S", -o, {times}, python3, examples/osi-sut/echo.py]
  agent: ego
"""


def scenario(system):
    """The roundabout without its sweeps and requirements, with `system`."""
    text = (ROOT / "scenarios" / "roundabout-six-agents.yaml").read_text()
    text = re.sub(r"(?ms)^sweeps:.*?(?=^\S)", "", text)
    text = re.sub(r"(?ms)^requirements:.*?(?=^\S|\Z)", "", text)
    return text + system


def run(file, out):
    started = time.perf_counter()
    done = subprocess.run([SIGHTLINE, "run", file, "--out", out], cwd=ROOT, capture_output=True, text=True)
    wall = time.perf_counter() - started
    # No requirement: exit 1 is "not exercised", never 0 or an error.
    if done.returncode not in (0, 1):
        raise SystemExit(f"sightline failed:\n{done.stderr}")
    return wall


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        times = tmp / "system-times"
        alone, driven = tmp / "alone.yaml", tmp / "driven.yaml"
        alone.write_text(scenario(""))
        driven.write_text(scenario(SYSTEM.format(times=times)))
        walls = {"alone": [], "with the echo system": []}
        system_cpu = []
        for _ in range(args.repeat):
            walls["alone"].append(run(alone, tmp / "out-alone"))
            walls["with the echo system"].append(run(driven, tmp / "out-driven"))
            user, sys_ = map(float, times.read_text().split()[-2:])
            system_cpu.append(user + sys_)
        a, d, s = (statistics.median(x) for x in (walls["alone"], walls["with the echo system"], system_cpu))
        print(f"load average: {open('/proc/loadavg').read().split()[:3]}")
        print(f"alone: {a:.3f} s wall (median of {args.repeat})")
        print(f"with the echo system: {d:.3f} s wall, the system's own CPU {s:.3f} s")
        print(f"protocol: {d - a - s:.3f} s, {100 * (d - a - s) / a:.1f} % of the run alone")


if __name__ == "__main__":
    main()
