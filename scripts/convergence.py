#!/usr/bin/python3
"""Error against CPU time for the physical model on one scene.

Renders the scene at a ladder of progressive passes, compares every image with a
reference (RMSE over all pixels and RGB channels, linear radiance, as OpenImageIO's
compare; and over the caustic: the pixels where the reference's caustic view is
above 1% of its brightest) and writes a CSV table, a Markdown table and a log-log
plot. Used for docs/PERFORMANCE.md ("Physical model: convergence"):

  scripts/convergence.py build/penumbra scenes/cornell_physical.json out/convergence
      [--reference REF.exr --caustic-reference CAUSTIC.exr] [--threads 2]

Without the references they are rendered first and kept in the output folder: the
mean of two renders (seeds 1 and 2) of 256 passes of 2M global + 2M caustic photons
at spp 1 (about an hour on two cores), and the caustic view, 16 passes of 2M caustic
photons.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

# (passes, spp, global photons per pass, caustic photons per pass): the scene's own
# budgets, one new camera sample per pass.
LADDER = [(p, 1, 200_000, 200_000) for p in (1, 2, 4, 8, 16, 32, 64)]
REFERENCE = (256, 1, 2_000_000, 2_000_000)
REFERENCE_SEEDS = (1, 2)
CAUSTIC_REFERENCE = (16, 1, 0, 2_000_000)
CAUSTIC_SHARE = 0.01  # of the caustic view's brightest pixel


def render(binary, scene, out, config, threads, aov=None, seed=None):
    passes, spp, global_photons, caustic = config
    stats = out + ".json"
    cmd = [binary, "render", scene, "-o", out, "-q", "--threads", str(threads), "--stats", stats,
           "--set", f"photons.passes={passes}", "--set", f"camera.spp={spp}",
           "--set", f"photons.global={global_photons}", "--set", f"photons.caustic={caustic}"]
    if aov:
        cmd += ["--aov", aov]
    if seed is not None:
        cmd += ["--set", f"render.seed={seed}"]
    subprocess.run(cmd, check=True)
    with open(stats) as f:
        return json.load(f)


def pixels(path):
    """RGB of every pixel, row by row, from oiiotool --dumpdata ("Pixel (x, y): r g b ...")."""
    out = subprocess.run(["oiiotool", "--dumpdata", path], capture_output=True, text=True, check=True).stdout
    return [tuple(float(v) for v in line.split("):")[1].split()[:3]) for line in out.splitlines()[1:]]


def rmse(image, reference, mask=None):
    squares, n = 0.0, 0
    for i, (a, b) in enumerate(zip(image, reference)):
        if mask is None or mask[i]:
            squares += sum((x - y) ** 2 for x, y in zip(a, b))
            n += 1
    return math.sqrt(squares / (3 * max(n, 1)))


def caustic_mask(caustic_view):
    lum = [0.2126 * r + 0.7152 * g + 0.0722 * b for r, g, b in caustic_view]
    top = max(lum)
    return [v > CAUSTIC_SHARE * top for v in lum]


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog([r["cpu_s"] for r in rows], [r["rmse"] for r in rows], "o-", label="penumbra physical")
    for r in rows:
        ax.annotate(f'{r["passes"]}p', (r["cpu_s"], r["rmse"]), textcoords="offset points",
                    xytext=(4, 4), fontsize=8)
    first = rows[min(2, len(rows) - 1)]
    cpu = [first["cpu_s"], rows[-1]["cpu_s"]]
    ax.loglog(cpu, [first["rmse"] * (c / cpu[0]) ** (-1 / 3) for c in cpu], color="grey", ls="--", lw=0.8,
              label="(CPU time)^-1/3")
    ax.set_xlabel("CPU seconds")
    ax.set_ylabel("RMSE vs converged render")
    ax.set_title("cornell_physical: error against time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("scene")
    ap.add_argument("outdir")
    ap.add_argument("--reference")
    ap.add_argument("--caustic-reference")
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    reference = args.reference or os.path.join(args.outdir, "reference.exr")
    if not os.path.exists(reference):
        # Two seeds' mean: half the noise of one (the k-nearest estimates' noise does
        # not fall with more photons a pass, only with more passes).
        halves = [os.path.join(args.outdir, f"reference_seed{s}.exr") for s in REFERENCE_SEEDS]
        for seed, half in zip(REFERENCE_SEEDS, halves):
            render(args.binary, args.scene, half, REFERENCE, args.threads, seed=seed)
        subprocess.run(["oiiotool", *halves, "--add", "--mulc", "0.5", "-o", reference], check=True)
    caustic = args.caustic_reference or os.path.join(args.outdir, "reference_caustic.exr")
    if not os.path.exists(caustic):
        render(args.binary, args.scene, caustic, CAUSTIC_REFERENCE, args.threads, aov="caustic")
    ref = pixels(reference)
    mask = caustic_mask(pixels(caustic))
    rows = []
    for config in LADDER:
        out = os.path.join(args.outdir, "p{}_s{}_g{}_c{}.exr".format(*config))
        stats = render(args.binary, args.scene, out, config, args.threads)
        t = stats["time_s"]
        image = pixels(out)
        row = {"passes": config[0], "spp": config[1], "global": config[2], "caustic": config[3],
               "cpu_s": round(stats["cpu_s"], 2), "total_s": round(t["total"], 3), "emit_s": round(t["emit"], 3),
               "maps_s": round(t["build_maps"], 3), "render_s": round(t["render"], 3),
               "rmse": round(rmse(image, ref), 5), "caustic_rmse": round(rmse(image, ref, mask), 4)}
        rows.append(row)
        print(row, flush=True)
    with open(os.path.join(args.outdir, "convergence.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.outdir, "convergence.md"), "w") as f:
        f.write("| passes | spp/pass | global/pass | caustic/pass | CPU s | total s | emit s | maps s | render s "
                "| RMSE | caustic RMSE |\n")
        f.write("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f.write("| {passes} | {spp} | {global} | {caustic} | {cpu_s} | {total_s} | {emit_s} | {maps_s} | "
                    "{render_s} | {rmse} | {caustic_rmse} |\n".format(**r))
    plot(rows, os.path.join(args.outdir, "convergence.png"))


if __name__ == "__main__":
    main()
