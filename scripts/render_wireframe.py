#!/usr/bin/python3
"""Renders a junction_sfm run's wireframe.ply to a PNG with Open3D's own renderer.

    /usr/bin/python3 scripts/render_wireframe.py <output dir> <sequence dir> <picture.png>
        [--width 1100] [--height 480] [--azimuth 70] [--elevation 35] [--fov 30]

Reads <output dir>/wireframe.ply with open3d.io.read_line_set (edges blue, points no edge uses
red) and <output dir>/trajectory_refined.txt (the camera path, orange), and draws them in
perspective from above one side, the floor down. Up is gravity from the robot's base frame as in
report.html (docs/report.md, UpDirection): base z from <sequence dir>/sequence.yaml's
T_base_camera, or the cameras' -y when that is the identity (data sets that give camera poses).
The view looks along the map's longer horizontal axis (of the vertices' 2nd to 98th percentile and
the cameras), turned by --azimuth degrees about the vertical towards the cameras' side and tilted
down by --elevation degrees, and is framed on that bulk of the map and every camera.

Debian's Open3D 0.16 has no headless EGL renderer (OffscreenRenderer fails: "EGL Headless is not
supported"), so the legacy Visualizer draws into an invisible window; without a display the script
runs itself again under xvfb-run (Debian xvfb). Needs python3-open3d and xvfb (scripts/setup.sh,
sfm_install_render_packages). Exit 1 with one line on stderr on bad input, 2 on bad usage.
"""
import argparse
import math
import os
import re
import shutil
import sys

import numpy as np


def fail(message):
    print(f"render_wireframe.py: {message}", file=sys.stderr)
    sys.exit(1)


def read_trajectory(path):
    """world_T_camera of every line of a TUM file: (positions N x 3, rotation matrices N x 3 x 3)."""
    positions, rotations = [], []
    with open(path, "r", encoding="ascii") as stream:
        for number, line in enumerate(stream, 1):
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if len(words) != 8:
                fail(f"{path}:{number}: expected 'timestamp tx ty tz qx qy qz qw'")
            tx, ty, tz, qx, qy, qz, qw = map(float, words[1:])
            positions.append([tx, ty, tz])
            rotations.append(quaternion_matrix(qw, qx, qy, qz))
    if not positions:
        fail(f"{path}: no pose")
    return np.array(positions), np.array(rotations)


def quaternion_matrix(w, x, y, z):
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def read_base_T_camera(path):
    """The 4 x 4 T_base_camera of an OpenCV-YAML sequence.yaml (identity when absent)."""
    try:
        with open(path, "r", encoding="utf-8") as stream:
            text = stream.read()
    except OSError as error:
        fail(f"{path}: {error.strerror}")
    match = re.search(r"T_base_camera:.*?data:\s*\[([^\]]*)\]", text, re.S)
    if match is None:
        return np.eye(4)
    values = [float(v) for v in match.group(1).replace(",", " ").split()]
    if len(values) != 16:
        fail(f"{path}: T_base_camera must have 16 values, not {len(values)}")
    return np.array(values).reshape(4, 4)


def up_direction(camera_rotations, base_T_camera):
    """docs/report.md's UpDirection: base z (or camera -y for an identity rig) averaged in the world."""
    identity = np.allclose(base_T_camera, np.eye(4), atol=1e-9)
    camera_R_base = base_T_camera[:3, :3].T
    up_in_base = np.array([0.0, -1.0, 0.0]) if identity else np.array([0.0, 0.0, 1.0])
    total = sum(r @ camera_R_base @ up_in_base for r in camera_rotations)
    norm = np.linalg.norm(total)
    return total / norm if norm > 1e-9 else np.array([0.0, 0.0, 1.0])


def view_extrinsic(vertices, centres, up, azimuth_deg, elevation_deg, fov_deg, aspect):
    """camera_T_world (4 x 4, OpenCV axes: x right, y down, z ahead) that frames the map's bulk."""
    bulk = vertices
    if len(vertices) >= 10:
        low, high = np.percentile(vertices, 2, axis=0), np.percentile(vertices, 98, axis=0)
        bulk = vertices[np.all((vertices >= low) & (vertices <= high), axis=1)]
    points = np.vstack([bulk, centres]) if len(bulk) else centres
    # The longer horizontal axis of the bulk: the principal direction of its horizontal spread.
    horizontal = points - np.outer(points @ up, up)
    centred = horizontal - horizontal.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    long_axis = vt[0] - (vt[0] @ up) * up
    long_axis /= np.linalg.norm(long_axis)
    # Look from the start of the camera path towards its end along that axis.
    if (centres[-1] - centres[0]) @ long_axis < 0:
        long_axis = -long_axis
    side = np.cross(up, long_axis)
    # Look from the cameras' side of the map (a facade is seen from the front, not from behind).
    centre = 0.5 * (points.min(axis=0) + points.max(axis=0))
    if (centres.mean(axis=0) - centre) @ side > 0:
        side = -side
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    horizontal_view = math.cos(a) * long_axis + math.sin(a) * side
    forward = math.cos(e) * horizontal_view - math.sin(e) * up
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    # Back off until every framed point is inside the field of view (with a 5 % margin).
    tan_x = math.tan(math.radians(fov_deg) / 2) * aspect * 0.95
    tan_y = math.tan(math.radians(fov_deg) / 2) * 0.95
    relative = points - centre
    x, y, z = relative @ right, relative @ down, relative @ forward
    distance = float(np.max(np.maximum(np.abs(x) / tan_x, np.abs(y) / tan_y) - z))
    eye = centre - max(distance, 1e-3) * forward
    rotation = np.vstack([right, down, forward])  # rows: the camera axes in the world
    extrinsic = np.eye(4)
    extrinsic[:3, :3] = rotation
    extrinsic[:3, 3] = -rotation @ eye
    return extrinsic


