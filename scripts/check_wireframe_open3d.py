#!/usr/bin/python3
"""Checks that Open3D reads a junction_sfm wireframe.ply with its edges (SPEC section 3).

    /usr/bin/python3 scripts/check_wireframe_open3d.py <output dir>/wireframe.ply

Reads the file with open3d.io.read_line_set (Debian python3-open3d, run with the system Python)
and, independently, parses the ASCII PLY here; prints what Open3D read and fails (exit 1, one line on
stderr) unless Open3D has every vertex (bit for bit) and every edge of the file. Exit 2: bad usage.
"""
import sys


def parse_ascii_ply(path):
    """Vertices (x, y, z as floats) and edges (vertex1, vertex2) of an ASCII PLY line set."""
    with open(path, "r", encoding="ascii") as stream:
        lines = stream.read().split("\n")
    if not lines or lines[0].strip() != "ply":
        raise ValueError(f"{path}: not a PLY file")
    elements = []  # (name, count, [property names])
    index = 1
    while True:
        if index >= len(lines):
            raise ValueError(f"{path}: no end_header")
        words = lines[index].split()
        index += 1
        if not words:
            continue
        if words[0] == "format" and words[1] != "ascii":
            raise ValueError(f"{path}: only ASCII PLY is parsed here, not {words[1]}")
        if words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            elements[-1][2].append(words[-1])
        elif words[0] == "end_header":
            break
    vertices, edges = [], []
    for name, count, properties in elements:
        for _ in range(count):
            values = lines[index].split()
            index += 1
            row = dict(zip(properties, values))
            if name == "vertex":
                vertices.append((float(row["x"]), float(row["y"]), float(row["z"])))
            elif name == "edge":
                edges.append((int(row["vertex1"]), int(row["vertex2"])))
    return vertices, edges


def main(argv):
    if len(argv) != 2:
        print(f"usage: {argv[0]} <wireframe.ply>", file=sys.stderr)
        return 2
    path = argv[1]
    try:
        vertices, edges = parse_ascii_ply(path)
    except (OSError, ValueError, KeyError, IndexError) as error:
        print(f"check_wireframe_open3d: {error}", file=sys.stderr)
        return 1
    import numpy as np
    import open3d as o3d

    line_set = o3d.io.read_line_set(path, print_progress=False)
    points = np.asarray(line_set.points)
    lines = np.asarray(line_set.lines)
    print(f"open3d {o3d.__version__}: read_line_set({path})")
    print(f"  {line_set}")
    print(f"  points {points.shape}, lines {lines.shape}; the file has {len(vertices)} vertices, {len(edges)} edges")
    if len(points):
        low, high = points.min(axis=0), points.max(axis=0)
        print(f"  bounding box min {low.tolist()} max {high.tolist()}")
    if points.shape != (len(vertices), 3) or lines.shape != (len(edges), 2):
        print(f"check_wireframe_open3d: {path}: Open3D read {points.shape[0]} points and {lines.shape[0]} lines, "
              f"the file has {len(vertices)} and {len(edges)}", file=sys.stderr)
        return 1
    if len(vertices) and not np.array_equal(points, np.array(vertices, dtype=np.float64)):
        print(f"check_wireframe_open3d: {path}: Open3D's points differ from the file's vertices", file=sys.stderr)
        return 1
    if len(edges) and not np.array_equal(lines, np.array(edges, dtype=lines.dtype)):
        print(f"check_wireframe_open3d: {path}: Open3D's lines differ from the file's edges", file=sys.stderr)
        return 1
    print("  OK: every vertex (bit for bit) and every edge read back")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
