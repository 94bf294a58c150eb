#!/usr/bin/python3
"""Mean radiance in the umbrae of a scene's spheres on its floor.

For each sphere, the umbra is the floor pixels (y = 0) the camera sees directly whose
every corner's floor point has the sphere between it and the scene's first light (a
point light, or every corner of a quad light), so pixels on the shadow's edge, whose
samples straddle it, are left out. Prints each region's
pixel count and mean radiance (over RGB) per image, and each image's ratio to the
first one (the reference) when given more than one:

  scripts/umbra_leak.py scenes/cornell_physical.json [--caustic CAUSTIC.exr] REF.exr A.exr ...

--caustic names a converged caustic view (--aov caustic): each umbra is then also
measured without its caustic (the pixels above 1% of that view's brightest, grown by
a pixel), where a leak shows undiluted.

The images may be any size (the scene's camera is scaled to it); oiiotool reads them.
"""
import json
import math
import re
import subprocess
import sys


def read_image(path):
    # oiiotool's text dump: one "Pixel (x, y): r g b" line a pixel
    out = subprocess.run(["oiiotool", "--dumpdata", path, "--ch", "R,G,B"], check=True,
                         capture_output=True, text=True).stdout.splitlines()
    width, height = map(int, re.match(r".*:\s*(\d+)\s*x\s*(\d+)", out[0]).groups())
    rows = [[None] * width for _ in range(height)]
    for line in out[1:]:
        m = re.match(r"\s*Pixel \((\d+), (\d+)\):\s*(.*)", line)
        if m:
            rows[int(m.group(2))][int(m.group(1))] = [float(v) for v in m.group(3).split()[:3]]
    return width, height, rows


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def hits_sphere(origin, direction, center, radius, t_max):
    # direction unit length; true when the segment [0, t_max) meets the sphere
    oc = sub(origin, center)
    b = dot(oc, direction)
    c = dot(oc, oc) - radius * radius
    disc = b * b - c
    if disc < 0:
        return False
    s = math.sqrt(disc)
    return (-b - s > 1e-6 and -b - s < t_max) or (-b + s > 1e-6 and -b + s < t_max)


class Regions:
    def __init__(self, scene, width, height):
        cam = scene["camera"]
        self.origin = cam["position"]
        forward = normalize(sub(cam["look_at"], cam["position"]))
        right = normalize(cross(forward, cam.get("up", [0, 1, 0])))
        up = cross(right, forward)
        self.frame = (forward, right, up)
        self.tan_half = math.tan(math.radians(cam["fov"]) * 0.5)
        self.width, self.height = width, height
        light = scene["lights"][0]
        if light["type"] == "quad":  # the umbra: every corner hidden (the light and a sphere are convex)
            c, e1, e2 = light["corner"], light["edge1"], light["edge2"]
            self.light_points = [[c[i] + a * e1[i] + b * e2[i] for i in range(3)] for a in (0, 1) for b in (0, 1)]
        else:
            self.light_points = [light["position"]]
        mats = scene["materials"]
        self.spheres = [(o["center"], o["radius"], o["material"]) for o in scene["objects"] if o["type"] == "sphere"]
        self.kinds = ["glass" if "transparent" in mats[m] else "mirror" if "reflective" in mats[m] else m
                      for _, _, m in self.spheres]

    def ray(self, fx, fy):
        forward, right, up = self.frame
        sx = (2.0 * fx / self.width - 1.0) * (self.width / self.height) * self.tan_half
        sy = (1.0 - 2.0 * fy / self.height) * self.tan_half
        return normalize([forward[i] + sx * right[i] + sy * up[i] for i in range(3)])

    def shadowing(self, fx, fy):
        """The sphere whose shadow the floor point seen at film (fx, fy) lies in; -1: lit
        or not the floor; -2: another surface first."""
        d = self.ray(fx, fy)
        if d[1] >= 0:
            return -2
        t = -self.origin[1] / d[1]
        if any(hits_sphere(self.origin, d, c, r, t) for c, r, _ in self.spheres):
            return -2
        p = [self.origin[i] + t * d[i] for i in range(3)]
        if abs(p[0]) > 1 or abs(p[2]) > 1:
            return -2
        for i, (c, r, _) in enumerate(self.spheres):
            if all(self.hidden(p, q, c, r) for q in self.light_points):
                return i
        return -1

    @staticmethod
    def hidden(p, light, center, radius):
        to_light = sub(light, p)
        dist = math.sqrt(dot(to_light, to_light))
        return hits_sphere(p, [x / dist for x in to_light], center, radius, dist)

    def region(self, x, y):
        corners = {self.shadowing(x + u, y + v) for u in (0.02, 0.98) for v in (0.02, 0.98)}
        return corners.pop() if len(corners) == 1 else -3


def main():
    args = sys.argv[1:]
    caustic = None
    if "--caustic" in args:
        i = args.index("--caustic")
        caustic = read_image(args[i + 1])[2]
        del args[i:i + 2]
    if len(args) < 2:
        sys.exit(__doc__)
    with open(args[0]) as f:
        scene = json.load(f)
    images = [(path, read_image(path)) for path in args[1:]]
    width, height = images[0][1][0], images[0][1][1]
    regions = Regions(scene, width, height)
    masks = {}
    for y in range(height):
        for x in range(width):
            r = regions.region(x, y)
            if r >= 0:
                masks.setdefault(regions.kinds[r] + " umbra", []).append((x, y))
    if caustic:
        # The caustic: pixels above 1% of the caustic view's brightest, grown by a pixel.
        top = max(sum(v) for row in caustic for v in row)
        lit = {(x, y) for y in range(height) for x in range(width) if sum(caustic[y][x]) > 0.01 * top}
        near = {(x + u, y + v) for x, y in lit for u in (-1, 0, 1) for v in (-1, 0, 1)}
        for kind in list(masks):
            dark = [p for p in masks[kind] if p not in near]
            if len(dark) < len(masks[kind]):
                masks[kind + " outside the caustic"] = dark
    ref_means = None
    for path, (w, h, rows) in images:
        if (w, h) != (width, height):
            sys.exit(f"{path}: {w}x{h}, the first image is {width}x{height}")
        means = {k: sum(sum(rows[y][x]) / 3.0 for x, y in px) / len(px) for k, px in masks.items()}
        parts = []
        for k in sorted(masks):
            part = f"{k} ({len(masks[k])} px) {means[k]:.6f}"
            if ref_means:
                part += f" ({100.0 * (means[k] / ref_means[k] - 1.0):+.2f}%)"
            parts.append(part)
        ref_means = ref_means or means
        print(f"{path}: " + "; ".join(parts))


if __name__ == "__main__":
    main()
