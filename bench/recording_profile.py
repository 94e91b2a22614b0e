"""Where `sightline run --record`'s CPU time goes, from a perf profile.

Record a profile with call stacks, then classify its samples:

    perf record -F 4000 --call-graph dwarf,16384 -o run.perf \
        target/release/sightline run scenarios/sumo-grid-semantic.yaml --record --out /tmp/e
    python3 bench/recording_profile.py run.perf

Each sample counts once, toward the first of the classes below whose frame
is on its stack (so compression inside a message's writing counts as
compression, and the recorder's encoding inside a simulated step counts as
encoding). docs/performance.md quotes the shares.

Given a second profile, of the same runs without `--record` and the same
number of them, it prints what the recording adds: each class's samples in
the first less those in the second.

    python3 bench/recording_profile.py record.perf plain.perf
"""

import collections
import subprocess
import sys

# (class, substrings of a frame's symbol), in order of precedence.
CLASSES = [
    ("lz4 compression (with its frame checksum)", ["LZ4", "XXH32"]),
    ("crc32 of chunks and attachments", ["crc32fast"]),
    ("the recording's hash (read back from disk)", ["staged_sha256"]),
    ("sha256 (the imports)", ["sha2::"]),
    ("recorder: start (scenario record, attachments, map)", ["mcap::write::{impl#1}::new", "Recorder<W>::new", "Recorder<W>>::new"]),
    ("recorder: agents and frames (/scene/agents, /tf)", ["mcap::write::scene::", "mcap::write::agents::"]),
    ("recorder: semantic steps (packets, messages, signals)", ["mcap::write::semantic::"]),
    ("recorder: grids and detections", ["mcap::write::world::"]),
    ("recorder: outcomes, objects and verdicts", ["mcap::write::outcomes", "Recorder<W>>::finish"]),
    ("recorder: other", ["sightline_reports::mcap"]),
    ("rendering results.json, junit.xml, report.html", ["sightline_reports::"]),
    ("writing files (buffered writes, the staged evidence moved in place)", ["BufWriter<W>::flush_buf", "BufWriter<W>::write_cold", "Staging::commit", "Manifest::apply"]),
    ("simulation of the recorded run (again, or as it runs)", ["resimulated<", "first_run<", "OneJob<sightline::evidence::Sinks"]),
    ("simulation, unrecorded", ["sightline_engine::"]),
    ("reading and compiling the scenario", ["sightline_dsl::"]),
]


def classify(profile):
    """Each class's samples in `profile`, and the total."""
    script = subprocess.run(
        ["perf", "script", "-i", profile, "-F", "ip,sym"], capture_output=True, text=True, check=True
    ).stdout
    counts = collections.Counter()
    total = 0
    for sample in script.split("\n\n"):
        stack = sample.strip()
        if not stack:
            continue
        total += 1
        name = next((name for name, marks in CLASSES if any(m in stack for m in marks)), "other")
        counts[name] += 1
    return counts, total


def main(profile, without=None):
    counts, total = classify(profile)
    if without is None:
        for name, count in counts.most_common():
            print(f"{100 * count / total:5.1f} %  {count:6d}  {name}")
        print(f"{total} samples")
        return
    plain, plain_total = classify(without)
    added = total - plain_total
    for name in sorted(set(counts) | set(plain), key=lambda n: plain[n] - counts[n]):
        diff = counts[name] - plain[name]
        print(f"{100 * diff / added:6.1f} %  {diff:+6d}  {name}")
    print(f"{added:+d} samples added ({total} with, {plain_total} without)")


if __name__ == "__main__":
    main(*sys.argv[1:3])
