#!/usr/bin/env python3
"""Distance to the limit (issue 11 item 7): the share of each benchmarked render's time
spent inside Embree and nanoflann, from perf samples, against the raw library rates that
build/bench/profile_render measures on the same scene's rays and points in the same run.
Standard library only; needs `perf`.

  profile_render.py BUILD_DIR OUT_DIR

Method: `perf record -e task-clock -k CLOCK_MONOTONIC` (CPU-time samples, kernel time
included as [kernel.kallsyms], no call graphs) of
profile_render, which renders the scene 3 times and writes each render's
CLOCK_MONOTONIC window. Each sample inside a window is attributed by its own (self)
frame: Embree = samples in libembree3 plus the sphere user-geometry callbacks Embree
calls (penumbra's sphereIntersect/sphereOccluded/intersectSphere); nanoflann = symbols
named nanoflann:: (header-only, so by symbol; whatever the compiler inlined into a
penumbra function counts as penumbra, so this share is a lower bound). TraceScene's own
wrapper around each call (intersect/occluded: the ray checks and RTCRay fill) is shown
apart as "wrapper", and the KD facade around nanoflann (gather/kd_tree.cpp: parts, hints,
the packed result set, into which nanoflann's searchLevel may be inlined) as "facade":
both are ours, not the library's."""
import collections
import json
import os
import re
import subprocess
import sys

# (label, scene file, overrides): the three scenes of bench_render's BM_Scene* runs.
SCENES = [("glass box (fig07)", "fig07_glass_in_box.json", []),
          ("showcase", "showcase.json", []),
          ("cornell_physical 1 spp", "cornell_physical.json", ["camera.spp=1"])]
EMBREE_CALLBACKS = ("sphereIntersect", "sphereOccluded", "intersectSphere")
WRAPPER = ("TraceScene::intersect", "TraceScene::occluded", "embreeAccepts")
LINE = re.compile(r"^\s*(\d+\.\d+):\s+[0-9a-f]+\s+(.*?)\s+\(([^()]*)\)\s*$")


def category(sym, dso):
    base = os.path.basename(dso)
    if base.startswith("libembree3") or any(c in sym for c in EMBREE_CALLBACKS):
        return "embree"
    if "nanoflann::" in sym:
        return "nanoflann"
    if any(w in sym for w in WRAPPER):
        return "wrapper"
    if "PhotonKdTree<" in sym:
        return "facade"
    if base.startswith("libtbb"):
        return "tbb"
    if "kernel" in dso:
        return "kernel"
    return "other"


