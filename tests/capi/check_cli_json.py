#!/usr/bin/env python3
"""check_cli_json.py KIND SPREAD ARGS...: runs `SPREAD ARGS...`, parses its stdout as JSON and checks
every key the CLI documents for that command (types and plausible values), printing "ok" or the first
problem (exit 1).

  predict    throw_width_m, working_width_to_and_fro_m, working_width_racetrack_m, cv_to_and_fro_percent,
             mean_radius_m,
             radial_width_m, and with --repeat the median time_per_prediction_us
  trajectory landing_position [x, y, z] (m, z on the ground), flight_time (s), steps
  inspect    materials[].name with their rpm rows and sample counts (EXPECT_* environment variables
             give the expected materials, rpm rows and samples per run)
"""
import json
import math
import os
import subprocess
import sys



def expected_rpm_rows():
    """The rpm rows the table should have: EXPECT_RPM (comma-separated) or the [sweep] rpm list of the
    scene file EXPECT_RPM_FROM_SCENE names (so the test follows the bundled scene)."""
    if "EXPECT_RPM" in os.environ:
        return [float(v) for v in os.environ["EXPECT_RPM"].split(",")]
    import tomllib
    with open(os.environ["EXPECT_RPM_FROM_SCENE"], "rb") as f:
        return [float(v) for v in tomllib.load(f)["sweep"]["rpm"]]

