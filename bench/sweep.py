#!/usr/bin/env python3
"""Reproduce seed 000's evaluation (thesis ch. 6) on bounce, through the CLI only.

Experiments:
  grid        Table 6.1: photon paths x radius, one photon bounce, against a one-bounce
              path-traced reference; frame time (bench) and single-frame MSE / MSSIM (compare)
  default     the multi-bounce default against a full reference; direct light alone

The frames and timings are the raw pipeline's (--no-denoise), as the thesis measured them; the
grid and the default comparison also score each single frame with the denoiser on (the CLI's
default), in columns named *_denoised.
  budget      section 6.1.1: the best grid cell by MSE and by MSSIM within a frame-time budget
  complexity  section 6.2: cubes:N, per-stage frame time and BVH build time against triangles

Writes CSV files, plots and index.html under --out (default out/report).
Exits non-zero when a command fails or a sanity check on the numbers does not hold.
"""

import argparse
import csv
import html
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


class SweepError(Exception):
    pass


@dataclass
class Config:
    size: int               # grid and default images: size x size pixels
    ref_spp: int            # samples per pixel of the path-traced references
    frames: int             # bench: frames timed
    warmup: int             # bench: frames before timing
    paths: list             # photon paths per frame (grid)
    radii: list             # radius, percent of the scene diagonal (grid)
    cubes: list             # N of cubes:N (complexity)
    cubes_size: int         # complexity images: pixels per side
    cubes_frames: int
    budget_ms: float        # frame-time budget of the fixed-budget analysis
    baseline: tuple = (1000, 4.0)   # the thesis's 1000 paths at r = 1.0 (see RADIUS_MAP)


# The thesis's radii (scene units of its Cornell box) mapped to percent of our box's diagonal:
# r% = 4 x r, so the ratios between radii are kept and its typical r = 1.0 is 4%.
RADIUS_MAP = {0.25: 1.0, 0.5: 2.0, 1.0: 4.0, 1.5: 6.0, 2.0: 8.0}

FULL = Config(size=256, ref_spp=1024, frames=50, warmup=5,
              paths=[350, 500, 700, 1000, 2500, 5000, 7500],
              radii=list(RADIUS_MAP.values()) + [12.0, 16.0],   # and beyond, to find the optimum
              cubes=[1, 10, 100, 1000, 10000, 100000], cubes_size=256, cubes_frames=20,
              budget_ms=33.0)
QUICK = Config(size=48, ref_spp=64, frames=5, warmup=1,
               paths=[500, 5000], radii=[4.0],
               cubes=[1, 100], cubes_size=48, cubes_frames=3,
               budget_ms=33.0, baseline=(500, 4.0))


# The raw pipeline: no temporal reuse or denoising (the CLI denoises by default).
RAW = ["--no-denoise"]


# ---------------------------------------------------------------- running the CLI

def run(cmd):
    """Runs one command; returns its stdout or raises with the command and its stderr."""
    shown = " ".join(str(c) for c in cmd)
    print(f"  $ {shown}", flush=True)
    try:
        p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    except OSError as e:
        raise SweepError(f"cannot run: {shown}\n{e}")
    if p.returncode != 0:
        raise SweepError(f"command failed (exit {p.returncode}): {shown}\n{p.stderr.strip()}")
    return p.stdout


class Bounce:
    def __init__(self, binary):
        self.bin = binary

    def reference(self, out, size, spp, max_bounces):
        run([self.bin, "reference", "cornell", "-W", size, "-H", size, "--spp", spp,
             "--max-bounces", max_bounces, "-o", out])

    def render(self, out, size, args):
        run([self.bin, "render", "cornell", "-W", size, "-H", size, *args, "-o", out])

    def bench(self, scene, size, frames, warmup, args, json_path):
        run([self.bin, "bench", scene, "-W", size, "-H", size, "--frames", frames,
             "--warmup", warmup, *args, "--json", json_path])
        return json.loads(Path(json_path).read_text())

    def compare(self, ref, test, heatmap):
        out = run([self.bin, "compare", ref, test, "--json", "--heatmap", heatmap])
        return json.loads(out)["srgb8"]

    def info(self, scene):
        out = run([self.bin, "info", scene])
        tris = re.search(r"^triangles\s+(\d+)", out, re.M)
        bvh = re.search(r"^BVH \(high\)\s+([\d.]+) MiB, built in ([\d.]+) ms", out, re.M)
        if not tris or not bvh:
            raise SweepError(f"cannot parse `bounce info {scene}`:\n{out}")
        return int(tris.group(1)), float(bvh.group(1)), float(bvh.group(2))


