#!/usr/bin/env python3
"""Cost model of data-parallel rendering and compositing (docs/scaling.md).

Reads the JSON files scripts/dp-scaling.sh writes, fits the model's constants to the measured frame
times, prints each run's measured and predicted time and the error, and draws docs/scaling.png: the fit at
1-8 ranks on this machine, and the model extrapolated to 1,024 ranks on the cluster stated below.

    scripts/dp-scaling.sh --out scaling-runs
    python3 scripts/scaling_model.py scaling-runs [--plot docs/scaling.png] [--json model.json]

Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).

The model. A frame traces the image's rays; with N ranks each ray is also traced by the other ranks it
visits. With C cores, K the exchange rounds per frame (ring: hops, bounds: rounds of alltoallv) and B_r
the bytes rank r sends:

    T = a * O + w * S + b * K + c * max_r B_r + t * O * (N - 1)   (bounds only in the last term)

O = max(max_r O_r, sum_r O_r / C) counts the rays the ranks trace of their own (generated, traced,
shaded; one rank uses every core) and a is seconds per such ray on one core; S is the time the busiest
rank spent tracing other ranks' rays (measured: ripple.visitMicroseconds), w its weight (1 if the
measurement explains itself); b is seconds per round (submissions, host work, the ranks waiting for
each other), c seconds per byte, t seconds per entry test of an own ray against another rank's boxes.
The extrapolation traces a visiting ray in v seconds, measured at 2 ranks (no core shared). Compositing: T = g * P * f / N + (rounds + 1) * l + P * f * s * (N - 1) / N / bw
(P pixels, f covered fraction, s = 20 bytes per fragment; g, l, bw fitted the same way).
"""

import argparse
import glob
import json
import math
import os
import sys

import numpy as np

CORES = 2  # this machine

# The cluster of the extrapolation: each rank a node that traces like this machine's two cores together,
# links of 100 Gb/s with 2 microseconds per message, the boxes scene's rays per frame.
CLUSTER = {"bandwidth_bytes_per_s": 12.5e9, "latency_s": 2e-6}


def load_runs(folder):
    runs = []
    for path in sorted(glob.glob(os.path.join(folder, "boxes-*.json"))):
        with open(path) as f:
            j = json.load(f)
        ranks = j["perRank"]
        own = [r["raysTracedPerFrame"] for r in ranks]
        visits = [r["raysReceivedPerFrame"] for r in ranks]
        runs.append({
            "file": os.path.basename(path),
            "ranks": j["ranks"],
            "exchange": j["exchange"] if j["ranks"] > 1 else "none",
            "partition": j["partition"],
            "seconds": j["secondsPerFrame"],
            "own_max": max(own),
            "own_rays": sum(own),
            "visits_max": max(visits),
            "visit_seconds": max(r.get("visitSecondsPerFrame", 0.0) for r in ranks),
            "visits": sum(visits),
            "rounds": max(r.get("exchangeRoundsPerFrame", 0) for r in ranks),
            "bytes_max": max(r["bytesSentPerFrame"] for r in ranks),
            "bytes_per_hop": j["bytesPerRayHop"],
        })
    composites = []
    for path in sorted(glob.glob(os.path.join(folder, "composite-*.json"))):
        with open(path) as f:
            j = json.load(f)
        composites.append(j)
    return runs, composites


def features(run):
    """The model's terms: rays a rank traces of its own (the busiest rank's, or the ranks' total over the
    cores when they share them; one rank uses every core), the seconds the busiest rank spent tracing
    other ranks' rays (measured), exchange rounds, the busiest rank's bytes, and the bounds exchange's
    entry tests (each own ray against each other rank)."""
    n = run["ranks"]
    own = run["own_rays"] / CORES if n == 1 else max(run["own_max"], run["own_rays"] / CORES)
    tests = max(run["own_max"], run["own_rays"] / CORES) * (n - 1) if run["exchange"] == "bounds" else 0.0
    return [own, run["visit_seconds"], run["rounds"], run["bytes_max"], tests]


