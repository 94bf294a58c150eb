#!/usr/bin/python3
"""Writes the smoke puff scenes/smoke.json renders: a float grid "density" of a few
thousand voxels, a ball of value noise fading to 0 at its rim. Deterministic values
(a fixed integer hash, no random module); OpenVDB stamps each file with a fresh UUID,
so only the bytes of the header differ between runs.

Usage: /usr/bin/python3 scripts/make_smoke_vdb.py [out.vdb] [--size N]
Needs Debian's python3-openvdb (pyopenvdb), which lives in /usr/bin/python3's path.
"""
import argparse
import math

import pyopenvdb as vdb


def hash01(i, j, k, seed):
    # A 32-bit integer hash of the lattice point: the same noise on every machine.
    h = (i * 73856093) ^ (j * 19349663) ^ (k * 83492791) ^ (seed * 2654435761)
    h &= 0xFFFFFFFF
    h = ((h >> 16) ^ h) * 0x45D9F3B & 0xFFFFFFFF
    h = ((h >> 16) ^ h) * 0x45D9F3B & 0xFFFFFFFF
    return ((h >> 16) ^ h) / 0xFFFFFFFF


def value_noise(x, y, z, seed):
    # Trilinear value noise with smoothstep weights.
    ix, iy, iz = math.floor(x), math.floor(y), math.floor(z)
    fx, fy, fz = x - ix, y - iy, z - iz
    sx, sy, sz = (f * f * (3 - 2 * f) for f in (fx, fy, fz))
    total = 0.0
    for dx in (0, 1):
        for dy in (0, 1):
            for dz in (0, 1):
                w = (sx if dx else 1 - sx) * (sy if dy else 1 - sy) * (sz if dz else 1 - sz)
                total += w * hash01(ix + dx, iy + dy, iz + dz, seed)
    return total


def density(x, y, z, n):
    # x, y, z in voxels from the centre; a ball of radius ~n/2 with two octaves of noise.
    r = math.sqrt(x * x + y * y + z * z) / (0.5 * n)
    noise = 0.65 * value_noise(x / 4.0, y / 4.0, z / 4.0, 1) + 0.35 * value_noise(x / 2.0, y / 2.0, z / 2.0, 2)
    d = (1.0 - r) * 1.6 + (noise - 0.5) * 1.2
    return max(0.0, min(1.0, d))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default="scenes/smoke.vdb")
    parser.add_argument("--size", type=int, default=24, help="voxels across the puff")
    parser.add_argument("--voxel", type=float, default=0.05, help="voxel size in scene units")
    args = parser.parse_args()
    n = args.size
    grid = vdb.FloatGrid()
    grid.name = "density"
    grid.gridClass = vdb.GridClass.FOG_VOLUME
    grid.transform = vdb.createLinearTransform(voxelSize=args.voxel)
    acc = grid.getAccessor()
    # Index 0..n-1 on each axis: n = 24 fills 3 x 3 x 3 of OpenVDB's 8^3 leaves exactly.
    c = 0.5 * (n - 1)
    for i in range(n):
        for j in range(n):
            for k in range(n):
                d = density(i - c, j - c, k - c, n)
                if d > 0.0:
                    acc.setValueOn((i, j, k), d)
    grid.saveFloatAsHalf = True  # half the bytes; smoke needs no more than 11 bits
    vdb.write(args.out, grids=[grid])
    print(f"{args.out}: {grid.activeVoxelCount()} voxels, box {grid.evalActiveVoxelBoundingBox()}")


if __name__ == "__main__":
    main()
