#!/usr/bin/python3
"""Plumb-line estimate of a VGG data set's radial distortion k1 (Brown 1971): straight edges bow.

    scripts/plumb_line_k1.py [vgg dir] [fx fy cx cy]

For every long segment of <name>.NNN.lines (> 100 px) the image's edge is located across the chord
at 17 points (gradient-magnitude peak, parabola sub-pixel, 5-tap binomial smoothing), and its bow
b = the 4t(1-t) coefficient of a fit a + b' t + b 4t(1-t) of those offsets is measured. Edges that
are not one clean edge (fit RMS > 0.5 px, or fewer than 12 of 17 profiles with a gradient peak) are
skipped. OpenCV's model x_d = x (1 + k1 r^2) (normalised coordinates, centre at cx, cy) predicts a
bow proportional to k1 for each segment (computed with k1 = -0.01: undistort the end points, take
the straight line between them, distort it again); k1 is the least-squares factor between measured
and predicted bows. Printed for all views and, as a check of its stability, for the even and odd
views separately. K defaults to the median of the Corridor's P files (docs/importers.md). Used for
docs/importers.md, "Self-calibration: why K is held"; `import_sequence --vgg_k1` takes the value.
"""
import sys

import numpy as np


def read_pgm(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    width, height = map(int, parts[1].split())
    return np.frombuffer(parts[3], np.uint8)[: width * height].reshape(height, width).astype(float)


def smooth(image):
    kernel = np.array([1, 4, 6, 4, 1.0]) / 16
    image = np.apply_along_axis(lambda r: np.convolve(r, kernel, "same"), 1, image)
    return np.apply_along_axis(lambda c: np.convolve(c, kernel, "same"), 0, image)


def bilinear(image, x, y):
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    inside = (x0 >= 0) & (y0 >= 0) & (x0 < image.shape[1] - 1) & (y0 < image.shape[0] - 1)
    x0, y0 = np.clip(x0, 0, image.shape[1] - 2), np.clip(y0, 0, image.shape[0] - 2)
    ax, ay = x - x0, y - y0
    value = ((1 - ax) * (1 - ay) * image[y0, x0] + ax * (1 - ay) * image[y0, x0 + 1] +
             (1 - ax) * ay * image[y0 + 1, x0] + ax * ay * image[y0 + 1, x0 + 1])
    return np.where(inside, value, np.nan)


def main():
    directory = sys.argv[1] if len(sys.argv) > 1 else "../shared/data/vgg-corridor"
    fx, fy, cx, cy = (map(float, sys.argv[2:6]) if len(sys.argv) > 5 else (502.616, 506.404, 295.385, 266.427))

    def distort(u, v, k1):
        x, y = (u - cx) / fx, (v - cy) / fy
        r2 = x * x + y * y
        return cx + fx * x * (1 + k1 * r2), cy + fy * y * (1 + k1 * r2)

    def undistort(u, v, k1):
        xd, yd = (u - cx) / fx, (v - cy) / fy
        x, y = xd, yd
        for _ in range(50):
            r2 = x * x + y * y
            x, y = xd / (1 + k1 * r2), yd / (1 + k1 * r2)
        return cx + fx * x, cy + fy * y

    probe = -0.01
    t = np.linspace(0.1, 0.9, 17)
    basis = np.stack([np.ones_like(t), t, 4 * t * (1 - t)], 1)
    measured, predicted, view_of = [], [], []
    for view in range(100):
        try:
            image = smooth(read_pgm("%s/bt.%03d.pgm" % (directory, view)))
            lines = open("%s/bt.%03d.lines" % (directory, view)).read().splitlines()
        except FileNotFoundError:
            break
        for line in lines:
            values = list(map(float, line.split()[:4]))
            p0, p1 = np.array(values[:2]), np.array(values[2:4])
            length = np.linalg.norm(p1 - p0)
            if length < 100:
                continue
            along = (p1 - p0) / length
            normal = np.array([-along[1], along[0]])
            offsets = []
            for ti in t:
                c = p0 + ti * (p1 - p0)
                s = np.arange(-6, 6.01, 0.25)
                profile = bilinear(image, c[0] + s * normal[0], c[1] + s * normal[1])
                if np.any(np.isnan(profile)):
                    offsets.append(np.nan)
                    continue
                gradient = np.abs(np.gradient(profile))
                i = np.argmax(gradient[4:-4]) + 4
                if gradient[i] < 3:
                    offsets.append(np.nan)
                    continue
                curvature = gradient[i - 1] - 2 * gradient[i] + gradient[i + 1]
                offsets.append(s[i] + 0.25 * (0.5 * (gradient[i - 1] - gradient[i + 1]) / curvature if curvature else 0))
            offsets = np.array(offsets)
            ok = ~np.isnan(offsets)
            if ok.sum() < 12:
                continue
            coefficients = np.linalg.lstsq(basis[ok], offsets[ok], rcond=None)[0]
            if np.sqrt(np.mean((offsets[ok] - basis[ok] @ coefficients) ** 2)) > 0.5:
                continue
            u0, u1 = undistort(*p0, probe), undistort(*p1, probe)
            curve = np.array([distort(u0[0] + ti * (u1[0] - u0[0]), u0[1] + ti * (u1[1] - u0[1]), probe) for ti in t])
            bow = np.linalg.lstsq(basis, (curve - p0) @ normal, rcond=None)[0][2]
            measured.append(coefficients[2])
            predicted.append(bow / probe)  # bow per unit k1
            view_of.append(view)
    measured, predicted, view_of = map(np.array, (measured, predicted, view_of))

    def estimate(mask):
        m, p = measured[mask], predicted[mask]
        k1 = (m @ p) / (p @ p)
        residual = m - k1 * p
        sigma = np.sqrt(residual @ residual / max(len(m) - 1, 1) / (p @ p))
        return k1, sigma, len(m)

    for label, mask in (("all views", np.ones(len(measured), bool)), ("even views", view_of % 2 == 0),
                        ("odd views", view_of % 2 == 1)):
        k1, sigma, n = estimate(mask)
        print("%-10s k1 %.4f +- %.4f from %d edges" % (label, k1, sigma, n))


if __name__ == "__main__":
    main()
