#!/usr/bin/env python3
"""The drop-point turn against DEM rows built at the turned drop point.

A table answers for another drop point by turning its launches about the disc axis (PredictionRequest::
drop_point_turn_rad). This script measures how far that holds: for each turn D it builds a one-row DEM
table of the scene with the feed turned (inlet.angle_rad + D, the same material, speed and seed) and
compares the table's prediction turned by D with that row's prediction at its own drop point:

  L1       sum over 0.5 m trays of |p_turned - p_row| of the single-pass transverse patterns (each sums to 1)
  dCV8/12/18  the to-and-fro CV at 8, 12 and 18 m bouts (what the chart, border and wind advice read),
           turned minus row (points), with the row's and the turned prediction's 95 % intervals (1.96 SE)
           added in quadrature as the bound
  dThrow   the throw width, turned minus row (m), with its bound as the CVs'
  dWW10/15 the headline to-and-fro working width at CV <= 10 % / 15 %, turned minus row (m), printed

The reference for the noise, at each turn: a second DEM row at the same turned drop point with another
seed, against the first (seed-to-seed L1 and differences). A turn is within the approximation's validity
when the turned table differs from the DEM row by no more than the second seed's row does, up to the
statistics: L1 at most 1.25 x the seed-to-seed L1, and each of the throw width and the three CVs within
the larger of its 95 % bound and 1.25 x the seed-to-seed difference. The working widths are printed, not
judged: where CV(W) grazes the target a band splits or joins between two statistically indistinguishable
patterns, and a headline width then jumps metres between two DEM seeds of the same drop point (the
second seed shows it) — that is the headline's fragility (docs/metrics.md), not the turn's error.

Tables already built in the output directory are reused (lookup_builder skips runs it already has).

Usage: tools/drop_point_check.py --table TABLE [--build DIR] [--out DIR] [--turns D1,D2,...]
                                 [--material NAME] [--rpm RPM] [--scene FILE] [--seed2 N] [--markdown]
Defaults: build/, /tmp/drop-point-check, turns -90,-75,-60,-45,-20,20,30,45,60 degrees, Urea at 600 rpm,
scenes/default.toml (whose DEM table TABLE is: the main job's out/default.sqlite), second seed 2.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parse_list(text):
    return [float(v) for v in text.split(",") if v.strip()]


def scene_inlet_angle(scene):
    # The scene's [inlet] angle_rad (the one key this script changes).
    section = None
    with open(scene) as f:
        for line in f:
            text = line.split("#", 1)[0].strip()
            if text.startswith("["):
                section = text.strip("[]").strip()
            elif section == "inlet" and text.startswith("angle_rad"):
                return float(text.split("=", 1)[1])
    raise SystemExit(f"{scene}: no [inlet] angle_rad")


def build_row(args, angle, seed, path):
    cmd = ["nice", "-n", "19", os.path.join(args.build, "lookup_builder", "lookup_builder"), args.scene,
           "--output", path, "--jobs", "1", "--threads", "1",
           "--set", f"inlet.angle_rad={angle!r}", "--set", f"numerics.seed={seed}",
           "--set", f'sweep.materials=["{args.material}"]', "--set", f"sweep.rpm=[{args.rpm!r}]"]
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start


def predict(args, path, target, turn_deg=0.0):
    cmd = [os.path.join(args.build, "tools", "spread", "spread"), "predict", "--tables", path,
           "--material", args.material, "--rpm", repr(args.rpm), "--cv-target", repr(target),
           "--drop-point-turn", repr(turn_deg), "--tray-width", "0.5", "--json"]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def l1(a, b):
    pa = dict(zip((round(c, 6) for c in a["transverse"]["centres_m"]), a["transverse"]["mass_fraction"]))
    pb = dict(zip((round(c, 6) for c in b["transverse"]["centres_m"]), b["transverse"]["mass_fraction"]))
    sa, sb = sum(pa.values()), sum(pb.values())
    return sum(abs(pa.get(c, 0.0) / sa - pb.get(c, 0.0) / sb) for c in set(pa) | set(pb))


def width(p):
    se = p["working_width_to_and_fro_se_m"]
    return p["working_width_to_and_fro_m"], (se if se is not None else float("nan"))


CV_WIDTHS = (8.0, 12.0, 18.0)


def predict_cv(args, path, width, turn_deg=0.0):
    cmd = [os.path.join(args.build, "tools", "spread", "spread"), "predict", "--tables", path,
           "--material", args.material, "--rpm", repr(args.rpm), "--width", repr(width),
           "--drop-point-turn", repr(turn_deg), "--tray-width", "0.5", "--json"]
    p = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    return p["cv_to_and_fro_percent"], p["cv_to_and_fro_se_percent"]


def compare(args, table_path, row_path, turn_deg):
    out = {}
    for bout_m in CV_WIDTHS:
        (ct, st), (cr, sr) = predict_cv(args, table_path, bout_m, turn_deg), predict_cv(args, row_path, bout_m)
        out[f"dcv{bout_m:.0f}"] = ct - cr
        out[f"boundcv{bout_m:.0f}"] = 1.96 * math.hypot(st, sr)
        out[f"cv{bout_m:.0f}"] = (ct, cr)
    for target in (10.0, 15.0):
        turned, row = predict(args, table_path, target, turn_deg), predict(args, row_path, target)
        (wt, st), (wr, sr) = width(turned), width(row)
        out[f"dww{target:.0f}"] = wt - wr
        out[f"bound{target:.0f}"] = 1.96 * math.hypot(st, sr)
        out[f"ww{target:.0f}"] = (wt, wr)
        if target == 15.0:
            out["l1"] = l1(turned, row)
            out["dthrow"] = turned["throw_width_m"] - row["throw_width_m"]
            out["bound_throw"] = 1.96 * math.hypot(turned["throw_width_se_m"], row["throw_width_se_m"])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--table", required=True, help="the scene's DEM table (the main job's out/default.sqlite)")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default="/tmp/drop-point-check")
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "default.toml"))
    ap.add_argument("--turns", type=parse_list, default=[-90.0, -75.0, -60.0, -45.0, -20.0, 20.0, 30.0, 45.0, 60.0])
    ap.add_argument("--material", default="Urea")
    ap.add_argument("--rpm", type=float, default=600.0)
    ap.add_argument("--seed2", type=int, default=2)
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    base = scene_inlet_angle(args.scene)

    header = ["turn deg", "build s", "L1"] + [f"dCV{w:.0f} pt (bound)" for w in CV_WIDTHS] + \
             ["dThrow m (bound)", "WW10 turned/row m", "WW15 turned/row m", "within"]
    print(("| " + " | ".join(header) + " |\n|" + "---|" * len(header)) if args.markdown else "\t".join(header))
    sys.stdout.flush()

    def line(label, seconds, c, within):
        row = [label, f"{seconds:.0f}", f"{c['l1']:.3f}"] + \
              [f"{c[f'dcv{w:.0f}']:+.1f} ({c[f'boundcv{w:.0f}']:.1f})" for w in CV_WIDTHS] + \
              [f"{c['dthrow']:+.2f} ({c['bound_throw']:.2f})",
               f"{c['ww10'][0]:.2f}/{c['ww10'][1]:.2f}", f"{c['ww15'][0]:.2f}/{c['ww15'][1]:.2f}", within]
        print(("| " + " | ".join(row) + " |") if args.markdown else "\t".join(row))
        sys.stdout.flush()

    validated = []
    for turn in [0.0] + args.turns:
        paths = [os.path.join(args.out, f"turn{turn:+.0f}.sqlite"), os.path.join(args.out, f"turn{turn:+.0f}_seed{args.seed2}.sqlite")]
        seconds = 0.0
        for path, seed in zip(paths, (1, args.seed2)):
            if turn == 0.0 and seed == 1:
                continue  # the table's own row
            if not os.path.exists(path):
                seconds += build_row(args, base + math.radians(turn), seed, path)
        row1 = args.table if turn == 0.0 else paths[0]
        noise = compare(args, row1, paths[1], 0.0)
        line(f"{turn:+.0f} seed {args.seed2}", 0.0, noise, "reference")
        if turn == 0.0:
            continue
        c = compare(args, args.table, paths[0], turn)
        ok = (c["l1"] <= 1.25 * noise["l1"] and
              all(abs(c[d]) <= max(c[b], 1.25 * abs(noise[d]))
                  for d, b in [("dthrow", "bound_throw")] +
                  [(f"dcv{w:.0f}", f"boundcv{w:.0f}") for w in CV_WIDTHS]))
        line(f"{turn:+.0f}", seconds, c, "yes" if ok else "no")
        if ok:
            validated.append(turn)
    # The validated range: the widest interval around 0 whose every measured turn is within.
    low = max([t for t in args.turns if t < 0 and t not in validated] or [-math.inf])
    high = min([t for t in args.turns if t > 0 and t not in validated] or [math.inf])
    inside = [t for t in validated if low < t < high] + [0.0]
    print(f"validated: {min(inside):+.0f} to {max(inside):+.0f} degrees "
          f"(the measured turns within, between the nearest ones outside)")


if __name__ == "__main__":
    main()
