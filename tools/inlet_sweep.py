#!/usr/bin/env python3
"""Sweep of the drop point (scene [inlet] angle_rad and offset_m) for one material and disc speed.

For each setting, builds a one-row DEM launch table with lookup_builder and predicts the pattern with
`spread predict --json` at CV targets 15 % and 10 %, then prints one line per setting:

  angle, offset, build time, throw width, headline working width at 15 % and at 10 %, the bands of bout
  widths within 15 % and within 10 % (lower-upper m, lowest CV), the peak CV between the first and the
  second band (what splits them), and the centre/shoulder ratio of the transverse pattern
  (mean mass fraction of the trays nearest the centre line over the largest tray's).

Tables already built in the output directory are reused (lookup_builder skips runs it already has).

Usage: tools/inlet_sweep.py [--build DIR] [--out DIR] [--angles A,B,...] [--offsets R,S,...]
                            [--material NAME] [--rpm RPM] [--scene FILE] [--markdown]
Defaults: build/, /tmp/inlet-sweep, the default angle (1.5 rad) +-30 deg in 15 deg steps, offsets
0.08,0.12,0.16 m, Urea at 600 rpm, scenes/default.toml.
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


def build_table(args, angle, offset, path):
    cmd = ["nice", "-n", "19", os.path.join(args.build, "lookup_builder", "lookup_builder"), args.scene,
           "--output", path, "--jobs", "1", "--threads", "1",
           "--set", f"inlet.angle_rad={angle!r}", "--set", f"inlet.offset_m={offset!r}",
           "--set", f'sweep.materials=["{args.material}"]', "--set", f"sweep.rpm=[{args.rpm!r}]"]
    if os.path.exists(path):
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return None
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start


def predict(args, path, target):
    cmd = [os.path.join(args.build, "tools", "spread", "spread"), "predict", "--tables", path,
           "--material", args.material, "--rpm", repr(args.rpm), "--cv-target", repr(target), "--json"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def centre_ratio(p):
    centres = p["transverse"]["centres_m"]
    mass = p["transverse"]["mass_fraction"]
    nearest = min(abs(c) for c in centres)
    at_centre = [m for c, m in zip(centres, mass) if abs(abs(c) - nearest) < 1e-9]
    return (sum(at_centre) / len(at_centre)) / max(mass)


def gap_peak_cv(p):
    """Largest to-and-fro CV between the first band's end and the second band's start (None: one band)."""
    bands = p["bands"]["to_and_fro"]
    if len(bands) < 2:
        return None
    lo, hi = bands[0]["upper_m"], bands[1]["lower_m"]
    cvs = [c["cv_to_and_fro_percent"] for c in p["cv_curve"]
           if lo < c["bout_width_m"] < hi and c["cv_to_and_fro_percent"] is not None]
    return max(cvs) if cvs else None


def bands_text(p):
    return " ".join(f"{b['lower_m']:.2f}-{b['upper_m']:.2f}({b['lowest_cv_percent']:.1f})"
                    for b in p["bands"]["to_and_fro"]) or "none"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default="/tmp/inlet-sweep")
    ap.add_argument("--scene", default=os.path.join(ROOT, "scenes", "default.toml"))
    ap.add_argument("--angles", type=parse_list,
                    default=[1.5 + k * math.radians(15.0) for k in (-2, -1, 0, 1, 2)])
    ap.add_argument("--offsets", type=parse_list, default=[0.08, 0.12, 0.16])
    ap.add_argument("--material", default="Urea")
    ap.add_argument("--rpm", type=float, default=600.0)
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    header = ["angle rad (deg)", "offset m", "build s", "throw m", "WW15 m", "WW10 m",
              "bands CV<=15 % (lowest CV)", "gap CV15 %", "bands CV<=10 % (lowest CV)", "gap CV10 %",
              "centre/max"]
    if args.markdown:
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
    else:
        print("\t".join(header))
    sys.stdout.flush()
    for offset in args.offsets:
        for angle in args.angles:
            path = os.path.join(args.out, f"inlet_a{angle:.3f}_r{offset:.3f}.sqlite")
            seconds = build_table(args, angle, offset, path)
            p15, p10 = predict(args, path, 15.0), predict(args, path, 10.0)
            gap15, gap10 = gap_peak_cv(p15), gap_peak_cv(p10)
            row = [f"{angle:.3f} ({math.degrees(angle):.0f})", f"{offset:.2f}",
                   "cached" if seconds is None else f"{seconds:.0f}",
                   f"{p15['throw_width_m']:.2f}", f"{p15['working_width_to_and_fro_m']:.2f}",
                   f"{p10['working_width_to_and_fro_m']:.2f}",
                   bands_text(p15), "-" if gap15 is None else f"{gap15:.1f}",
                   bands_text(p10), "-" if gap10 is None else f"{gap10:.1f}", f"{centre_ratio(p15):.2f}"]
            print(("| " + " | ".join(row) + " |") if args.markdown else "\t".join(row))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