def fit(runs):
    """Non-negative least squares on relative errors (each run weighs by its own time)."""
    from scipy.optimize import nnls
    x = np.array([features(r) for r in runs], dtype=float)
    y = np.array([r["seconds"] for r in runs], dtype=float)
    scale = x.max(axis=0)
    scale[scale == 0] = 1.0
    coefficients, _ = nnls((x / scale) / y[:, None], np.ones_like(y))
    return coefficients / scale


def visits_per_ray(runs, exchange, partition):
    """(N, mean visits to other ranks per own ray) of the measured runs."""
    points = []
    for r in runs:
        if r["exchange"] == exchange and r["partition"] == partition and r["ranks"] > 1:
            points.append((r["ranks"], r["visits"] / r["own_rays"]))
    return sorted(points)


def fit_power(points):
    """v(N) = p * (N - 1)^q through the measured points (log-log least squares)."""
    n = np.array([p[0] - 1 for p in points], dtype=float)
    v = np.array([p[1] for p in points], dtype=float)
    q, log_p = np.polyfit(np.log(n), np.log(v), 1)
    return math.exp(log_p), q


def extrapolate(coefficients, runs, ranks):
    """Seconds per frame on the stated cluster, for the ring and for the bounds exchange on spatially
    partitioned data: visits per ray as fitted on the slabs here, the exponent capped at 1/3 (a ray
    crosses about N^(1/3) of N bricks)."""
    a, _, b, _, t = coefficients
    # Seconds per visiting ray on one core, measured where the ranks do not share a core (2 ranks).
    two = [r for r in runs if r["ranks"] == 2 and r["visits_max"] > 0]
    v = float(np.mean([r["visit_seconds"] / r["visits_max"] for r in two]))
    one = [r for r in runs if r["ranks"] == 1]
    rays = float(np.mean([r["own_rays"] for r in one]))  # the image's rays per frame
    # Ring: `cycles` queue cycles per frame of N hops each (one message per hop); bounds: `rounds`
    # alltoallv per frame, whatever N (each a message to every other rank).
    cycles = float(np.mean([r["rounds"] / r["ranks"] for r in runs if r["exchange"] == "ring"]))
    rounds = float(np.mean([r["rounds"] for r in runs if r["exchange"] == "bounds"]))
    hop_bytes = {e: float(np.mean([r["bytes_per_hop"] for r in runs if r["exchange"] == e])) for e in ("ring", "bounds")}
    p, q = fit_power(visits_per_ray(runs, "bounds", "slabs"))
    q_bricks = min(q, 1.0 / 3.0)
    own_seconds, visit_seconds = a / CORES, v / CORES  # a node traces on both cores
    latency, bandwidth = CLUSTER["latency_s"], CLUSTER["bandwidth_bytes_per_s"]
    out = {"ranks": list(ranks), "ring": [], "bounds": [], "raysPerFrame": rays, "ringCycles": cycles,
           "secondsPerVisit": v, "secondsPerRound": b,
           "boundsRounds": rounds, "visits_fit": {"p": p, "q": q, "q_bricks": q_bricks}}
    for n in ranks:
        if n == 1:
            out["ring"].append(own_seconds * rays)
            out["bounds"].append(own_seconds * rays)
            continue
        # Ring: a rank traces its rays / N and every other rank's (rays in all), sends rays * bytes per hop.
        # Each round costs what it cost here (b: submissions, host work, waiting) plus its messages.
        out["ring"].append(own_seconds * rays / n + visit_seconds * rays * (n - 1) / n + cycles * n * (b + latency)
                           + rays * hop_bytes["ring"] / bandwidth)
        visits = p * (n - 1) ** q_bricks
        sent = rays / n * visits * hop_bytes["bounds"]
        out["bounds"].append(own_seconds * rays / n + visit_seconds * rays / n * visits
                             + rounds * (b + (n - 1) * latency) + sent / bandwidth + t / CORES * rays / n * (n - 1))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="the JSON files of scripts/dp-scaling.sh")
    parser.add_argument("--plot", default="docs/scaling.png")
    parser.add_argument("--json", default="", help="also write the fit, table and extrapolation here")
    args = parser.parse_args()
    runs, composites = load_runs(args.folder)
    if not runs:
        sys.exit(f"scaling_model.py: no boxes-*.json in {args.folder}")
    coefficients = fit(runs)
    a, w, b, c, t = coefficients
    print(f"fit: a = {a * 1e9:.1f} ns per own ray (one core), w = {w:.2f} x the measured visit seconds, "
          f"b = {b * 1e3:.3f} ms per exchange round, c = {c * 1e9:.3f} ns per byte sent, "
          f"t = {t * 1e9:.2f} ns per entry test (own ray x other rank)")
    print(f"{'run':34s} {'ranks':>5s} {'measured s':>10s} {'model s':>8s} {'error':>7s}")
    errors = []
    table = []
    for r in sorted(runs, key=lambda r: (r["partition"], r["exchange"], r["ranks"])):
        predicted = float(np.dot(coefficients, features(r)))
        error = predicted / r["seconds"] - 1.0
        errors.append(abs(error))
        table.append({"file": r["file"], "ranks": r["ranks"], "measured": r["seconds"], "model": predicted})
        print(f"{r['file']:34s} {r['ranks']:5d} {r['seconds']:10.3f} {predicted:8.3f} {100 * error:+6.1f}%")
    print(f"largest error {100 * max(errors):.1f}%, mean {100 * float(np.mean(errors)):.1f}% over {len(runs)} runs")
    # Out of sample: fitted on one partition's runs, predicting the other's.
    for held in ("random", "slabs"):
        train = [r for r in runs if r["partition"] != held]
        test = [r for r in runs if r["partition"] == held]
        if not train or not test:
            continue
        k = fit(train)
        out = [abs(float(np.dot(k, features(r))) / r["seconds"] - 1.0) for r in test]
        print(f"fitted without the {held} runs, predicting them: largest error {100 * max(out):.1f}%, "
              f"mean {100 * float(np.mean(out)):.1f}% over {len(test)} runs")

    ranks = [1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024]
    ext = extrapolate(coefficients, runs, ranks)
    vf = ext["visits_fit"]
    print(f"visits per ray, bounds on slabs: {vf['p']:.3f} * (N - 1)^{vf['q']:.3f} (bricks: exponent {vf['q_bricks']:.3f})")
    print(f"{'ranks':>6s} {'ring s':>10s} {'bounds s':>10s}   (stated cluster: 100 Gb/s, 2 us, nodes of 2 cores)")
    for n, ring, bounds in zip(ranks, ext["ring"], ext["bounds"]):
        print(f"{n:6d} {ring:10.4f} {bounds:10.4f}")

    if args.json:
        with open(args.json, "w") as f:
            json.dump({"coefficients": {"a": a, "w": w, "b": b, "c": c, "t": t}, "runs": table, "extrapolation": ext,
                       "largestError": max(errors)}, f, indent=2)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (partition, exchange), style in {("random", "ring"): "C0o", ("random", "bounds"): "C1o",
                                         ("slabs", "ring"): "C0s", ("slabs", "bounds"): "C1s"}.items():
        sel = sorted([r for r in runs if (r["partition"] == partition and r["exchange"] == exchange)
                      or (r["ranks"] == 1 and r["partition"] == partition)], key=lambda r: r["ranks"])
        n = [r["ranks"] for r in sel]
        left.plot(n, [r["seconds"] for r in sel], style, label=f"{partition}, {exchange}: measured")
        left.plot(n, [float(np.dot(coefficients, features(r))) for r in sel], style[:2] + "--", alpha=0.7)
    left.set_xlabel("ranks (mpirun --oversubscribe on 2 cores)")
    left.set_ylabel("seconds per frame")
    left.set_title(f"boxes, 256x256, 4 spp: measured (marks), model (dashed), worst {100 * max(errors):.0f}%",
                   fontsize=9)
    left.legend(fontsize=7)
    left.grid(alpha=0.3)
    right.loglog(ranks, ext["ring"], "C0-", label="ring")
    right.loglog(ranks, ext["bounds"], "C1-", label="bounds (bricks)")
    right.set_xlabel("ranks")
    right.set_ylabel("seconds per frame")
    right.set_title("model on a cluster: 100 Gb/s, 2 us links, a 2-core node per rank", fontsize=9)
    right.legend()
    right.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=90)
    print(f"wrote {args.plot}")


if __name__ == "__main__":
    main()
