#!/usr/bin/env python3
"""check_size_classes_json.py SPREAD TABLE MATERIAL RPM: `spread predict --size-classes --json` on a table of
a sieve material gives the object size_classes: SGN and UI near the sheet's (EXPECT_SGN, EXPECT_UI, within
3), class shares summing to 100 %, fine and coarse halves of the mass, and the larger classes landing
further out (mean radius increasing over the classes with at least 100 launch samples; the coarse half
beyond the fine half). Prints "ok" or the first problem (exit 1)."""
import json
import math
import os
import subprocess
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


spread, table, material, rpm = sys.argv[1:5]
out = subprocess.run([spread, "predict", "--tables", table, "--material", material, "--rpm", rpm, "--size-classes",
                      "--json"], capture_output=True, text=True)
if out.returncode != 0:
    fail(f"exit {out.returncode}: {out.stderr.strip()}")
sc = json.loads(out.stdout).get("size_classes")
if not isinstance(sc, dict):
    fail("no size_classes object")
for key, expected in (("size_guide_number", "EXPECT_SGN"), ("uniformity_index", "EXPECT_UI")):
    if abs(sc[key] - float(os.environ[expected])) > 3:
        fail(f"{key} {sc[key]:.1f}, the sheet's {os.environ[expected]}")
total = sum(c["mass_percent"] for c in sc["classes"])
if abs(total - 100.0) > 1e-6:
    fail(f"class shares sum to {total} %")
for half in ("fine", "coarse"):
    if abs(sc[half]["mass_percent"] - 50.0) > 2.0:
        fail(f"the {half} half holds {sc[half]['mass_percent']:.1f} % of the mass")
if not sc["coarse"]["mean_radius_m"] > sc["fine"]["mean_radius_m"]:
    fail(f"coarse half at {sc['coarse']['mean_radius_m']} m, not beyond the fine half's {sc['fine']['mean_radius_m']} m")
radii = [c["mean_radius_m"] for c in sc["classes"] if c["sample_count"] >= 100]
if len(radii) < 3 or any(not b > a for a, b in zip(radii, radii[1:])):
    fail(f"mean radius not increasing with size over the classes: {radii}")
for c in sc["classes"]:
    if c["sample_count"] > 0 and not (isinstance(c["cv_to_and_fro_percent"], (int, float)) and math.isfinite(c["cv_to_and_fro_percent"])):
        fail(f"class {c['lower_mm']}-{c['upper_mm']} mm without a CV")
print("ok")
