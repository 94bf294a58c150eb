#!/usr/bin/env python3
"""Google Benchmark JSON (BENCH_OUT/*.json) -> the markdown tables of `make bench`
(figure, 1T, 2T, speed-up, target) and `make scaling` (per scene and stage).
Standard library only.  Usage: bench_table.py {bench|scaling} RESULTS_DIR"""
import glob
import json
import os
import re
import sys

SCENES = [("GlassBox", "glass box (fig07, Whitted)"), ("Showcase", "showcase (precomputed)"),
          ("CornellPhysical", "cornell_physical, 1 spp (exact gathers)")]
RAY_SCENES = [("glass_box", "glass box"), ("showcase", "showcase"), ("cornell_physical", "cornell_physical")]
GATE_SCENES = [("SoftShadows/samples:16", "soft_shadows, 16 samples"),
               ("SoftShadows/samples:64", "soft_shadows, 64 samples"),
               ("SoftShadowsPhysical/samples:16", "soft_shadows_physical, 16 samples"),
               ("SoftShadowsPhysical/samples:64", "soft_shadows_physical, 64 samples"),
               ("SoftShadowsDense", "soft_shadows_dense, 64 samples")]
# (off - on) / (off - ceiling); avoided / the ungated render's shadow rays; gated vs
# ungated RMSE over the image mean; (auto - 0.05 s) / off.
GATE_FIGURES = [("saving realised", "realised", "share", ("min", 0.90)),
                ("shadow rays avoided", "rays_avoided", "share", ("min", 0.95)),
                ("RMSE / image mean", "rmse_of_mean", "share", ("max", 0.005)),
                ("auto over off", "auto_over_off", "ratio", ("max", 1.10))]
# (figure, name regex with {T} for the thread count, value, unit, scale, target): value is
# "rate" (items/s), "time" (s) or "counter:NAME"; target a 2T/1T speed-up, or ("max", v)
# / ("min", v) for a bound every thread count must stay within.
FIGURES = (
    [(f"Embree {kind} rays, {label}", rf"^Rays/{key}/{kind}/threads:{{T}}/", "rate", "Mrays/s", 1e-6, None)
     for key, label in RAY_SCENES for kind in ("camera", "shadow", "incoherent")]
    + [("Photon emission, fig14 5M+5M", r"^BM_EmitCornell/{T}/", "rate", "Mphotons/s", 1e-6, 1.9),
       ("Map build, fig14 (both maps)", r"^BM_BuildMapsCornell/{T}/", "time", "s", 1.0, 1.8),
       ("Photon pass, fig14 (emission + both maps)", r"^BM_PhotonPassCornell/{T}/", "time", "s", 1.0, None),
       ("kNN k=50, 1M photons, scan-line", r"^Knn50/1M/.*morton:1/leaf:48/threads:{T}/shuffled:0", "rate",
        "kqueries/s", 1e-3, None),
       ("Gate classify k=50, 1M photons", r"^Classify/1M/.*morton:1/leaf:48/threads:{T}/shuffled:0", "rate",
        "kqueries/s", 1e-3, None)]
    + [(f"Render {label}", rf"^BM_Scene{key}/threads:{{T}}/", "time", "s", 1.0, 1.9) for key, label in SCENES]
    + [("Control: compute only (the machine's ceiling)", r"^BM_ControlCompute/threads:{T}/", "time", "s", 1.0,
        None)]
    + [("glTF load, 1M triangles (loadScene + BVH)", r"^BM_LoadGltf1M/threads:{T}/", "time", "s", 1.0, ("max", 2.0)),
       ("glTF load, peak memory per triangle (BVH included)", r"^BM_LoadGltf1M/threads:{T}/",
        "counter:peak_B_per_tri", "B", 1.0, ("max", 100.0)),
       ("glTF load, memory held per triangle (scene + BVH)", r"^BM_LoadGltf1M/threads:{T}/",
        "counter:held_B_per_tri", "B", 1.0, None)]
    # The gate against the frame's ceiling (bench_gate: 2 threads only, the 2T column).
    + [(f"Gate, {label}: {what}", rf"^BM_Gate{key}/threads:{{T}}/", f"counter:{counter}", unit, 1.0, target)
       for key, label in GATE_SCENES for what, counter, unit, target in GATE_FIGURES])
STAGES = [("load_s", "load + BVH"), ("emit_s", "photon emission"), ("maps_s", "map build"),
          ("precompute_s", "lookup precompute"), ("render_s", "render (tiles)"), ("total_s", "total")]


