#!/usr/bin/env python3
"""Issue 10's real-time quality targets, measured through the CLI only.

Measurements (each denoised, as the CLI runs by default, and raw with --no-denoise):
  references  `bounce reference scenes/cornell-walk.bounce.json --at T` for the poses compared
  at rest     `bounce sequence cornell`: the first displayed frame and frame 30 (1 s) against the
              t = 0 reference (the plain Cornell box view); MSE8, MSSIM, FLIP, mean frame ms
  in motion   `bounce sequence scenes/cornell-walk.bounce.json`: frames 30 and 60 (1 s, 2 s into
              the walk) against the references of those poses
  cost        `bounce bench cornell`, every frame without history and with --accumulate: the
              total and the denoise stage
  light move  `bounce bench scenes/dynamic-cornell.bounce.json --settle --flicker 60`: frames to
              settle within 5% after the light moves, flicker at rest

Writes OUT/realtime.json and OUT/realtime.md (default OUT = out/realtime), with each target
beside its value. A missed target is a result, not an error; the exit status is non-zero only
when a command fails or a number is absurd (NaN, negative, MSSIM above 1).
"""

import argparse
import datetime
import json
import math
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from sweep import SweepError, run, stage, write_atomic

ROOT = Path(__file__).resolve().parent.parent
WALK = ROOT / "scenes" / "cornell-walk.bounce.json"
DYNAMIC = ROOT / "scenes" / "dynamic-cornell.bounce.json"


@dataclass
class Config:
    size: int                  # every image: size x size pixels
    ref_spp: int               # samples per pixel of the path-traced references
    fps: int
    rest_to: float             # at rest: sequence length, s
    rest_frames: list          # at rest: frame indices compared (first frame, settled frame)
    motion_to: float           # in motion: sequence length, s
    motion_frames: list        # in motion: frame indices compared, each against its own pose
    bench_args: list = field(default_factory=list)     # cost runs: frame counts (bench defaults)
    # Light move: bench's temporal runs use their own size (128x128) unless -W/-H are given; its
    # timed frames are not used here, so only one is rendered.
    temporal_args: list = field(default_factory=lambda: ["--frames", "1"])
    flicker: int = 60


FULL = Config(size=512, ref_spp=4096, fps=30, rest_to=1.0, rest_frames=[0, 30],
              motion_to=2.0, motion_frames=[30, 60])
# A smoke test: tiny images, a few frames; the "1 s" frames become the last frame rendered.
QUICK = Config(size=48, ref_spp=32, fps=30, rest_to=0.2, rest_frames=[0, 6],
               motion_to=0.2, motion_frames=[3, 6],
               bench_args=["--frames", "3", "--warmup", "1"],
               temporal_args=["--frames", "1", "--warmup", "1", "-W", "48", "-H", "48",
                              "--settle-frames", "8"],
               flicker=8)

MODES = {"denoised": [], "raw": ["--no-denoise"]}


# ---------------------------------------------------------------- running the CLI

class Bounce:
    def __init__(self, binary, cfg):
        self.bin = binary
        self.cfg = cfg

    def size(self):
        return ["-W", self.cfg.size, "-H", self.cfg.size]

    def reference(self, out, at):
        run([self.bin, "reference", WALK, "--at", f"{at:g}", *self.size(),
             "--spp", self.cfg.ref_spp, "-o", out])

    def sequence(self, scene, to, frames, mode_args, out_dir, json_path):
        """Renders 0..to at the config's fps; writes at least the wanted frames; returns the
        --json record."""
        every = math.gcd(*frames) or 1
        run([self.bin, "sequence", scene, "--to", f"{to:g}", "--fps", self.cfg.fps,
             "--every", every, *self.size(), *mode_args,
             "-o", out_dir / "f_%04d.png", "--json", json_path])
        return json.loads(Path(json_path).read_text())

    def bench(self, scene, args, json_path):
        run([self.bin, "bench", scene, *args, "--json", json_path])
        return json.loads(Path(json_path).read_text())

    def compare(self, ref, test, heatmap):
        out = run([self.bin, "compare", ref, test, "--json", "--heatmap", heatmap])
        j = json.loads(out)
        return {**j["srgb8"], "flip": j["flip"]["mean"]}


# ---------------------------------------------------------------- measurements

def reference_path(out, cfg, at):
    # Size and spp in the name, so that --keep-references never reuses an image of other settings.
    return out / f"reference_t{at:g}_{cfg.size}px_{cfg.ref_spp}spp.png"


