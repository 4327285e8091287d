#!/usr/bin/python3
"""The shape of a junction_sfm trajectory without its scale: Sim(3) ATE and step lengths.

    scripts/trajectory_shape.py <junction_sfm output dir> [label]

Reads trajectory_odometry.txt, trajectory_refined.txt and trajectory_groundtruth.txt (TUM format,
camera poses, SPEC section 3) and metrics.json, and prints one line per run:

    label  ATE odometry -> refined (ratio) | Sim(3) ATE odometry / refined (refined's scale) | steps

ATE is metrics.json's (rigid SE(3) alignment, docs/metrics.md). Sim(3) ATE is the RMSE of the
camera centres after the best similarity onto the true ones (Umeyama 1991, with scale): what is
left when the scale, which one camera cannot observe, is taken out. "steps" are the refined step
lengths over the true ones, each scaled by the Sim(3) scale (1.000 = the right relative length).
Used for the vgg-corridor diagnosis in docs/backend_results.md ("vgg-corridor: ... what the truth
can decide").
"""
import json
import os
import sys

import numpy as np


def load_centres(path):
    centres = {}
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            values = line.split()
            centres[float(values[0])] = np.array([float(v) for v in values[1:4]])
    return centres


def sim3_ate(estimate, truth):
    """RMSE after the best similarity of estimate onto truth, and its scale (Umeyama 1991)."""
    stamps = sorted(set(estimate) & set(truth))
    a = np.array([estimate[t] for t in stamps])
    b = np.array([truth[t] for t in stamps])
    a0, b0 = a - a.mean(0), b - b.mean(0)
    u, s, vt = np.linalg.svd(b0.T @ a0 / len(stamps))
    d = np.eye(3)
    if np.linalg.det(u @ vt) < 0:
        d[2, 2] = -1
    rotation = u @ d @ vt
    scale = np.trace(np.diag(s) @ d) / ((a0**2).sum() / len(stamps))
    residual = b0 - scale * (rotation @ a0.T).T
    return float(np.sqrt((residual**2).sum(1).mean())), float(scale)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    label = sys.argv[2] if len(sys.argv) > 2 else out
    truth = load_centres(os.path.join(out, "trajectory_groundtruth.txt"))
    odometry = load_centres(os.path.join(out, "trajectory_odometry.txt"))
    refined = load_centres(os.path.join(out, "trajectory_refined.txt"))
    with open(os.path.join(out, "metrics.json")) as f:
        metrics = json.load(f)
    sim3_odometry, _ = sim3_ate(odometry, truth)
    sim3_refined, scale = sim3_ate(refined, truth)
    stamps = sorted(truth)
    steps = " ".join(
        "%.3f" % (scale * np.linalg.norm(refined[b] - refined[a]) / np.linalg.norm(truth[b] - truth[a]))
        for a, b in zip(stamps, stamps[1:]))
    ate_odometry, ate_refined = metrics["ate_odometry_m"], metrics["ate_refined_m"]
    print("%s  ATE %.4f -> %.4f (%.3f) | Sim(3) ATE %.4f / %.4f (scale %.4f) | steps %s" %
          (label, ate_odometry, ate_refined, ate_refined / ate_odometry, sim3_odometry, sim3_refined, scale, steps))


if __name__ == "__main__":
    main()