def samples(perf_data):
    out = subprocess.run(["perf", "script", "-i", perf_data, "-F", "time,ip,sym,dso"],
                         capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        m = LINE.match(line)
        if m:
            sym = re.sub(r"\+0x[0-9a-f]+$", "", m.group(2))
            yield float(m.group(1)), sym, m.group(3)


def attribute(perf_data, windows):
    """Per window kind ('whole', 'render'): category counts and the top other symbols."""
    counts = {w: collections.Counter() for w in ("whole", "render")}
    others = collections.Counter()
    for t, sym, dso in samples(perf_data):
        for r in windows:
            if r["t0"] <= t <= r["t1"]:
                cat = category(sym, dso)
                counts["whole"][cat] += 1
                if r["render_t0"] > 0 and t >= r["render_t0"]:
                    counts["render"][cat] += 1
                    if cat == "other":
                        others[sym[:70]] += 1
                break
    return counts, others


def raw_library_seconds(r, raw):
    """Render-phase library work at the raw rates: rays x ns per ray; gathers x ns per kNN
    through the facade the renderer calls, and through one plain nanoflann tree."""
    rays = (r["camera_rays"] * raw["camera_ns"] + r["shadow_rays"] * raw["shadow_ns"]
            + r["secondary_rays"] * raw["incoherent_ns"]) * 1e-9
    if "knn_global_ns" in raw:  # physical: one caustic and one global gather per diffuse hit
        knn = r["gathers"] * 0.5 * (raw["knn_global_ns"] + raw["knn_caustic_ns"]) * 1e-9
        plain = r["gathers"] * 0.5 * (raw["nanoflann_global_ns"] + raw["nanoflann_caustic_ns"]) * 1e-9
    else:
        # classic: gathers (fallbacks from the cache included) and exact gate votes
        knn = (r["gathers"] * raw.get("knn_indirect_ns", 0.0)
               + r["gate_queries"] * raw.get("knn_shadow_ns", 0.0)) * 1e-9
        plain = r["gathers"] * raw.get("nanoflann_indirect_ns", 0.0) * 1e-9
    return rays, knn, plain


def pct(c, cat):
    total = sum(c.values())
    return 100.0 * c[cat] / total if total else 0.0


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    build, out_dir = sys.argv[1:]
    os.makedirs(out_dir, exist_ok=True)
    src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    rows, notes = [], []
    for label, scene, overrides in SCENES:
        for threads in (1, 2):
            tag = f"{os.path.splitext(scene)[0]}-{threads}t"
            data, js = os.path.join(out_dir, tag + ".perf.data"), os.path.join(out_dir, tag + ".json")
            subprocess.run(["perf", "record", "-q", "-k", "CLOCK_MONOTONIC", "-e", "task-clock", "-F", "1999",
                            "-o", data, "--", os.path.join(build, "bench", "profile_render"),
                            os.path.join(src, "scenes", scene), str(threads), "3", js] + overrides,
                           check=True, stderr=subprocess.DEVNULL)
            with open(js) as f:
                run = json.load(f)
            counts, others = attribute(data, run["renders"])
            raw = run["raw"]
            r = min(run["renders"], key=lambda x: x["total_s"])
            ray_s, knn_s, plain_s = raw_library_seconds(r, raw)
            rows.append((label, threads, r, counts, raw, ray_s, knn_s, plain_s))
            top = ", ".join(f"{s} {100.0 * n / max(1, sum(counts['render'].values())):.1f}%"
                            for s, n in others.most_common(5))
            notes.append(f"- {label}, {threads}T, render phase, top non-library symbols: {top}")
    print("| render | T | total s | render s | perf: Embree | nanoflann | libraries (whole run) "
          "| render phase: Embree | nanoflann | libraries | wrapper | KD facade | at raw rates: rays s | kNN s | raw / render | kNN s, plain nanoflann |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for label, threads, r, c, raw, ray_s, knn_s, plain_s in rows:
        w, p = c["whole"], c["render"]
        print(f"| {label} | {threads} | {r['total_s']:.3f} | {r['render_s']:.3f} | "
              f"{pct(w, 'embree'):.1f}% | {pct(w, 'nanoflann'):.1f}% | "
              f"**{pct(w, 'embree') + pct(w, 'nanoflann'):.1f}%** | {pct(p, 'embree'):.1f}% | "
              f"{pct(p, 'nanoflann'):.1f}% | **{pct(p, 'embree') + pct(p, 'nanoflann'):.1f}%** | "
              f"{pct(p, 'wrapper'):.1f}% | {pct(p, 'facade'):.1f}% | "
              f"{ray_s:.3f} | {knn_s:.3f} | {(ray_s + knn_s) / r['render_s']:.2f} | {plain_s:.3f} |")
    print("\nRaw rates (same run, same thread count, ns of wall time per call):")
    for label, threads, r, c, raw, ray_s, knn_s, plain_s in rows:
        keys = [k for k in raw if k.endswith("_ns")]
        print(f"- {label}, {threads}T: " + ", ".join(f"{k[:-3]} {raw[k]:.0f} ns" for k in keys)
              + f"; render counts: {r['camera_rays']} camera, {r['shadow_rays']} shadow, "
              f"{r['secondary_rays']} secondary rays, {r['gathers']} gathers, {r['cache_lookups']} cache lookups")
    print()
    print("\n".join(notes))


if __name__ == "__main__":
    main()