def make_references(b, cfg, out, times, keep):
    print("references", flush=True)
    secs = {}
    for at in times:
        path = reference_path(out, cfg, at)
        if keep and path.is_file():
            print(f"  kept {path}", flush=True)
            secs[f"{at:g}"] = None
            continue
        t0 = time.time()
        b.reference(path, at)
        secs[f"{at:g}"] = time.time() - t0
    return secs


def frame_file(seq_json, index):
    for f in seq_json["frames"]:
        if f["index"] == index and "file" in f:
            return Path(f["file"])
    raise SweepError(f"sequence did not write frame {index}")


def mean_stage(seq_json, name):
    """Mean over the sequence's frames of one stage's ms; NaN when the stage did not run."""
    values = [f["stages"][name] for f in seq_json["frames"] if name in f.get("stages", {})]
    return sum(values) / len(values) if values else float("nan")


def run_sequence(b, cfg, out, what, scene, to, frames, ref_at):
    """One sequence per mode; each wanted frame against the reference of its pose."""
    print(f"{what}: {scene}", flush=True)
    result = {}
    for mode, args in MODES.items():
        d = out / what / mode
        d.mkdir(parents=True, exist_ok=True)
        j = b.sequence(scene, to, frames, args, d, out / "json" / f"sequence_{what}_{mode}.json")
        entry = {"mean_frame_ms": j["mean_frame_ms"],
                 "mean_frame_ms_after_first": j["mean_frame_ms_after_first"],
                 "denoise_ms": mean_stage(j, "denoise"),
                 "frames": {}}
        for k in frames:
            img = frame_file(j, k)
            ref = reference_path(out, cfg, ref_at(k))
            m = b.compare(ref, img, d / f"f_{k:04d}_error.png")
            entry["frames"][str(k)] = {"time": k / cfg.fps, "reference_at": ref_at(k),
                                       "mse8": m["mse"], "mssim": m["mssim"], "flip": m["flip"]}
        result[mode] = entry
    return result


def run_cost(b, cfg, out):
    print("cost: bench cornell", flush=True)
    result = {}
    for mode, args in MODES.items():
        for acc in (False, True):
            name = f"{mode}_{'accumulate' if acc else 'every_frame'}"
            j = b.bench("cornell", [*b.size(), *cfg.bench_args, *(["--accumulate"] if acc else []), *args],
                        out / "json" / f"bench_{name}.json")
            total, total_sd = stage(j, "total")
            result[name] = {"frame_ms": total, "frame_sd_ms": total_sd,
                            "denoise_ms": stage(j, "denoise")[0],
                            "width": j["width"], "frames": j["frames"],
                            "machine": j.get("machine", {})}
    return result


def run_light_move(b, cfg, out):
    print("light move: bench dynamic-cornell --settle --flicker", flush=True)
    result = {}
    for mode, args in MODES.items():
        j = b.bench(DYNAMIC, ["--settle", "--flicker", cfg.flicker, *cfg.temporal_args, *args],
                    out / "json" / f"bench_light_{mode}.json")
        s, f = j.get("settle"), j.get("flicker")
        if not s or not f:
            raise SweepError("bench --settle --flicker wrote no settle or flicker record")
        if not s["applicable"]:
            raise SweepError(f"settle was not measured: {s['reason']}")
        result[mode] = {"settle_frames": s["frames"], "settled": s["settled"],
                        "settle_max_frames": s["max_frames"], "settle_tolerance": s["tolerance"],
                        "flicker_at_rest": f["at_rest"],
                        "flicker_accumulation_off": f["accumulation_off"],
                        "temporal_size": s["width"]}
    return result


# ---------------------------------------------------------------- targets and checks

def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and not math.isnan(v)


def at_most(bound):
    return (f"<= {bound:g}", lambda v: is_number(v) and v <= bound)


def at_least(bound):
    return (f">= {bound:g}", lambda v: is_number(v) and v >= bound)


def settle_value(light):
    """Frames to settle, or a note when the light never settled within the frames measured."""
    return light["settle_frames"] if light["settled"] else f"not in {light['settle_max_frames']}"