def load(results):
    runs, context = [], {}
    for path in sorted(glob.glob(os.path.join(results, "*.json"))):
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, ValueError):
            continue
        if "benchmarks" not in data:
            continue
        context = data.get("context", context)
        runs += [b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"]
    return runs, context


def seconds(run):
    scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[run.get("time_unit", "ns")]
    return run["real_time"] * scale


def find(runs, pattern, threads):
    """The fastest repetition of a benchmark (the shared machine only ever slows a run)."""
    rx = re.compile(pattern.replace("{T}", str(threads)))
    matches = [r for r in runs if rx.search(r["name"])]
    return min(matches, key=seconds) if matches else None


def share(run):
    return "-" if run is None or "cpu_share" not in run else f"{run['cpu_share']:.2f}"


def fmt(v):
    return "-" if v is None else f"{v:.3g}" if v < 100 else f"{v:.0f}"


def bench_table(runs):
    out = ["| figure | unit | 1T | 2T | speed-up | target | CPU share 1T / 2T |",
           "|---|---|---:|---:|---:|---|---|"]
    for figure, pattern, kind, unit, scale, target in FIGURES:
        vals, found = [], []
        for t in (1, 2):
            r = find(runs, pattern, t)
            found.append(r)
            if r is None:
                vals.append(None)
            elif kind == "rate":
                vals.append(r.get("items_per_second", 0.0) * scale)
            elif kind.startswith("counter:"):
                vals.append(r.get(kind[len("counter:"):], 0.0) * scale)
            else:
                vals.append(seconds(r) * scale)
        if vals == [None, None]:
            continue
        speedup = None
        if None not in vals and min(vals) > 0 and not kind.startswith("counter:"):
            speedup = vals[1] / vals[0] if kind == "rate" else vals[0] / vals[1]
        verdict = ""
        if isinstance(target, tuple) and target[0] == "min":
            worst = min(v for v in vals if v is not None)
            verdict = f">= {target[1]:g} {unit}: " + ("met" if worst >= target[1] else "**not met**")
        elif isinstance(target, tuple):
            worst = max(v for v in vals if v is not None)
            verdict = f"<= {target[1]:g} {unit}: " + ("met" if worst <= target[1] else "**not met**")
        elif target is not None:
            verdict = f">= {target}: " + ("-" if speedup is None else "met" if speedup >= target else "**not met**")
        out.append(f"| {figure} | {unit} | {fmt(vals[0])} | {fmt(vals[1])} | "
                   f"{'-' if speedup is None else f'{speedup:.2f}'} | {verdict} | {share(found[0])} / {share(found[1])} |")
    return out


def scaling_table(runs):
    out = ["| scene | stage | 1T s | 2T s | speed-up | CPU share 1T / 2T |", "|---|---|---:|---:|---:|---|"]
    # The control first: what this run's two vCPUs gave register-only arithmetic.
    r1, r2 = (find(runs, rf"^BM_ControlCompute/threads:{t}/", t) for t in (1, 2))
    if r1 and r2:
        a, b = seconds(r1), seconds(r2)
        out.append(f"| control (compute only) | the machine's ceiling | {a:.3f} | {b:.3f} | {a / b:.2f} | "
                   f"{share(r1)} / {share(r2)} |")
    # Stages of the fastest repetition of each (the fastest total).
    for key, label in SCENES:
        r1, r2 = (find(runs, rf"^BM_Scene{key}/threads:{t}/", t) for t in (1, 2))
        if not r1 or not r2:
            continue
        for stage, name in STAGES:
            a, b = r1.get(stage, 0.0), r2.get(stage, 0.0)
            if a < 1e-3 and b < 1e-3:
                continue  # a stage this scene does not have
            sp = f"{a / b:.2f}" if b > 0 else "-"
            out.append(f"| {label} | {name} | {a:.3f} | {b:.3f} | {sp} | {share(r1)} / {share(r2)} |")
    for figure, pattern in (("emission (trace + store)", r"^BM_EmitCornell/{T}/"),
                            ("both maps built", r"^BM_BuildMapsCornell/{T}/"),
                            ("emission + both maps", r"^BM_PhotonPassCornell/{T}/")):
        r1, r2 = find(runs, pattern, 1), find(runs, pattern, 2)
        if r1 and r2:
            a, b = seconds(r1), seconds(r2)
            out.append(f"| fig14 photon pass, 5M+5M | {figure} | {a:.3f} | {b:.3f} | {a / b:.2f} | "
                       f"{share(r1)} / {share(r2)} |")
    return out


def main():
    if len(sys.argv) != 3 or sys.argv[1] not in ("bench", "scaling"):
        sys.exit(__doc__)
    runs, ctx = load(sys.argv[2])
    if not runs:
        sys.exit(f"no benchmark JSON in {sys.argv[2]}")
    lines = bench_table(runs) if sys.argv[1] == "bench" else scaling_table(runs)
    print("\n".join(lines))
    reps = max((r.get("repetitions", 1) for r in runs), default=1)
    print(f"\nBest of {reps} repetition(s), 1T and 2T interleaved. CPU share = process CPU time / "
          "(wall x threads): well below 1 means other work had the cores and the speed-up is the load's.")
    print(f"{ctx.get('date', '')}, {ctx.get('num_cpus', '?')} CPUs, load average at start "
          f"{ctx.get('loadavg_at_start', '?')}, penumbra build "
          f"{ctx.get('penumbra_build_type', '?')}; libbenchmark reports "
          f"'{ctx.get('library_build_type', '?')}' (Debian compiles it without NDEBUG; "
          f"our code's flags are the penumbra build's). JSON: {sys.argv[2]}/")


if __name__ == "__main__":
    main()