# ---------------------------------------------------------------- small helpers

def stage(bench_json, name):
    for s in bench_json["stages"] + [bench_json["total"]]:
        if s["name"] == name:
            return s["mean_ms"], s["stddev_ms"]
    return float("nan"), float("nan")


def technique_stages(bench_json):
    """The technique's time, prepare (photon tracing) plus indirect (estimation), and the larger
    of their deviations."""
    prep, prep_sd = stage(bench_json, "prepare")
    ind, ind_sd = stage(bench_json, "indirect")
    return prep + ind, max(prep_sd, ind_sd)


def one_bounce_args(paths, radius_pct):
    return ["--photons", paths, "--radius", f"{radius_pct:g}%", "--bounces", "1"]


def write_atomic(path, data, mode="w"):
    """Writes to a temporary file beside path, then renames it over path."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix="." + path.name + ".")
    try:
        with os.fdopen(fd, mode) as f:
            f.write(data)
        os.chmod(tmp, 0o644)    # mkstemp makes it private
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def write_csv(path, rows):
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    write_atomic(path, buf.getvalue())


# ---------------------------------------------------------------- experiments

def make_references(b, cfg, out):
    print("references", flush=True)
    t0 = time.time()
    b.reference(out / "reference_1bounce.png", cfg.size, cfg.ref_spp, 1)
    t1 = time.time()
    b.reference(out / "reference_full.png", cfg.size, cfg.ref_spp, -1)
    return {"one_bounce_s": t1 - t0, "full_s": time.time() - t1}


def grid_cell(b, cfg, out, paths, radius):
    name = f"p{paths}_r{radius:g}"
    args = one_bounce_args(paths, radius)
    j = b.bench("cornell", cfg.size, cfg.frames, cfg.warmup, [*args, *RAW],
                out / "json" / f"{name}.json")
    ref = out / "reference_1bounce.png"
    img = out / "grid" / f"{name}.png"
    b.render(img, cfg.size, ["--spp", "1", *args, *RAW])
    m = b.compare(ref, img, out / "grid" / f"{name}_error.png")
    img_dn = out / "grid" / f"{name}_denoised.png"
    b.render(img_dn, cfg.size, ["--spp", "1", *args])
    md = b.compare(ref, img_dn, out / "grid" / f"{name}_denoised_error.png")
    total, total_sd = stage(j, "total")
    ind, ind_sd = technique_stages(j)
    return {"paths": paths, "radius_pct": radius,
            "stored": j["photons"]["stored_per_frame"],
            "frame_ms": total, "frame_sd_ms": total_sd,
            "indirect_ms": ind, "indirect_sd_ms": ind_sd,
            "mse": m["mse"], "nrmse": m["nrmse"], "mssim": m["mssim"],
            "mse_denoised": md["mse"], "mssim_denoised": md["mssim"]}


def run_grid(b, cfg, out):
    print("grid (Table 6.1)", flush=True)
    return [grid_cell(b, cfg, out, p, r) for p in cfg.paths for r in cfg.radii]


def run_default(b, cfg, out):
    """The multi-bounce default (one frame and converged) and direct light, against both refs."""
    print("default technique and direct light", flush=True)
    j = b.bench("cornell", cfg.size, cfg.frames, cfg.warmup, RAW, out / "json" / "default.json")
    jd = b.bench("cornell", cfg.size, cfg.frames, cfg.warmup, ["-t", "direct", *RAW],
                 out / "json" / "direct.json")
    # The same two with the denoiser: its cost beside the raw frame.
    j_dn = b.bench("cornell", cfg.size, cfg.frames, cfg.warmup, [],
                   out / "json" / "default_denoised.json")
    jd_dn = b.bench("cornell", cfg.size, cfg.frames, cfg.warmup, ["-t", "direct"],
                    out / "json" / "direct_denoised.json")
    images = {
        "tiled_1frame": ["--spp", "1", "--photons", "2000"],
        "tiled_converged": [],      # render's still defaults: 20,000 paths x 16 passes
        "direct": ["-t", "direct", "--spp", "1"],
    }
    rows = []
    for name, args in images.items():
        t0 = time.time()
        b.render(out / f"{name}.png", cfg.size, [*args, *RAW])
        secs = time.time() - t0
        b.render(out / f"{name}_denoised.png", cfg.size, args)
        timed = name != "tiled_converged"
        bench_j, bench_dn = (jd, jd_dn) if name == "direct" else (j, j_dn)
        for ref in ("full", "1bounce"):
            m = b.compare(out / f"reference_{ref}.png", out / f"{name}.png",
                          out / f"{name}_vs_{ref}_error.png")
            md = b.compare(out / f"reference_{ref}.png", out / f"{name}_denoised.png",
                           out / f"{name}_denoised_vs_{ref}_error.png")
            rows.append({"image": name, "reference": ref,
                         "frame_ms": stage(bench_j, "total")[0] if timed else float("nan"),
                         "frame_ms_denoised": stage(bench_dn, "total")[0] if timed else float("nan"),
                         "denoise_ms": stage(bench_dn, "denoise")[0] if timed else float("nan"),
                         "render_s": secs,
                         "mse": m["mse"], "nrmse": m["nrmse"], "mssim": m["mssim"],
                         "mse_denoised": md["mse"], "mssim_denoised": md["mssim"]})
    return rows, j


def best_within_budget(grid, budget_ms):
    """Section 6.1.1: among cells whose mean frame time fits the budget, the best by each metric."""
    fit = [r for r in grid if r["frame_ms"] <= budget_ms]
    if not fit:
        return None
    return {"budget_ms": budget_ms, "cells": len(fit),
            "by_mse": min(fit, key=lambda r: r["mse"]),
            "by_mssim": max(fit, key=lambda r: r["mssim"])}


def run_complexity(b, cfg, out):
    print("scene complexity (section 6.2)", flush=True)
    rows = []
    for n in cfg.cubes:
        scene = f"cubes:{n}"
        tris, bvh_mib, bvh_ms = b.info(scene)
        j = b.bench(scene, cfg.cubes_size, cfg.cubes_frames, min(cfg.warmup, 3),
                    RAW, out / "json" / f"cubes{n}.json")
        row = {"cubes": n, "triangles": tris, "bvh_build_ms": bvh_ms, "bvh_mib": bvh_mib}
        for s in j["stages"] + [j["total"]]:
            row[s["name"] + "_ms"] = s["mean_ms"]
            row[s["name"] + "_sd_ms"] = s["stddev_ms"]
        rows.append(row)
    keys = set(rows[0])
    if any(set(r) != keys for r in rows):
        raise SweepError("bench reported different stages for different scenes")
    return rows


# ---------------------------------------------------------------- checks

def check_numbers(grid, default_rows, complexity, cfg):
    """Sanity checks that must hold; returns the list of failures."""
    bad = []
    want = len(cfg.paths) * len(cfg.radii)
    if len(grid) != want:
        bad.append(f"grid has {len(grid)} rows, expected {want}")
    for r in grid + default_rows:
        for k, v in r.items():
            if isinstance(v, float) and math.isnan(v) and k not in ("frame_ms", "frame_ms_denoised",
                                                                     "denoise_ms"):
                bad.append(f"NaN {k} in {r}")
    for r in grid:
        if not (r["frame_ms"] > 0 and r["stored"] > 0 and 0 < r["mssim"] <= 1):
            bad.append(f"implausible grid row {r}")
    for r in grid + default_rows:
        if not (0 < r["mssim_denoised"] <= 1 and r["mse_denoised"] >= 0):
            bad.append(f"implausible denoised scores in {r}")
    for r in default_rows:
        if r["image"] != "tiled_converged" and not r["denoise_ms"] > 0:
            bad.append(f"no denoise stage timed for {r['image']}")
    for radius in cfg.radii:
        col = sorted((r for r in grid if r["radius_pct"] == radius), key=lambda r: r["paths"])
        if len(col) >= 2 and not col[-1]["mse"] < col[0]["mse"]:
            bad.append(f"MSE did not fall from {col[0]['paths']} to {col[-1]['paths']} paths "
                       f"at radius {radius}%: {col[0]['mse']:.1f} -> {col[-1]['mse']:.1f}")
    mse = {(r["image"], r["reference"]): r["mse"] for r in default_rows}
    if not mse[("tiled_converged", "full")] < mse[("direct", "full")]:
        bad.append("the converged tiled image is not closer to the full reference than direct light")
    if not mse[("tiled_1frame", "full")] < mse[("direct", "full")]:
        bad.append("one tiled frame is not closer to the full reference than direct light")
    tris = [r["triangles"] for r in complexity]
    if tris != [14 + 12 * r["cubes"] for r in complexity]:
        bad.append(f"cubes:N triangle counts are not 14 + 12N: {tris}")
    return bad


# ---------------------------------------------------------------- plots

def plot_grid(grid, cfg, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
    for radius in cfg.radii:
        col = sorted((r for r in grid if r["radius_pct"] == radius), key=lambda r: r["paths"])
        x = [r["paths"] for r in col]
        axes[0].errorbar(x, [r["frame_ms"] for r in col], yerr=[r["frame_sd_ms"] for r in col],
                         marker="o", capsize=2, label=f"r = {radius:g}%")
        axes[1].plot(x, [r["mse"] for r in col], marker="o", label=f"r = {radius:g}%")
        axes[2].plot(x, [r["mssim"] for r in col], marker="o", label=f"r = {radius:g}%")
    axes[0].axhline(cfg.budget_ms, color="grey", ls="--", lw=1)
    for ax, title in zip(axes, ["frame time (ms, mean ± sd)", "MSE (8-bit), one frame",
                                "MSSIM, one frame"]):
        ax.set_xscale("log")
        ax.set_xlabel("photon paths per frame")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Cornell box {cfg.size}x{cfg.size}, one photon bounce, one-bounce reference",
                 fontsize=10)
    fig.tight_layout()
    save_fig(fig, out / "grid.png")
    plt.close(fig)


def plot_budget(grid, cfg, out):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for radius in cfg.radii:
        col = [r for r in grid if r["radius_pct"] == radius]
        axes[0].scatter([r["frame_ms"] for r in col], [r["mse"] for r in col], label=f"{radius:g}%")
        axes[1].scatter([r["frame_ms"] for r in col], [r["mssim"] for r in col], label=f"{radius:g}%")
    for ax, t in zip(axes, ["MSE (8-bit)", "MSSIM"]):
        ax.axvline(cfg.budget_ms, color="grey", ls="--", lw=1)
        ax.set_xlabel("frame time (ms)")
        ax.set_ylabel(t)
        ax.grid(alpha=0.3)
    axes[0].legend(title="radius", fontsize=8)
    fig.suptitle(f"error against cost; dashed: the {cfg.budget_ms:g} ms budget", fontsize=10)
    fig.tight_layout()
    save_fig(fig, out / "budget.png")
    plt.close(fig)


def plot_complexity(rows, cfg, out):
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 3.8))
    x = [r["triangles"] for r in rows]
    for name in ("gbuffer", "direct", "prepare/photon trace", "prepare/clearance",
                 "indirect/tile bins", "indirect/estimate low-res", "indirect/upsample + edges",
                 "total"):
        if name + "_ms" in rows[0]:
            axes[0].plot(x, [r[name + "_ms"] for r in rows], marker="o", label=name,
                         lw=2.5 if name == "total" else 1.2)
    axes[0].set_ylabel("ms per frame")
    axes[0].legend(fontsize=7)
    axes[1].plot(x, [r["bvh_build_ms"] for r in rows], marker="o")
    axes[1].set_ylabel("BVH build (ms)")
    axes[1].set_yscale("log")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("triangles (cubes:N)")
        ax.grid(alpha=0.3)
    fig.suptitle(f"scene complexity, {cfg.cubes_size}x{cfg.cubes_size}, default tiled settings",
                 fontsize=10)
    fig.tight_layout()
    save_fig(fig, out / "complexity.png")
    plt.close(fig)


def save_fig(fig, path):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=80)
    write_atomic(path, buf.getvalue(), "wb")


# ---------------------------------------------------------------- report page

def html_table(rows, cols):
    head = "".join(f"<th>{html.escape(c)}</th>" for c in cols)
    body = ""
    for r in rows:
        cells = "".join(f"<td>{v:.4g}</td>" if isinstance(v, float) else f"<td>{html.escape(str(v))}</td>"
                        for v in (r[c] for c in cols))
        body += f"<tr>{cells}</tr>\n"
    return f"<table><tr>{head}</tr>\n{body}</table>\n"


def figure(src, caption):
    return (f'<figure><img src="{html.escape(src)}" width="256">'
            f"<figcaption>{html.escape(caption)}</figcaption></figure>")


def write_index(out, cfg, grid, default_rows, budgets, complexity, meta):
    p = [f"<!doctype html><meta charset='utf-8'><title>bounce evaluation</title>",
         "<style>body{font-family:sans-serif;max-width:1400px} figure{display:inline-block;margin:4px}"
         " td,th{padding:2px 8px;text-align:right} table{border-collapse:collapse}"
         " tr:nth-child(even){background:#eee}</style>",
         f"<h1>bounce evaluation (seed 000, chapter 6)</h1><p>{html.escape(meta)}</p>",
         "<h2>Images</h2>",
         figure("reference_full.png", "reference, all bounces"),
         figure("tiled_converged.png", "tiled, converged still"),
         figure("tiled_1frame.png", "tiled, one frame (default)"),
         figure("direct.png", "direct light only"),
         figure("tiled_1frame_denoised.png", "tiled, one frame, denoised"), "<br>",
         figure("reference_1bounce.png", "reference, one bounce"),
         figure("tiled_converged_vs_full_error.png", "error: converged tiled vs full"),
         figure("tiled_1frame_vs_full_error.png", "error: one tiled frame vs full"),
         figure("direct_vs_full_error.png", "error: direct vs full"),
         html_table(default_rows, list(default_rows[0].keys())),
         "<h2>Table 6.1 grid: one bounce, one frame</h2>",
         '<img src="grid.png">', html_table(grid, list(grid[0].keys())),
         "<h3>Error heat maps (rows: paths, columns: radius)</h3><table>"]
    for paths in cfg.paths:
        p.append("<tr>" + "".join(
            f"<td>{figure(f'grid/p{paths}_r{r:g}_error.png', f'{paths} paths, {r:g}%')}</td>"
            for r in cfg.radii) + "</tr>")
    p.append("</table><h2>Fixed budget (section 6.1.1)</h2><img src='budget.png'>")
    for b in budgets:
        if b is None:
            continue
        p.append(f"<p>Budget {b['budget_ms']:.3g} ms ({b['cells']} cells fit): best MSE "
                 f"{b['by_mse']['mse']:.4g} at {b['by_mse']['paths']} paths, "
                 f"{b['by_mse']['radius_pct']:g}%; best MSSIM {b['by_mssim']['mssim']:.4g} at "
                 f"{b['by_mssim']['paths']} paths, {b['by_mssim']['radius_pct']:g}%</p>")
    p.append("<h2>Scene complexity (section 6.2)</h2><img src='complexity.png'>")
    cols = ["cubes", "triangles", "bvh_build_ms", "gbuffer_ms", "direct_ms", "prepare_ms", "indirect_ms", "total_ms"]
    p.append(html_table(complexity, [c for c in cols if c in complexity[0]]))
    write_atomic(out / "index.html", "\n".join(p) + "\n")


# ---------------------------------------------------------------- main

def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="tiny sizes and few configurations (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "out" / "report"), help="output folder")
    ap.add_argument("--bounce", default=str(ROOT / "build" / "release" / "bounce"), help="the bounce binary")
    ap.add_argument("--budget", type=float, help="frame-time budget in ms (default 33)")
    return ap.parse_args()


def ensure_matplotlib():
    """Re-runs under the system python when this one lacks matplotlib (e.g. a pyenv shim)."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        system = "/usr/bin/python3"
        if os.path.realpath(sys.executable) != os.path.realpath(system) and os.access(system, os.X_OK):
            os.execv(system, [system, *sys.argv])
        raise SystemExit("sweep: matplotlib is missing (apt-get install python3-matplotlib)")


