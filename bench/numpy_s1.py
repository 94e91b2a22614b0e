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

It is also the independent check of the bundled field experiment
(scenarios/evidential-field.yaml, tests/e2e/field_reference.rs): with
--error-model, --methods and --rules it computes what that scenario sweeps,
written from docs/scenario-language.md and docs/findings/seed-001.md, not from
sightline's code: the `wrong_label` reading (a wrong label with probability e,
an occupied cell mislabelled Empty, an empty one Occupy or Unknown with e/2
each, then Dirichlet(k(1 - e0), k e0/2, k e0/2) around the label), the
mean-one (n times the weights) and nearest-one (d_min/d_i) weights, Bayesian
log-odds fusion (pignistic p = m(O) + m(U)/2 clamped to [1e-6, 1 - 1e-6],
decided on (1 - p, p, 0), its uncertainty the binary entropy in bits) and the
`exceeds` rule (p_max > theta). The pairwise fold is not computed. Each method
fuses the same draws; each rule reads the same fused cells. Besides each mean,
it prints the standard deviation over cells, for the check's standard errors.

usage: numpy_s1.py [--gamma G ...] [--seed N] [--error-model M] [--methods NAME ...] [--rules R ...]
       (prints one JSON line per gamma)
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


# The methods, by the labels the bundled field scenario gives them: None for
# Dempster's rule, a weight scaling for the hybrid rule, or Bayes.
METHODS = {
    "Baseline": None,
    "Proposed": "sum_to_one",
    "Proposed, mean-one weights": "mean_one",
    "Proposed, nearest-one weights": "nearest_one",
    "Bayes": "bayes",
}
EMPTY, OCCUPY, UNKNOWN = 0, 1, 2
PROBABILITY_CLAMP = 1e-6


def experiment(gamma, rng, error_model="dirichlet_mean", methods=("Baseline", "Proposed"), rules=("margin",)):
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

    # Unnormalised Dempster combinations, starting from the vacuous mass; Bayes
    # sums log-odds.
    fused = {
        name: np.zeros(CELLS * CELLS) if METHODS[name] == "bayes"
        else [np.zeros(CELLS * CELLS), np.zeros(CELLS * CELLS), np.ones(CELLS * CELLS)]
        for name in methods
    }
    for cells, d, dc in in_range:
        source = draw(truth[cells], EPSILON0 + gamma / 100.0 * d / RANGE, error_model, rng)
        for name in methods:
            scaling = METHODS[name]
            if scaling is None:
                combine(fused[name], cells, source)
            elif scaling == "bayes":
                p = np.clip(source[1] + 0.5 * source[2], PROBABILITY_CLAMP, 1.0 - PROBABILITY_CLAMP)
                fused[name][cells] += np.log(p / (1.0 - p))
            else:
                weight = {
                    "sum_to_one": lambda: 1.0 / (dc * inverse_sum[cells]),
                    "mean_one": lambda: count[cells] / (dc * inverse_sum[cells]),
                    "nearest_one": lambda: nearest[cells] / dc,
                }[scaling]()
                weight = np.where(weighted[cells], weight, 1.0)
                largest = np.maximum(np.maximum(source[0], source[1]), source[2])
                powers = [np.power(m / largest, weight) for m in source]
                total = powers[0] + powers[1] + powers[2]
                combine(fused[name], cells, [p / total for p in powers])

    observed = count > 0
    result = {"gamma": gamma, "error_model": error_model, "weighted_cells": int(weighted.sum())}
    for name in methods:
        if METHODS[name] == "bayes":
            p = 1.0 / (1.0 + np.exp(-fused[name]))
            result[name] = tally([1.0 - p, p, np.zeros_like(p)], truth, observed, rules, entropy(p))
        else:
            result[name] = tally(fused[name], truth, observed, rules)
    return result


