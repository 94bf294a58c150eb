#!/usr/bin/env python3
"""Writes docs/gallery.md from the --stats files of a gallery run."""
import json
import pathlib
import sys

FIGURES = {
    "fig01_depth": "Fig. 1: depth view of a mesh (near black, far white)",
    "fig02_phong": "Fig. 2: Phong spheres (ambient, diffuse, specular), no shadows",
    "fig03_shadows": "Fig. 3: the same with shadows",
    "fig04_reflection": "Fig. 4: a red ball reflected across a green plane by another ball",
    "fig05_reflective_mesh": "Fig. 5: a reflective mesh (teapot)",
    "fig06_thin_glass": "Fig. 6: a thin transparent cuboid in front of a red sphere",
    "fig07_glass_in_box": "Fig. 7: a transparent, reflective ball inside a partial cube",
    "fig08_through_mesh": "Fig. 8: a sphere seen through a transparent mesh",
    "fig09_intersecting": "Fig. 9: a yellow ball intersecting a transparent ball",
    "fig10_blue_glass": "Fig. 10: a blue transparent ball",
    "fig11_gate_shadows": "Figs. 11-12: shadows decided by the shadow photon map (two lights); photons.gate on, as the report rendered it (auto would cast every ray for point lights)",
    "fig12_gate_thin_wall": "Fig. 12: the gate next to a thin wall (photons from its far side do not vote); photons.gate on, as the report rendered it (auto would cast every ray for one point light)",
    "fig13_cornell_indirect": "Fig. 13: the indirect term alone (--aov indirect)",
    "fig14_cornell": "Fig. 14: Cornell-style box, indirect light replacing ambient",
    "fig15_globe": "Fig. 15: spherical texture mapping (textured globe)",
    "fig16_texture_add": "Fig. 16: texture added to the lit colour (the report's first attempt)",
    "fig17_texture_multiply": "Fig. 17: texture multiplying the lit colour (the report's fix)",
    "showcase": "Showcase: reflection, refraction, photon-mapped shadows and indirect light, teapot, textured planet",
    "cornell_physical": "Physical model: caustic and global maps, progressive passes",
    "environment_sky": "Physical model under an environment light",
    "soft_shadows": "Area lights' soft shadows, the gate voting per light stratum",
    "soft_shadows_physical": "The same in the physical model",
    "soft_shadows_dense": "A quad and a sphere light over a dense occluder and a thin wall, 64 samples",
    "teapot_1m": "A 1M-triangle teapot",
}
MAPS = ("shadow", "indirect", "caustic", "global")

out = pathlib.Path(sys.argv[1])
print("# Gallery\n")
print("Every scene in `scenes/`, rendered by `make gallery` (which wrote this file) on the")
print("project machine (2 cores). Times are wall-clock seconds for the whole render and")
print("its CPU share of 2 threads; photons are those stored, per map (over every pass);")
print("the contact sheet is `out/gallery/contact_sheet.png`.\n")
print("![showcase](showcase.png)\n")
print("![contact sheet](contact_sheet.png)\n")
print("| scene | shows | model | size | passes | time (s) | CPU share | photons stored | shadow rays cast / avoided |")
print("|---|---|---|---|---:|---:|---:|---|---|")
for stats_file in sorted(out.glob("*.json")):
    s = json.loads(stats_file.read_text())
    name = stats_file.stem
    p, g = s["photons"], s["gate"]
    stored = ", ".join(f"{m} {p['stored_' + m]:,}" for m in MAPS if p.get("stored_" + m, 0) > 0) or "none"
    print(f"| {name} | {FIGURES.get(name, '')} | {s['model']} | {s['image']['width']}x{s['image']['height']} "
          f"spp {s['image']['spp']} | {s.get('passes', 1)} | {s['time_s']['total']:.2f} | "
          f"{s.get('cpu_share', 0):.2f} | {stored} | "
          f"{g['shadow_rays_cast']:,} / {g['shadow_rays_avoided']:,} |")
