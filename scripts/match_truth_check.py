#!/usr/bin/env python3
"""How far each match of a junction_sfm run lies from the true epipolar geometry.

Usage: scripts/match_truth_check.py <output dir> [gate_px (default 3)]

Reads the run's own outputs only: junctions/*.json (locations), matches/*.csv, the true camera
poses trajectory_groundtruth.txt (written when the sequence has ground truth) and the pinhole K of
colmap/cameras.txt (COLMAP's pixel convention, centre of the top-left pixel at 0.5, shifted back to
the project's OpenCV convention). For every pair it prints the number of matches, how many lie more
than gate_px from the true epipolar lines (the larger of the two point-to-line distances) and the
median distance; a pair with most matches beyond the gate was matched on a wrong relative pose. Plain Python,
no numpy. The distance cannot see a wrong match along its epipolar line.
"""
import glob
import json
import math
import os
import re
import sys


def rotation(qx, qy, qz, qw):
    n = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    qx, qy, qz, qw = qx / n, qy / n, qz / n, qw / n
    return [[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
            [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
            [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def matvec(a, v):
    return [sum(a[i][k] * v[k] for k in range(3)) for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def read_poses(path):
    poses = []
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = [float(x) for x in line.split()]
        poses.append((rotation(v[4], v[5], v[6], v[7]), v[1:4]))  # world_T_camera
    return poses


def read_pinhole(path):
    for line in open(path):
        if line.startswith('#') or not line.strip():
            continue
        v = line.split()
        if v[1] != 'PINHOLE':
            sys.exit(path + ': expected a PINHOLE camera, found ' + v[1])
        fx, fy, cx, cy = (float(x) for x in v[4:8])
        return fx, fy, cx - 0.5, cy - 0.5
    sys.exit(path + ': no camera')


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit('usage: match_truth_check.py <output dir> [gate_px]')
    run = sys.argv[1]
    gate = float(sys.argv[2]) if len(sys.argv) == 3 else 3.0
    truth_path = os.path.join(run, 'trajectory_groundtruth.txt')
    if not os.path.exists(truth_path):
        sys.exit(truth_path + ': missing (the sequence has no ground truth?)')
    poses = read_poses(truth_path)
    fx, fy, cx, cy = read_pinhole(os.path.join(run, 'colmap', 'cameras.txt'))
    junctions = {}
    total = beyond = 0
    for path in sorted(glob.glob(os.path.join(run, 'matches', '*.csv'))):
        a, b = (int(x) for x in re.findall(r'(\d+)_(\d+)', os.path.basename(path))[0])
        for f in (a, b):
            if f not in junctions:
                doc = json.load(open(os.path.join(run, 'junctions', '%06d.json' % f)))
                junctions[f] = {j['id']: (j['x'], j['y']) for j in doc['junctions']}
        # E = [t]x R with (R, t) = camera_b_T_camera_a; distances in pixels through K.
        ra, ta = poses[a]
        rb, tb = poses[b]
        r = matmul(transpose(rb), ra)
        t = matvec(transpose(rb), [ta[i] - tb[i] for i in range(3)])
        e = matmul([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]], r)
        distances = []
        for line in open(path).readlines()[1:]:
            ia, ib = (int(x) for x in line.split(',')[:2])
            (xa, ya), (xb, yb) = junctions[a][ia], junctions[b][ib]
            na = [(xa - cx) / fx, (ya - cy) / fy, 1.0]
            nb = [(xb - cx) / fx, (yb - cy) / fy, 1.0]
            la, lb = matvec(e, na), matvec(transpose(e), nb)
            res = abs(sum(nb[i] * la[i] for i in range(3)))
            distances.append(max(res / math.hypot(la[0] / fx, la[1] / fy),
                                 res / math.hypot(lb[0] / fx, lb[1] / fy)))
        n = len(distances)
        far = sum(d > gate for d in distances)
        median = sorted(distances)[n // 2] if n else float('nan')
        flag = '  FAILED' if n and far > 0.3 * n else ''
        print('%d-%d: %d matches, %d beyond %.1f px, median %.2f px%s' % (a, b, n, far, gate, median, flag))
        total += n
        beyond += far
    print('all pairs: %d matches, %d beyond %.1f px (%.1f %%)' % (total, beyond, gate,
                                                                100.0 * beyond / max(total, 1)))


if __name__ == '__main__':
    main()