def draw(occupied, epsilon, error_model, rng):
    """Each in-range cell's mass vector (Empty, Occupy, Unknown) under
    `error_model`, for the cells' truth `occupied` and misdetection `epsilon`."""
    n = len(occupied)
    if error_model == "dirichlet_mean":
        major = rng.standard_gamma(CONCENTRATION * (1.0 - epsilon))
        minor = CONCENTRATION * epsilon / 2.0
        other, unknown = rng.standard_gamma(minor), rng.standard_gamma(minor)
        empty_g = np.where(occupied, other, major)
        occupied_g = np.where(occupied, major, other)
    elif error_model == "wrong_label":
        u = rng.random(n)
        label = np.where(
            occupied,
            np.where(u < epsilon, EMPTY, OCCUPY),
            np.where(u < epsilon / 2.0, OCCUPY, np.where(u < epsilon, UNKNOWN, EMPTY)),
        )
        major = rng.standard_gamma(CONCENTRATION * (1.0 - EPSILON0), size=n)
        first, second = rng.standard_gamma(CONCENTRATION * EPSILON0 / 2.0, size=(2, n))
        # The label's state takes the major draw, the other two the minor ones in order.
        empty_g = np.where(label == EMPTY, major, first)
        occupied_g = np.where(label == OCCUPY, major, np.where(label == EMPTY, first, second))
        unknown = np.where(label == UNKNOWN, major, second)
    else:
        raise ValueError(f"unknown error model {error_model}")
    total = empty_g + occupied_g + unknown
    return (empty_g / total, occupied_g / total, unknown / total)


def combine(fused, cells, source):
    """Dempster's rule, unnormalised: fused[cells] combined with `source`."""
    e, o, u = (f[cells] for f in fused)
    se, so, su = source
    fused[0][cells] = e * (se + su) + u * se
    fused[1][cells] = o * (so + su) + u * so
    fused[2][cells] = u * su


def entropy(p):
    """Binary entropy in bits, with 0 log 0 = 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        term = lambda q: np.where(q > 0.0, -q * np.log2(q), 0.0)
        return term(p) + term(1.0 - p)


def tally(fused, truth, observed, rules, uncertainty=None):
    """The counts of each decision rule over the observed cells, and the mean
    and standard deviation of the conflict (Dempster's rules only) and of the
    uncertainty (the Unknown mass, or a Bayesian cell's entropy)."""
    agreement = fused[0] + fused[1] + fused[2]
    masses = np.stack([f / agreement for f in fused])
    best = np.argmax(masses, axis=0)
    p_max = np.max(masses, axis=0)
    result = {}
    for rule in rules:
        if rule == "margin":
            decided = 2.0 * p_max - masses.sum(axis=0) >= THRESHOLD
        elif rule == "exceeds":
            decided = p_max > THRESHOLD
        else:
            raise ValueError(f"unknown decision rule {rule}")
        decided &= observed
        occupied_decision = decided & (best == OCCUPY)
        empty_decision = decided & (best == EMPTY)
        result[rule] = {
            "below_threshold": int((observed & ~decided).sum()),
            "correct": int((occupied_decision & truth).sum() + (empty_decision & ~truth).sum()),
            "false_alarms": int((occupied_decision & ~truth).sum()),
            "missed_detections": int((empty_decision & truth).sum()),
            "decided_unknown": int((decided & (best == UNKNOWN)).sum()),
        }
    if uncertainty is None:
        conflict = 1.0 - agreement[observed]
        result["mean_conflict"] = float(conflict.mean())
        result["sd_conflict"] = float(conflict.std())
        uncertainty = masses[2]
    result["mean_uncertainty"] = float(uncertainty[observed].mean())
    result["sd_uncertainty"] = float(uncertainty[observed].std())
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gamma", type=float, nargs="+", default=[10.0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--error-model", default="dirichlet_mean", choices=["dirichlet_mean", "wrong_label"])
    parser.add_argument("--methods", nargs="+", default=["Baseline", "Proposed"], choices=list(METHODS))
    parser.add_argument("--rules", nargs="+", default=["margin"], choices=["margin", "exceeds"])
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    for gamma in args.gamma:
        print(json.dumps(experiment(gamma, rng, args.error_model, args.methods, args.rules)))


if __name__ == "__main__":
    main()
