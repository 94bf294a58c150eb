#!/usr/bin/env python3
"""Error against time of a penumbra sweep (results.csv -> tradeoff.png).

Log axes: each run's standalone time (total_s, or with --cost cpu its CPU seconds,
total_cpu_s, as penumbra sweep draws it when its runs were contended) against its error under --metric
(relmse by default; psnr is drawn as the RMSE of clamped values it comes from).
Every run is a grey dot; one series per varied knob joins the runs that vary only
that knob, every other knob at the best run's value (the lowest error), so each
series shows what that knob buys around the best setting; the Pareto front (runs
no other run beats on both time and error) is the black staircase. The reference
(error 0) cannot sit on a log axis and is left out.

Usage: plot_tradeoff.py results.csv tradeoff.png [--title TITLE] [--metric NAME] [--cost wall|cpu]
"""
import argparse
import csv
import os
import sys


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def knob_order(values):
    """Values sorted numerically when they all are numbers, else as given."""
    unique = list(dict.fromkeys(values))
    if all(number(v) is not None for v in unique):
        return sorted(unique, key=number)
    return unique


# The error each metric ranks by, lower better, and its axis label.
METRICS = {
    "relmse": (lambda r: float(r["rel_mse"]), "relative MSE against the reference"),
    "rmse": (lambda r: float(r["rmse"]), "RMSE against the reference"),
    "psnr": (lambda r: 10.0 ** (-float(r["psnr"]) / 20.0), "RMSE of values clamped to [0, 1] (PSNR's)"),
    "rmse-clamped": (lambda r: 10.0 ** (-float(r["psnr"]) / 20.0), "RMSE of values clamped to [0, 1]"),
}


# What the time axis reads: wall seconds, or CPU seconds where other work shared the cores.
COSTS = {
    "wall": ("total_s", "time of the run as a standalone render (s)"),
    "cpu": ("total_cpu_s", "CPU time of the run as a standalone render (CPU s)"),
}


def pareto(points):
    front, best = [], float("inf")
    for t, e, row in sorted(points, key=lambda p: (p[0], p[1])):
        if e < best:
            front.append((t, e, row))
            best = e
    return front


# Exit codes penumbra sweep tells apart: data it cannot plot (the message says why),
# and matplotlib missing.
NOTHING_TO_PLOT, NO_MATPLOTLIB = 2, 3


def fail(message):
    print(message, file=sys.stderr)
    sys.exit(NOTHING_TO_PLOT)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--title", default=None)
    parser.add_argument("--metric", default="relmse", choices=sorted(METRICS))
    parser.add_argument("--cost", default="wall", choices=sorted(COSTS))
    args = parser.parse_args()

    with open(args.csv, newline="") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        rows = list(reader)
    if "run" not in header or "reference" not in header:
        fail(f"{args.csv}: not a penumbra sweep results.csv")
    knobs = header[header.index("run") + 1:header.index("reference")]
    error, ylabel = METRICS[args.metric]
    column, xlabel = COSTS[args.cost]
    if column not in header:
        fail(f"{args.csv}: has no {column} column (written by an older penumbra)")
    cost = lambda r: float(r[column])
    runs = [r for r in rows if r["reference"] != "1" and error(r) > 0.0]
    if not runs:
        fail(f"{args.csv}: no run with a positive error to plot (every run matches the reference)")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib cannot be imported (python3-matplotlib: make deps installs it)", file=sys.stderr)
        sys.exit(NO_MATPLOTLIB)

    fig, ax = plt.subplots(figsize=(7.5, 5.0), dpi=120)
    ax.scatter([cost(r) for r in runs], [error(r) for r in runs],
               s=14, color="0.75", zorder=1, label="every run")
    orders = {k: knob_order([r[k] for r in rows]) for k in knobs}
    best = min(runs, key=error)
    markers = "osD^vP*X"
    for i, knob in enumerate(knobs):
        if len(orders[knob]) < 2:
            continue
        series = [r for r in runs if all(r[o] == best[o] for o in knobs if o != knob)]
        series.sort(key=lambda r: orders[knob].index(r[knob]))
        if len(series) < 2:
            continue
        xs = [cost(r) for r in series]
        ys = [error(r) for r in series]
        line, = ax.plot(xs, ys, marker=markers[i % len(markers)], zorder=3, label=f"{knob} (others as the best run)")
        for x, y, r in zip(xs, ys, series):
            ax.annotate(r[knob], (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7,
                        color=line.get_color())
    front = pareto([(cost(r), error(r), r) for r in runs])
    ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black", linewidth=1.2,
            zorder=2, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    title = args.title or os.path.basename(os.path.dirname(os.path.abspath(args.csv)))
    ax.set_title(f"{title}: error against time")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = args.png + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, args.png)  # never a half-written plot


if __name__ == "__main__":
    main()