def render(args):
    import open3d as o3d

    ply = os.path.join(args.output, "wireframe.ply")
    if not os.path.isfile(ply):
        fail(f"{ply}: no such file")
    line_set = o3d.io.read_line_set(ply)
    vertices = np.asarray(line_set.points)
    if len(vertices) == 0:
        fail(f"{ply}: no vertex")
    centres, rotations = read_trajectory(os.path.join(args.output, "trajectory_refined.txt"))
    up = up_direction(rotations, read_base_T_camera(os.path.join(args.sequence, "sequence.yaml")))
    line_set.paint_uniform_color([0.12, 0.30, 0.75])
    # The vertices no edge uses (loose points) in red.
    used = np.zeros(len(vertices), dtype=bool)
    lines = np.asarray(line_set.lines)
    if len(lines):
        used[lines.ravel()] = True
    loose = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(vertices[~used]))
    loose.paint_uniform_color([0.85, 0.15, 0.10])
    path = o3d.geometry.LineSet(o3d.utility.Vector3dVector(centres),
                                o3d.utility.Vector2iVector([[i, i + 1] for i in range(len(centres) - 1)]))
    path.paint_uniform_color([0.95, 0.55, 0.05])

    visualizer = o3d.visualization.Visualizer()
    if not visualizer.create_window(visible=False, width=args.width, height=args.height):
        fail("Open3D could not open a window (no display, and not run under xvfb-run)")
    for geometry in (line_set, loose, path):
        visualizer.add_geometry(geometry)
    option = visualizer.get_render_option()
    option.background_color = np.array([1.0, 1.0, 1.0])
    option.line_width = 2.0
    option.point_size = 3.0
    fov_deg = args.fov
    camera = o3d.camera.PinholeCameraParameters()
    focal = args.height / 2 / math.tan(math.radians(fov_deg) / 2)
    # The legacy Visualizer accepts only a principal point at the image centre minus half a pixel.
    camera.intrinsic = o3d.camera.PinholeCameraIntrinsic(args.width, args.height, focal, focal,
                                                         args.width / 2 - 0.5, args.height / 2 - 0.5)
    camera.extrinsic = view_extrinsic(vertices, centres, up, args.azimuth, args.elevation, fov_deg,
                                      args.width / args.height)
    if not visualizer.get_view_control().convert_from_pinhole_camera_parameters(camera, True):
        fail("Open3D refused the view")
    visualizer.poll_events()
    visualizer.update_renderer()
    image = np.asarray(visualizer.capture_screen_float_buffer(do_render=True))
    visualizer.destroy_window()
    if image.size == 0 or float(image.min()) >= 1.0:
        fail("Open3D rendered a blank picture")
    o3d.io.write_image(args.picture, o3d.geometry.Image((image * 255).round().astype(np.uint8)))
    print(f"{args.picture}: {len(vertices)} vertices, {len(lines)} edges, {len(centres)} cameras; "
          f"up {np.round(up, 3).tolist()}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="junction_sfm output directory (wireframe.ply, trajectory_refined.txt)")
    parser.add_argument("sequence", help="the sequence directory it ran on (sequence.yaml)")
    parser.add_argument("picture", help="the PNG to write")
    parser.add_argument("--width", type=int, default=1100)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--azimuth", type=float, default=70.0,
                        help="degrees about the vertical from the map's long axis")
    parser.add_argument("--elevation", type=float, default=35.0, help="degrees the view looks down")
    parser.add_argument("--fov", type=float, default=30.0, help="vertical field of view, degrees")
    args = parser.parse_args()
    if not (args.width > 0 and args.height > 0 and -90 < args.elevation < 90 and 5 <= args.fov <= 90):
        parser.print_usage(sys.stderr)
        sys.exit(2)
    if not os.environ.get("DISPLAY") and not os.environ.get("RENDER_WIREFRAME_XVFB"):
        xvfb = shutil.which("xvfb-run")
        if xvfb is None:
            fail("no display and no xvfb-run (apt-get install xvfb)")
        os.environ["RENDER_WIREFRAME_XVFB"] = "1"
        os.execv(xvfb, [xvfb, "-a", "-s", "-screen 0 1920x1080x24", sys.executable] + sys.argv)
    render(args)


if __name__ == "__main__":
    main()