def table_rows(cfg, rest, motion, cost, light):
    """Rows of (measurement, denoised value, raw value, target or None, unit format)."""
    rows = []
    first, settled = cfg.rest_frames
    for k, what in ((first, "first displayed frame"), (settled, f"frame {settled}")):
        d, r = rest["denoised"]["frames"][str(k)], rest["raw"]["frames"][str(k)]
        t = k / cfg.fps
        mssim_t = at_least(0.90) if k == first else at_least(0.98)
        rows.append((f"at rest, {what} ({t:g} s): MSSIM", d["mssim"], r["mssim"], mssim_t, "{:.4f}"))
        rows.append((f"at rest, {what} ({t:g} s): MSE8", d["mse8"], r["mse8"],
                     None if k == first else at_most(10), "{:.1f}"))
        rows.append((f"at rest, {what} ({t:g} s): FLIP", d["flip"], r["flip"], None, "{:.4f}"))
    rows.append(("at rest, sequence mean frame ms", rest["denoised"]["mean_frame_ms"],
                 rest["raw"]["mean_frame_ms"], None, "{:.1f}"))
    for k in cfg.motion_frames:
        d, r = motion["denoised"]["frames"][str(k)], motion["raw"]["frames"][str(k)]
        t = k / cfg.fps
        rows.append((f"in motion, frame {k} ({t:g} s): MSSIM", d["mssim"], r["mssim"],
                     at_least(0.95), "{:.4f}"))
        rows.append((f"in motion, frame {k} ({t:g} s): MSE8", d["mse8"], r["mse8"],
                     at_most(30), "{:.1f}"))
        rows.append((f"in motion, frame {k} ({t:g} s): FLIP", d["flip"], r["flip"], None, "{:.4f}"))
    rows.append(("in motion, sequence mean frame ms", motion["denoised"]["mean_frame_ms"],
                 motion["raw"]["mean_frame_ms"], None, "{:.1f}"))
    rows.append(("in motion, sequence mean frame ms after the first",
                 motion["denoised"]["mean_frame_ms_after_first"],
                 motion["raw"]["mean_frame_ms_after_first"], None, "{:.1f}"))
    for acc, what in (("every_frame", "every frame, no history"), ("accumulate", "at rest, --accumulate")):
        d, r = cost[f"denoised_{acc}"], cost[f"raw_{acc}"]
        rows.append((f"bench frame ms ({what})", d["frame_ms"], r["frame_ms"], at_most(33), "{:.1f}"))
        rows.append((f"bench denoise stage ms ({what})", d["denoise_ms"], None, at_most(5), "{:.2f}"))
    d, r = light["denoised"], light["raw"]
    rows.append((f"light move: frames to settle within {100 * d['settle_tolerance']:g}%",
                 settle_value(d), settle_value(r), at_most(4), "{:d}"))
    rows.append(("light move: flicker at rest (%)", 100 * d["flicker_at_rest"],
                 100 * r["flicker_at_rest"], at_most(1), "{:.2f}"))
    return rows


def absurd(results):
    """Numbers no measurement can give: NaN, negative, MSSIM outside (0, 1], no time."""
    bad = []

    def walk(v, path):
        if isinstance(v, dict):
            for k, x in v.items():
                walk(x, f"{path}.{k}")
        elif isinstance(v, bool) or v is None or isinstance(v, str):
            return
        elif isinstance(v, (int, float)):
            # Only the raw runs may lack the denoise stage (NaN there means "did not run").
            if math.isnan(v) and not (path.endswith("denoise_ms") and ".raw" in path):
                bad.append(f"{path} is NaN")
            elif v < 0:
                bad.append(f"{path} = {v} is negative")
            elif path.endswith("mssim") and not 0 < v <= 1:
                bad.append(f"{path} = {v} is outside (0, 1]")
            elif path.endswith("flip") and not 0 <= v <= 1:
                bad.append(f"{path} = {v} is outside [0, 1]")
            elif path.endswith(("frame_ms", "frame_ms_after_first")) and v == 0:
                bad.append(f"{path} is zero")

    walk(results, "")
    for mode in MODES:
        light = results["light_move"][mode]
        if light["settled"] and light["settle_frames"] is None:
            bad.append(f"light_move.{mode}: settled without a frame count")
        if light["flicker_at_rest"] is None:
            bad.append(f"light_move.{mode}: flicker at rest is not a number")
    return bad


# ---------------------------------------------------------------- report

def fmt(v, spec):
    if isinstance(v, str):
        return v
    return spec.format(v) if is_number(v) else "–"


