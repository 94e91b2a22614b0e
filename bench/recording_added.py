"""What `sightline run --record` adds to a bundled scenario's run, in wall and
CPU time, for one or more builds measured interleaved.

Each round runs every binary on the scenario without and with `--record`
(results in /tmp/recording-added); each figure is the median over the rounds;
CPU time is user + system of every thread, from `wait4`. docs/performance.md
("What the evidence adds") quotes it:

    python3 bench/recording_added.py /tmp/sightline-base target/release/sightline -n 10 \
        -s sumo-town-semantic -s opendrive-crossroads-semantic -s urban-falsify
"""

import argparse
import os
import statistics
import subprocess
import time


def one(binary, scenario, record):
    """Wall and CPU seconds of one run."""
    command = [binary, "run", f"scenarios/{scenario}.yaml", "--out", "/tmp/recording-added"]
    command += ["--record"] if record else []
    start = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, _, usage = os.wait4(child.pid, 0)
    return time.perf_counter() - start, usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("binaries", nargs="+", help="sightline builds to compare")
    parser.add_argument("-n", type=int, default=10, help="rounds (default 10)")
    parser.add_argument("-s", action="append", required=True, help="a scenario of scenarios/, without .yaml")
    args = parser.parse_args()
    for scenario in args.s:
        runs = {}
        for _ in range(args.n):
            for binary in args.binaries:
                for record in (False, True):
                    runs.setdefault((binary, record), []).append(one(binary, scenario, record))
        for binary in args.binaries:
            median = lambda record, i: statistics.median(run[i] for run in runs[(binary, record)]) * 1000
            plain_wall, plain_cpu = median(False, 0), median(False, 1)
            wall, cpu = median(True, 0), median(True, 1)
            print(
                f"{scenario:32s} {binary:32s} plain wall {plain_wall:7.1f} cpu {plain_cpu:7.1f} ms"
                f" | --record wall {wall:7.1f} cpu {cpu:7.1f} ms"
                f" | added wall {100 * (wall / plain_wall - 1):+4.0f} % cpu {100 * (cpu / plain_cpu - 1):+4.0f} %"
            )


if __name__ == "__main__":
    main()
