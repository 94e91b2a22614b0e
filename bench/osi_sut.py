#!/usr/bin/env python3
"""What the protocol of a system under test costs (issue 21), whole process.

Runs the bundled roundabout's first point (its sweeps and requirements left
out: 300 steps, the 360 000-cell grid) `--repeat` times each way with the
release build: alone, and with `examples/osi-sut/echo.py`, a system that
answers every step with an empty osi3.SensorData, serving the ego's lidar.
The system's own CPU time is measured by GNU time around it (the system runs
on the critical path: the world waits for its answer). Prints the medians of
wall and CPU time (sightline's, with the processes it waited for) and the
protocol's share: (with − alone − the system's own CPU) / alone; on a loaded
machine the CPU figure is the steadier.

    cargo build --release -p sightline
    PATH=$PWD/target/osi-python/bin:$PATH python3 bench/osi_sut.py [--repeat 5]

(the PATH gives the example the Python with osi-python that ci/tools.sh installs)
"""

import argparse
import os
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
    text = re.sub(r"(?ms)^(requirements|references):.*?(?=^\S|\Z)", "", text)
    return text + system


def run(file, out):
    """Runs sightline on `file`; (wall s, CPU s of sightline and what it waited for)."""
    started = time.perf_counter()
    process = subprocess.Popen(
        [SIGHTLINE, "run", file, "--out", out], cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE
    )
    stderr = process.stderr.read()
    _, status, usage = os.wait4(process.pid, 0)
    wall = time.perf_counter() - started
    # Without requirements every run exits 0; anything else is a failure.
    if os.waitstatus_to_exitcode(status) != 0:
        raise SystemExit(f"sightline failed:\n{stderr.decode()}")
    return wall, usage.ru_utime + usage.ru_stime


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
        load = open("/proc/loadavg").read().split()[:3]
        alone_runs, driven_runs, system_cpu = [], [], []
        for _ in range(args.repeat):
            alone_runs.append(run(alone, tmp / "out-alone"))
            driven_runs.append(run(driven, tmp / "out-driven"))
            user, sys_ = map(float, times.read_text().split()[-2:])
            system_cpu.append(user + sys_)
        med = statistics.median
        a_wall, a_cpu = med(r[0] for r in alone_runs), med(r[1] for r in alone_runs)
        d_wall, d_cpu = med(r[0] for r in driven_runs), med(r[1] for r in driven_runs)
        s_cpu = med(system_cpu)
        print(f"load average before: {load}, after: {open('/proc/loadavg').read().split()[:3]}")
        print(f"medians of {args.repeat} runs each")
        print(f"alone:     {a_wall:.3f} s wall, {a_cpu:.3f} s CPU")
        print(f"with echo: {d_wall:.3f} s wall, {d_cpu:.3f} s CPU, of which the system's own {s_cpu:.3f} s")
        wall = d_wall - a_wall - s_cpu
        cpu = d_cpu - a_cpu - s_cpu
        print(f"protocol: {wall:.3f} s wall ({100 * wall / a_wall:.1f} %), {cpu:.3f} s CPU ({100 * cpu / a_cpu:.1f} %)")


if __name__ == "__main__":
    main()
