#!/usr/bin/python3
"""Error against wall time for the physical model on one scene.

Renders the scene at a ladder of progressive settings, compares every image with a
reference through OpenImageIO's compare (oiiotool --diff: RMSE over all pixels and
RGB channels, linear radiance) and writes a CSV table, a Markdown table and a
log-log plot. Used for docs/PERFORMANCE.md ("Physical model: convergence"):

  scripts/convergence.py build/penumbra scenes/cornell_physical.json out/convergence
      [--reference REF.exr] [--threads 2]

Without --reference, the reference is rendered first (256 passes, 1 spp each,
200k global + 400k caustic photons a pass) and kept in the output folder.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

# (passes, spp, global photons per pass, caustic photons per pass)
LADDER = [
    (1, 1, 50_000, 50_000),
    (2, 1, 100_000, 100_000),
    (4, 1, 100_000, 200_000),
    (8, 1, 100_000, 200_000),
    (16, 1, 100_000, 200_000),
    (32, 1, 100_000, 200_000),
    (64, 1, 100_000, 200_000),
]
REFERENCE = (256, 1, 200_000, 400_000)


def render(binary, scene, out, config, threads):
    passes, spp, global_photons, caustic = config
    stats = out + ".json"
    cmd = [binary, "render", scene, "-o", out, "-q", "--threads", str(threads), "--stats", stats,
           "--set", f"photons.passes={passes}", "--set", f"camera.spp={spp}",
           "--set", f"photons.global={global_photons}", "--set", f"photons.caustic={caustic}"]
    subprocess.run(cmd, check=True)
    with open(stats) as f:
        return json.load(f)


def rmse(image, reference):
    # oiiotool --diff runs ImageBufAlgo::compare; exit status 1 only means "differs".
    res = subprocess.run(["oiiotool", image, reference, "--diff"], capture_output=True, text=True)
    m = re.search(r"RMS error = ([0-9.eE+-]+)", res.stdout)
    if not m:
        sys.exit("cannot read oiiotool --diff output:\n" + res.stdout + res.stderr)
    return float(m.group(1))


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.loglog([r["total_s"] for r in rows], [r["rmse"] for r in rows], "o-", label="penumbra physical")
    for r in rows:
        ax.annotate(f'{r["passes"]}p', (r["total_s"], r["rmse"]), textcoords="offset points",
                    xytext=(4, 4), fontsize=8)
    ax.axhline(0.045, color="grey", ls="--", lw=0.8, label="target RMSE 0.045")
    ax.axvline(20, color="grey", ls=":", lw=0.8, label="20 s")
    ax.set_xlabel("wall time on 2 threads [s]")
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
    ap.add_argument("--threads", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    reference = args.reference or os.path.join(args.outdir, "reference.exr")
    if not os.path.exists(reference):
        render(args.binary, args.scene, reference, REFERENCE, args.threads)
    rows = []
    for config in LADDER:
        out = os.path.join(args.outdir, "p{}_s{}_g{}_c{}.exr".format(*config))
        stats = render(args.binary, args.scene, out, config, args.threads)
        t = stats["time_s"]
        row = {"passes": config[0], "spp": config[1], "global": config[2], "caustic": config[3],
               "total_s": round(t["total"], 3), "emit_s": round(t["emit"], 3),
               "maps_s": round(t["build_maps"], 3), "render_s": round(t["render"], 3),
               "rmse": round(rmse(out, reference), 5)}
        rows.append(row)
        print(row, flush=True)
    with open(os.path.join(args.outdir, "convergence.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.outdir, "convergence.md"), "w") as f:
        f.write("| passes | spp/pass | global/pass | caustic/pass | total s | emit s | maps s | render s | RMSE |\n")
        f.write("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in rows:
            f.write("| {passes} | {spp} | {global} | {caustic} | {total_s} | {emit_s} | {maps_s} | "
                    "{render_s} | {rmse} |\n".format(**r))
    plot(rows, os.path.join(args.outdir, "convergence.png"))


if __name__ == "__main__":
    main()