def json_safe(v):
    """NaN (a stage that did not run) becomes null: JSON has no NaN."""
    if isinstance(v, dict):
        return {k: json_safe(x) for k, x in v.items()}
    if isinstance(v, list):
        return [json_safe(x) for x in v]
    return None if isinstance(v, float) and math.isnan(v) else v


def markdown(rows, meta):
    lines = [f"# Real-time quality (issue 10 targets)", "", meta, "",
             "| measurement | denoised | raw (`--no-denoise`) | target | met (denoised) |",
             "|---|---:|---:|---:|:---:|"]
    met_count = 0
    for what, d, r, target, spec in rows:
        if target:
            met = target[1](d)
            met_count += met
            t, m = target[0], "yes" if met else "**no**"
        else:
            t, m = "", ""
        lines.append(f"| {what} | {fmt(d, spec)} | {fmt(r, spec)} | {t} | {m} |")
    targets = sum(1 for row in rows if row[3])
    lines += ["", f"{met_count} of {targets} targets met by the denoised pipeline.", ""]
    return "\n".join(lines), met_count, targets


# ---------------------------------------------------------------- main

def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="48x48, few frames (smoke test)")
    ap.add_argument("--out", default=str(ROOT / "out" / "realtime"), help="output folder")
    ap.add_argument("--bounce", default=str(ROOT / "build" / "release" / "bounce"), help="the bounce binary")
    ap.add_argument("--keep-references", action="store_true",
                    help="reuse reference images already in OUT (same size and spp); they do not "
                         "depend on the real-time pipeline")
    return ap.parse_args()


def main():
    a = parse_args()
    cfg = QUICK if a.quick else FULL
    binary = Path(a.bounce)
    if not (binary.is_file() and os.access(binary, os.X_OK)):
        print(f"realtime_eval: no executable bounce binary at {binary} (build it, or pass --bounce)",
              file=sys.stderr)
        return 2
    out = Path(a.out)
    (out / "json").mkdir(parents=True, exist_ok=True)
    b = Bounce(binary, cfg)
    start = time.time()
    motion_at = lambda k: k / cfg.fps
    ref_times = sorted({0.0, *(motion_at(k) for k in cfg.motion_frames)})
    try:
        ref_secs = make_references(b, cfg, out, ref_times, a.keep_references)
        rest = run_sequence(b, cfg, out, "rest", "cornell", cfg.rest_to, cfg.rest_frames,
                            lambda k: 0.0)
        motion = run_sequence(b, cfg, out, "motion", WALK, cfg.motion_to, cfg.motion_frames,
                              motion_at)
        cost = run_cost(b, cfg, out)
        light = run_light_move(b, cfg, out)
    except SweepError as e:
        print(f"realtime_eval: {e}", file=sys.stderr)
        return 1

    machine = cost["denoised_every_frame"]["machine"]
    meta = (f"{'quick' if a.quick else 'full'} run, {datetime.date.today()}, "
            f"{time.time() - start:.0f} s; {cfg.size}x{cfg.size}, references {cfg.ref_spp} spp; "
            f"sequences at {cfg.fps} fps; light move at {light['denoised']['temporal_size']}px "
            f"(bench's temporal size); {machine.get('cpu', '?')}, {machine.get('threads', '?')} "
            f"threads. Quality does not depend on machine load; the timings do.")
    rows = table_rows(cfg, rest, motion, cost, light)
    text, met, targets = markdown(rows, meta)
    results = {"mode": "quick" if a.quick else "full", "meta": meta,
               "config": {"size": cfg.size, "ref_spp": cfg.ref_spp, "fps": cfg.fps,
                          "rest_frames": cfg.rest_frames, "motion_frames": cfg.motion_frames},
               "reference_seconds": ref_secs,
               "rest": rest, "motion": motion, "cost": cost, "light_move": light,
               "targets": [{"measurement": w, "denoised": d, "raw": r, "target": t[0],
                            "met": bool(t[1](d))} for w, d, r, t, _ in rows if t],
               "targets_met": met, "targets_total": targets}
    bad = absurd({k: results[k] for k in ("rest", "motion", "cost", "light_move")})
    write_atomic(out / "realtime.json", json.dumps(json_safe(results), indent=2) + "\n")
    write_atomic(out / "realtime.md", text)
    print(text)
    for msg in bad:
        print(f"realtime_eval: absurd number: {msg}", file=sys.stderr)
    print(f"wrote {out / 'realtime.md'}" + ("" if not bad else f"; {len(bad)} absurd number(s)"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