def main():
    ensure_matplotlib()
    a = parse_args()
    cfg = QUICK if a.quick else FULL
    if a.budget:
        cfg.budget_ms = a.budget
    binary = Path(a.bounce)
    if not (binary.is_file() and os.access(binary, os.X_OK)):
        print(f"sweep: no executable bounce binary at {binary} (build it, or pass --bounce)",
              file=sys.stderr)
        return 2
    out = Path(a.out)
    for d in (out, out / "grid", out / "json"):
        d.mkdir(parents=True, exist_ok=True)
    b = Bounce(binary)
    start = time.time()
    try:
        ref_times = make_references(b, cfg, out)
        grid = run_grid(b, cfg, out)
        default_rows, default_bench = run_default(b, cfg, out)
        complexity = run_complexity(b, cfg, out)
    except SweepError as e:
        print(f"sweep: {e}", file=sys.stderr)
        return 1

    base = next((r for r in grid if (r["paths"], r["radius_pct"]) == cfg.baseline), None)
    budgets = [best_within_budget(grid, cfg.budget_ms)]
    if base:
        budgets.append(best_within_budget(grid, base["frame_ms"]))
    write_csv(out / "grid.csv", grid)
    write_csv(out / "default.csv", default_rows)
    write_csv(out / "complexity.csv", complexity)
    write_atomic(out / "budget.json", json.dumps(budgets, indent=2) + "\n")
    plot_grid(grid, cfg, out)
    plot_budget(grid, cfg, out)
    plot_complexity(complexity, cfg, out)
    machine = default_bench.get("machine", {})
    meta = (f"{'quick' if a.quick else 'full'} sweep, {time.time() - start:.0f} s; images "
            f"{cfg.size}x{cfg.size}, references {cfg.ref_spp} spp (one bounce "
            f"{ref_times['one_bounce_s']:.0f} s, full {ref_times['full_s']:.0f} s); bench "
            f"{cfg.frames} frames after {cfg.warmup}; complexity {cfg.cubes_size}x{cfg.cubes_size}, "
            f"{cfg.cubes_frames} frames; {machine.get('cpu', '?')}, {machine.get('threads', '?')} threads")
    write_index(out, cfg, grid, default_rows, budgets, complexity, meta)
    print(meta)
    for bud in budgets:
        if bud:
            print(f"budget {bud['budget_ms']:.3g} ms: best MSE {bud['by_mse']['mse']:.1f} "
                  f"({bud['by_mse']['paths']} paths, {bud['by_mse']['radius_pct']:g}%), best MSSIM "
                  f"{bud['by_mssim']['mssim']:.4f} ({bud['by_mssim']['paths']} paths, "
                  f"{bud['by_mssim']['radius_pct']:g}%)")

    bad = check_numbers(grid, default_rows, complexity, cfg)
    for msg in bad:
        print(f"sweep: check failed: {msg}", file=sys.stderr)
    print(f"wrote {out / 'index.html'}" + ("" if not bad else f"; {len(bad)} check(s) failed"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
