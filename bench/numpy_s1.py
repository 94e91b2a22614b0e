#!/usr/bin/env python3
"""The seed 001 experiment (S1) in vectorised numpy: the reference that
sightline's field engine is measured against (issue 20, docs/performance.md).

The same experiment as bench/s1-one-gamma.yaml and bench/s1-table.yaml: a
500 m square of 0.5 m cells (1000 x 1000), each occupied with probability 0.1;
16 sensors of range 200 m at the centres of a 4 x 4 tiling; each sensor in range
of a cell reports a mass vector (Empty, Occupy, Unknown) drawn from
Dirichlet(k(1 - e), k e/2, k e/2) with the large parameter on the truth,
k = 32, e = e0 + gamma/100 * d/R, e0 = 0.0625; Baseline fuses a cell's sources
with Dempster's rule, Proposed with the hybrid distance-weighted rule as the
paper writes it (weights (1/d_i) / sum_j (1/d_j), each source's masses raised
to its weight and renormalised, then Dempster's rule; where the sources'
distances differ by at most 50 m, Dempster's rule alone); distances below half
a cell count as half a cell; a cell is decided when p_max - p_others >= 0.8.
It counts, per method, the cells below the threshold, the correct decisions,
false alarms, missed detections and cells decided Unknown, and the mean
conflict and Unknown mass (what sightline's tally also computes).

Vectorised as numpy code is written: sensor by sensor over every cell in range
(numpy's Generator draws the Gamma variates: Marsaglia and Tsang with a
ziggurat normal, as sightline does), Dempster's rule unnormalised over the
whole grid and normalised once. Its random stream is numpy's (PCG64), not
sightline's, so its counts agree with sightline's within sampling error, not
to the cell.

usage: numpy_s1.py [--gamma G ...] [--seed N]      (prints one JSON line per gamma)
"""

import argparse
import json

import numpy as np

CELLS = 1000
CELL = 0.5
RANGE = 200.0
CONCENTRATION = 32.0
EPSILON0 = 0.0625
OCCUPIED = 0.1
THRESHOLD = 0.8
SWITCH = 50.0
LAYOUT = 4


def experiment(gamma, rng):
    centres = (np.arange(CELLS) + 0.5) * CELL
    side = CELLS * CELL
    sensors = [((c + 0.5) * side / LAYOUT, (r + 0.5) * side / LAYOUT) for r in range(LAYOUT) for c in range(LAYOUT)]
    truth = (rng.random(CELLS * CELLS) < OCCUPIED)

    def distances(sensor):
        dx = centres[None, :] - sensor[0]
        dy = centres[:, None] - sensor[1]
        return np.sqrt(dx * dx + dy * dy).ravel()

    # What the weights of each cell depend on: 1/d summed, nearest, farthest.
    inverse_sum = np.zeros(CELLS * CELLS)
    nearest = np.full(CELLS * CELLS, np.inf)
    farthest = np.zeros(CELLS * CELLS)
    count = np.zeros(CELLS * CELLS, dtype=np.int64)
    in_range = []
    for sensor in sensors:
        d = distances(sensor)
        cells = np.flatnonzero(d <= RANGE)
        dc = np.maximum(d[cells], CELL / 2)
        in_range.append((cells, d[cells], dc))
        inverse_sum[cells] += 1.0 / dc
        nearest[cells] = np.minimum(nearest[cells], dc)
        farthest[cells] = np.maximum(farthest[cells], dc)
        count[cells] += 1
    weighted = (count > 1) & (farthest - nearest > SWITCH)

    # Unnormalised Dempster combinations, starting from the vacuous mass.
    baseline = [np.zeros(CELLS * CELLS), np.zeros(CELLS * CELLS), np.ones(CELLS * CELLS)]
    proposed = [np.zeros(CELLS * CELLS), np.zeros(CELLS * CELLS), np.ones(CELLS * CELLS)]
    for cells, d, dc in in_range:
        epsilon = EPSILON0 + gamma / 100.0 * d / RANGE
        major = rng.standard_gamma(CONCENTRATION * (1.0 - epsilon))
        minor = CONCENTRATION * epsilon / 2.0
        other, unknown = rng.standard_gamma(minor), rng.standard_gamma(minor)
        occupied = truth[cells]
        empty_g = np.where(occupied, other, major)
        occupied_g = np.where(occupied, major, other)
        total = empty_g + occupied_g + unknown
        source = (empty_g / total, occupied_g / total, unknown / total)
        combine(baseline, cells, source)
        weight = np.where(weighted[cells], 1.0 / (dc * inverse_sum[cells]), 1.0)
        largest = np.maximum(np.maximum(source[0], source[1]), source[2])
        powers = [np.power(m / largest, weight) for m in source]
        total = powers[0] + powers[1] + powers[2]
        combine(proposed, cells, [p / total for p in powers])

    observed = count > 0
    return {
        "gamma": gamma,
        "Baseline": tally(baseline, truth, observed),
        "Proposed": tally(proposed, truth, observed),
        "weighted_cells": int(weighted.sum()),
    }


def combine(fused, cells, source):
    """Dempster's rule, unnormalised: fused[cells] combined with `source`."""
    e, o, u = (f[cells] for f in fused)
    se, so, su = source
    fused[0][cells] = e * (se + su) + u * se
    fused[1][cells] = o * (so + su) + u * so
    fused[2][cells] = u * su


def tally(fused, truth, observed):
    agreement = fused[0] + fused[1] + fused[2]
    masses = np.stack([f / agreement for f in fused])
    best = np.argmax(masses, axis=0)
    p_max = np.max(masses, axis=0)
    decided = (2.0 * p_max - masses.sum(axis=0) >= THRESHOLD) & observed
    occupied_decision = decided & (best == 1)
    empty_decision = decided & (best == 0)
    return {
        "below_threshold": int((observed & ~decided).sum()),
        "correct": int((occupied_decision & truth).sum() + (empty_decision & ~truth).sum()),
        "false_alarms": int((occupied_decision & ~truth).sum()),
        "missed_detections": int((empty_decision & truth).sum()),
        "decided_unknown": int((decided & (best == 2)).sum()),
        "mean_conflict": float((1.0 - agreement[observed]).mean()),
        "mean_uncertainty": float(masses[2][observed].mean()),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gamma", type=float, nargs="+", default=[10.0])
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    for gamma in args.gamma:
        print(json.dumps(experiment(gamma, rng)))


if __name__ == "__main__":
    main()
