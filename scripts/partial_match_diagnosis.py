#!/usr/bin/python3
"""Where a junction_sfm run's matches go wrong, full against partial (docs/matching_results.md,
"Partial correspondence: where the wrong matches came from"). A match is partial when its two
junctions have different segment counts (junctions/*.json).

  partial_match_diagnosis.py generated SEQUENCE OUTPUT   # truth/frames vertices within 3 px
  partial_match_diagnosis.py vgg VGG_DIR OUTPUT          # 2 px from the epipolar lines of bt.NNN.P

generated: per kind (full, partial) the matches, those with both junctions at true vertices and
the wrong ones among them; per partial type pair right / wrong / not both at vertices; the tracks
of tracks.csv by what their views are at. vgg: consecutive pairs, per kind and type pair, matches
and those farther than 2 px from the true epipolar lines.
"""
import collections, glob, json, math, os, sys

mode, seq, out = sys.argv[1:4]
junctions = {}


def frame_junctions(f):
    if f not in junctions:
        data = json.load(open(os.path.join(out, "junctions/%06d.json" % f)))
        junctions[f] = {j["id"]: j for j in data["junctions"]}
    return junctions[f]


def matches():
    for path in sorted(glob.glob(os.path.join(out, "matches/*.csv"))):
        fa, fb = map(int, os.path.basename(path)[:-4].split("_"))
        for line in open(path).read().split("\n")[1:]:
            if line:
                a, b, _ = line.split(",")
                ja, jb = frame_junctions(fa)[int(a)], frame_junctions(fb)[int(b)]
                kind = "full" if len(ja["segments"]) == len(jb["segments"]) else "partial"
                yield fa, fb, ja, jb, kind, "-".join(sorted([ja["type"], jb["type"]]))


if mode == "generated":
    vertices = {}

    def vertex_at(f, j):
        if f not in vertices:
            vertices[f] = [(int(p[1]), float(p[2]), float(p[3]))
                           for p in (l.split() for l in open(os.path.join(seq, "truth/frames/%06d.txt" % f)))
                           if p and p[0] == "vertex"]
        best = min(((math.hypot(u - j["x"], v - j["y"]), vid) for vid, u, v in vertices[f]), default=None)
        return best[1] if best and best[0] <= 3.0 else None

    counts = collections.Counter()
    pairs = collections.defaultdict(lambda: [0, 0, 0])
    for fa, fb, ja, jb, kind, types in matches():
        va, vb = vertex_at(fa, ja), vertex_at(fb, jb)
        counts[kind, "matches"] += 1
        if va is not None and vb is not None:
            counts[kind, "both at vertices"] += 1
            counts[kind, "wrong"] += va != vb
        if kind == "partial":
            pairs[types][2 if va is None or vb is None else int(va != vb)] += 1
    for kind in ("full", "partial"):
        print(kind, {k[1]: v for k, v in counts.items() if k[0] == kind})
    print("partial type pairs [right, wrong, not both at vertices]:", dict(pairs))
    tracks = collections.defaultdict(list)
    for line in open(os.path.join(out, "tracks.csv")).read().split("\n")[1:]:
        if line:
            t, f, j = map(int, line.split(","))
            tracks[t].append(vertex_at(f, frame_junctions(f)[j]))
    kinds = collections.Counter()
    for views in tracks.values():
        seen = set(v for v in views if v is not None)
        kinds["two or more vertices" if len(seen) > 1 else "no vertex" if not seen else
              "one vertex" if None not in views else "one vertex and views off any vertex"] += 1
    print("tracks:", dict(kinds))
else:
    import numpy as np

    def camera(i):
        return np.loadtxt(os.path.join(seq, "bt.%03d.P" % i))

    def fundamental(p1, p2):  # x2^T F x1 = 0
        centre = np.linalg.svd(p1)[2][-1]
        e = p2 @ centre
        cross = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
        return cross @ p2 @ np.linalg.pinv(p1)

    def distance(line, x):
        return abs(line @ np.array([x[0], x[1], 1.0])) / math.hypot(line[0], line[1])

    counts = collections.Counter()
    for fa, fb, ja, jb, kind, types in matches():
        if fb - fa != 1:
            continue
        F = fundamental(camera(fa), camera(fb))
        xa, xb = np.array([ja["x"], ja["y"], 1.0]), np.array([jb["x"], jb["y"], 1.0])
        d = max(distance(F @ xa, xb), distance(F.T @ xb, xa))
        counts[kind, types, "matches"] += 1
        counts[kind, types, "wrong (> 2 px)"] += d > 2
    for key in sorted(counts):
        print(key, counts[key])
