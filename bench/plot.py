#!/usr/bin/env python3
"""Turns the JSON of bench_step and bench_rays (--json) into PNG charts with
gnuplot (Debian: gnuplot-nox).

    python3 bench/plot.py --out bench/plots bench/raw/*.json

Charts (those whose data the inputs hold):
  ms_per_step.png          frame time (median, bar up to p99) against ray budget,
                           per scene and backend, with the paper's three Unity points
  casts_per_second_vs_budget.png
                           the backends' casts per second against ray budget
  casts_per_second_vs_triangles.png
                           rays per second against triangle count: soundpaint's
                           closest_hit, Embree, and the two backends stepping
  bvh_build_vs_triangles.png
                           BVH build time against triangle count

Generated levels (gen:N) are joined by lines; scenes from files are single
points. Python 3 standard library only.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"]
BUDGET_TICS = [(0.5, "0"), (1, "1"), (10, "10"), (100, "100"), (500, "500"), (2500, "2500"),
               (10000, "10k"), (100000, "100k"), (1000000, "1M")]


def scene_label(spec):
    if spec.startswith("gen:"):
        return "generated %s" % spec[4:]
    return os.path.splitext(os.path.basename(spec))[0]


def budget_x(budget):
    return budget if budget > 0 else 0.5  # a log axis has no 0


class Chart:
    """One gnuplot chart: data blocks plus plot clauses."""

    def __init__(self, name, title, xlabel, ylabel, xformat="%.0s%c", yformat="%g"):
        self.name, self.title, self.xlabel, self.ylabel = name, title, xlabel, ylabel
        self.settings = ["set logscale xy", "set grid xtics ytics mxtics mytics lc rgb '#dddddd'",
                         "set format x '%s'" % xformat, "set format y '%s'" % yformat]
        self.blocks, self.clauses, self.xs = [], [], []

    def series(self, rows, title, style):
        """rows: tuples of numbers, one per point; style: gnuplot 'using ... with ...';
        title None: not in the key."""
        if not rows:
            return
        block = "$d%d" % len(self.blocks)
        body = "\n".join(" ".join("%.9g" % v for v in row) for row in rows)
        self.blocks.append("%s << EOD\n%s\nEOD" % (block, body))
        key = "notitle" if title is None else "title '%s'" % title.replace("'", "")
        self.clauses.append("%s %s %s" % (block, style, key))
        self.xs += [row[0] for row in rows]

    def script(self, path):
        lines = ["set terminal pngcairo size 1100,800 noenhanced font 'DejaVu Sans,11'",
                 "set output '%s'" % path, "set title '%s'" % self.title,
                 "set xlabel '%s'" % self.xlabel, "set ylabel '%s'" % self.ylabel,
                 "set key below left Left reverse maxcols 2 spacing 1.1 height 1.5", "set xlabel offset 0,-0.5",
                 "set xrange [%g:%g]" % (min(self.xs) / 1.6, max(self.xs) * 1.6)]
        return "\n".join(self.blocks + lines + self.settings + ["plot " + ", \\\n  ".join(self.clauses)]) + "\n"


def step_charts(documents):
    time_chart = Chart("ms_per_step", "Frame cost of soundpaint against ray budget "
                       "(paper workload: 15 sources, every 0.25 s; bars reach p99)",
                       "rays per step (budget)", "ms per frame (set_listener + step)")
    rate_chart = Chart("casts_per_second_vs_budget", "Backends: casts per second against ray budget",
                       "rays per step (budget)", "casts per second", yformat="%.0s%c")
    for chart in (time_chart, rate_chart):
        chart.settings.append("set xtics (%s)" % ", ".join('"%s" %g' % (label, x) for x, label in BUDGET_TICS))
    colour = 0
    for doc in documents:
        scene = scene_label(doc["scene"]["spec"])
        for backend in sorted({r["backend"] for r in doc["results"]}):
            rows = sorted((r for r in doc["results"] if r["backend"] == backend), key=lambda r: r["budget"])
            c = COLOURS[colour % len(COLOURS)]
            colour += 1
            device = rows[0]["device"].split(", driver")[0].split(" (")[0]
            time_chart.series([(budget_x(r["budget"]), r["ms_per_step_median"], r["ms_per_step_median"],
                                r["ms_per_step_p99"]) for r in rows],
                              "%s, %s (%s): wall median" % (scene, backend, device),
                              "using 1:2:3:4 with yerrorlines lw 2 pt 7 lc rgb '%s'" % c)
            gpu = [(budget_x(r["budget"]), r["gpu_ms_per_step_median"]) for r in rows
                   if r.get("gpu_ms_per_step_median") is not None and r["gpu_ms_per_step_median"] > 0]
            time_chart.series(gpu, "%s, %s: GPU timestamps median" % (scene, backend),
                              "using 1:2 with linespoints dt 2 lw 1.5 pt 6 lc rgb '%s'" % c)
            rate_chart.series([(r["budget"], r["casts_per_second"]) for r in rows if r["budget"] > 0],
                              "%s, %s (%s)" % (scene, backend, device),
                              "using 1:2 with linespoints lw 2 pt 7 lc rgb '%s'" % c)
    paper = {}
    for doc in documents:
        paper.update({int(k): v for k, v in doc.get("paper_unity_overhead_ms", {}).items()})
    time_chart.series(sorted(paper.items()), "paper (Unity, frame-time overhead incl. rendering)",
                      "using 1:2 with points pt 5 ps 2.2 lc rgb 'black'")
    return [time_chart, rate_chart]


def ray_charts(documents):
    files = "lines: generated levels; triangles: scene files"
    rate_chart = Chart("casts_per_second_vs_triangles", "Rays per second against triangle count (%s)" % files,
                       "triangles", "rays (casts) per second", yformat="%.0s%c")
    build_chart = Chart("bvh_build_vs_triangles", "BVH build time against triangle count (%s)" % files,
                        "triangles", "build ms")
    casts, builds = {}, {}  # label -> [(triangles, value, generated)]
    for doc in documents:
        threads = doc["settings"]["threads"]
        for scene in doc["scenes"]:
            generated = scene["spec"].startswith("gen:")
            point = lambda value: (scene["triangles"], value, generated)
            for cast in scene["casts"]:
                casts.setdefault("%s (%d threads)" % (cast["caster"], threads), []).append(
                    point(cast["rays_per_second"]))
            for backend in scene.get("backends", []):
                casts.setdefault("%s backend stepping, %d rays/step" % (backend["backend"], backend["budget"]),
                                 []).append(point(backend["casts_per_second"]))
            for build in scene["bvh_builds"]:
                builds.setdefault("%s (%d thread%s)" % (build["builder"], build["threads"],
                                                        "" if build["threads"] == 1 else "s"), []).append(
                    point(build["ms"]))
    for chart, table in ((rate_chart, casts), (build_chart, builds)):
        for i, (label, points) in enumerate(table.items()):
            c = COLOURS[i % len(COLOURS)]
            chart.series(sorted((t, v) for t, v, g in points if g), label,
                         "using 1:2 with linespoints lw 2 pt 7 lc rgb '%s'" % c)
            chart.series(sorted((t, v) for t, v, g in points if not g), None,
                         "using 1:2 with points pt 9 ps 1.8 lc rgb '%s'" % c)
    return [rate_chart, build_chart]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("inputs", nargs="+", help="JSON files written by bench_step / bench_rays --json")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "plots"),
                        help="directory for the PNGs (default: bench/plots)")
    args = parser.parse_args()
    gnuplot = shutil.which("gnuplot")
    if not gnuplot:
        sys.exit("plot.py: gnuplot not found (Debian: apt-get install gnuplot-nox)")
    by_kind = {"bench_step": [], "bench_rays": []}
    for path in args.inputs:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        if doc.get("benchmark") not in by_kind:
            sys.exit("plot.py: %s: not bench_step or bench_rays output" % path)
        by_kind[doc["benchmark"]].append(doc)
    charts = []
    if by_kind["bench_step"]:
        charts += step_charts(by_kind["bench_step"])
    if by_kind["bench_rays"]:
        charts += ray_charts(by_kind["bench_rays"])
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for chart in charts:
            if not chart.clauses:
                continue
            png = os.path.join(args.out, chart.name + ".png")
            script = os.path.join(tmp, chart.name + ".gp")
            with open(script, "w", encoding="utf-8") as f:
                f.write(chart.script(png))
            subprocess.run([gnuplot, script], check=True)
            print(png)


if __name__ == "__main__":
    main()