def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def number(obj, key, where, positive=False):
    if key not in obj:
        fail(f"{where}: key '{key}' missing (keys: {sorted(obj)})")
    value = obj[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        fail(f"{where}: '{key}' is not a finite number: {value!r}")
    if positive and not value > 0:
        fail(f"{where}: '{key}' must be > 0, got {value}")
    return value


def check_predict(out, args):
    for key in ("throw_width_m", "cv_to_and_fro_percent", "mean_radius_m", "radial_width_m"):
        number(out, key, "predict", positive=True)
    # One name per quantity across the commands (`calibrate tray` writes the same keys).
    widths = {}
    for mode in ("to_and_fro", "racetrack"):
        key = f"working_width_{mode}_m"
        widths[mode] = number(out, key, "predict", positive=True)
        if widths[mode] > out["throw_width_m"] + 1e-9:
            fail(f"predict: {key} {widths[mode]} m exceeds the throw width {out['throw_width_m']} m")
        number(out, f"working_width_{mode}_se_m", "predict", positive=True)
    if out["cv_to_and_fro_percent"] > 1000:
        fail(f"predict: cv_to_and_fro_percent {out['cv_to_and_fro_percent']} implausible")
    # Uncertainty, crossings, the CV(W) curve and the wider bands it allows, per overlap.
    for key in ("throw_width_se_m", "cv_to_and_fro_se_percent"):
        number(out, key, "predict", positive=True)
    for key in ("cv_target_crossings", "bands", "band_count", "first_band_width_m"):
        if not isinstance(out.get(key), dict) or set(out[key]) != {"to_and_fro", "racetrack"}:
            fail(f"predict: '{key}' is not an object with to_and_fro and racetrack: {out.get(key)!r}")
    curve = out.get("cv_curve")
    if not isinstance(curve, list) or not curve or not all(
            isinstance(p, dict) and {"bout_width_m", "cv_to_and_fro_percent", "cv_racetrack_percent"} <= set(p)
            for p in curve):
        fail(f"predict: 'cv_curve' is not a list of {{bout_width_m, cv_to_and_fro_percent, cv_racetrack_percent}}: {curve!r}")
    # Every band: ordered, the headline's upper end is the working width, the first band's is
    # first_band_width_m, and a band is established exactly when its lowest CV's 95 % bound is within
    # the target.
    target = out["cv_target_percent"]
    for mode, bands in out["bands"].items():
        if out["band_count"][mode] < len(bands):
            fail(f"predict: band_count {out['band_count'][mode]} ({mode}) below the {len(bands)} bands listed")
        previous_upper = 0.0
        for band in bands:
            if not (previous_upper <= band["lower_m"] <= band["bout_width_m"] <= band["upper_m"]):
                fail(f"predict: band {band!r} ({mode}) is not ordered after {previous_upper} m")
            previous_upper = band["upper_m"]
            if band["cv_percent"] is None or band["cv_percent"] > target + 1e-9:
                fail(f"predict: band {band!r} ({mode}) has a CV above the target at its widest bout")
            bound = band["lowest_cv_percent"] + 1.96 * (band["lowest_cv_se_percent"] or float("inf"))
            if band["established"] != (bound <= target):
                fail(f"predict: band {band!r} ({mode}): established disagrees with its lowest CV's 95 % bound {bound}")
        headline = [b for b in bands if b["headline"]]
        if bands and (len(headline) != 1 or headline[0]["upper_m"] != widths[mode]):
            fail(f"predict: the headline band ({mode}) does not end at the working width {widths[mode]} m: {bands!r}")
        if bands and bands[0]["upper_m"] != out["first_band_width_m"][mode]:
            fail(f"predict: first_band_width_m ({mode}) is not the first band's upper end")
    if "--repeat" in args:
        number(out, "time_per_prediction_us", "predict", positive=True)
        if out.get("repeat") != int(args[args.index("--repeat") + 1]):
            fail(f"predict: 'repeat' {out.get('repeat')!r} differs from --repeat")
    elif "time_per_prediction_us" in out:
        fail("predict: time_per_prediction_us present without --repeat")


def check_trajectory(out, args):
    position = out.get("landing_position")
    if not (isinstance(position, list) and len(position) == 3):
        fail(f"trajectory: 'landing_position' is not [x, y, z]: {position!r}")
    for i, axis in enumerate("xyz"):
        number({axis: position[i]}, axis, "trajectory.landing_position")
    ground_z = float(args[args.index("--ground-z") + 1]) if "--ground-z" in args else 0.0
    if abs(position[2] - ground_z) > 1e-6:
        fail(f"trajectory: landing z {position[2]} m is not the ground {ground_z} m")
    number(out, "flight_time", "trajectory", positive=True)
    steps = out.get("steps")
    if not (isinstance(steps, int) and not isinstance(steps, bool) and steps > 0):
        fail(f"trajectory: 'steps' is not a positive integer: {steps!r}")
    # Launched forward (+x) from 1 m: it must land ahead and take at least the vacuum fall time.
    if "EXPECT_MIN_X" in os.environ and not position[0] >= float(os.environ["EXPECT_MIN_X"]):
        fail(f"trajectory: landed at x {position[0]} m, expected >= {os.environ['EXPECT_MIN_X']}")
    if "EXPECT_MIN_TIME" in os.environ and not out["flight_time"] >= float(os.environ["EXPECT_MIN_TIME"]):
        fail(f"trajectory: flight_time {out['flight_time']} s, expected >= {os.environ['EXPECT_MIN_TIME']}")


def check_inspect(out, args):
    materials = out.get("materials")
    if not (isinstance(materials, list) and materials):
        fail(f"inspect: 'materials' is not a non-empty list: {materials!r}")
    names = []
    for m in materials:
        if not isinstance(m.get("name"), str) or not m["name"]:
            fail(f"inspect: a material without a name: {m!r}")
        names.append(m["name"])
        rpm, counts = m.get("rpm"), m.get("sample_counts")
        if not (isinstance(rpm, list) and isinstance(counts, list) and len(rpm) == len(counts) and rpm):
            fail(f"inspect: material {m['name']}: rpm rows {rpm!r} and sample_counts {counts!r} do not match")
        if rpm != sorted(rpm):
            fail(f"inspect: material {m['name']}: rpm rows not ascending: {rpm}")
        if "EXPECT_RPM" in os.environ or "EXPECT_RPM_FROM_SCENE" in os.environ:
            expected = expected_rpm_rows()
            if rpm != expected:
                fail(f"inspect: material {m['name']}: rpm rows {rpm}, expected {expected}")
        if "EXPECT_SAMPLES" in os.environ and any(c != int(os.environ["EXPECT_SAMPLES"]) for c in counts):
            fail(f"inspect: material {m['name']}: sample counts {counts}, expected {os.environ['EXPECT_SAMPLES']} each")
    if "EXPECT_MATERIALS" in os.environ:
        expected = sorted(os.environ["EXPECT_MATERIALS"].split(","))
        if sorted(names) != expected:
            fail(f"inspect: materials {sorted(names)}, expected {expected}")
    runs = out.get("runs", [])
    if len(runs) != sum(len(m["rpm"]) for m in materials):
        fail(f"inspect: {len(runs)} runs but the materials list {sum(len(m['rpm']) for m in materials)} rpm rows")


def main():
    if len(sys.argv) < 3:
        fail("usage: check_cli_json.py predict|trajectory|inspect SPREAD ARGS...")
    kind, command = sys.argv[1], sys.argv[2:]
    checks = {"predict": check_predict, "trajectory": check_trajectory, "inspect": check_inspect}
    if kind not in checks:
        fail(f"unknown kind {kind!r}")
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{' '.join(command)} exited {run.returncode}: {run.stderr.strip()}")
    try:
        out = json.loads(run.stdout)
    except json.JSONDecodeError as e:
        fail(f"stdout is not JSON ({e}): {run.stdout[:200]!r}")
    if not isinstance(out, dict):
        fail(f"stdout is JSON but not an object: {out!r}")
    checks[kind](out, command[2:])
    print("ok")


if __name__ == "__main__":
    main()
