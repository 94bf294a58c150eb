#!/usr/bin/env python3
"""Jobs files of the farm test and bench: written from a template, appended to, and read back.

  jobs_file.py write TEMPLATE SCENES_DIR [--no-tiles] [--scale N] [KEY=VALUE...] > jobs.json
      (@SCENES@ -> SCENES_DIR; --scale multiplies every camera.width and camera.height the
      file sets, its jobs' too; each KEY=VALUE is added to the top-level set)
  jobs_file.py append JOBS SCENE                                   (one job: out/{name}.png)
  jobs_file.py untile JOBS NAME > whole.json           (job NAME alone, without "tiles")
"""
import json
import sys


def scaled(sets, factor):
    out = []
    for s in sets:
        key, _, value = s.partition("=")
        out.append(f"{key}={int(float(value)) * factor}" if key in ("camera.width", "camera.height") else s)
    return out


def write(template, scenes, *args):
    doc = json.loads(open(template).read().replace("@SCENES@", scenes))
    if "--no-tiles" in args:  # for a binary without the "tiles" key
        doc["jobs"] = [j for j in doc["jobs"] if "tiles" not in j]
    if "--scale" in args:  # the same jobs at a farm's size
        at = args.index("--scale") + 1
        if at >= len(args) or not args[at].isdigit() or int(args[at]) < 1:
            sys.exit("jobs_file.py write: --scale takes a whole number, at least 1")
        factor = int(args[at])
        doc["set"] = scaled(doc.get("set", []), factor)
        for job in doc["jobs"]:
            if "set" in job:
                job["set"] = scaled(job["set"], factor)
    doc["set"] = doc.get("set", []) + [a for a in args if "=" in a]
    json.dump(doc, sys.stdout, indent=1)
    print()


def append(path, scene):
    doc = json.load(open(path))
    doc["jobs"].append({"scene": scene, "output": "out/{name}.png"})
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)


def untile(path, name):
    doc = json.load(open(path))
    doc["jobs"] = [dict((k, v) for k, v in j.items() if k != "tiles") for j in doc["jobs"] if j.get("name") == name]
    if not doc["jobs"]:
        sys.exit(f"{path}: no job named {name}")
    json.dump(doc, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    commands = {"write": write, "append": append, "untile": untile}
    if len(sys.argv) < 2 or sys.argv[1] not in commands:
        sys.exit(__doc__)
    commands[sys.argv[1]](*sys.argv[2:])
