#!/usr/bin/env python3
"""compare_tables.py A B: exit 0 when two launch-table files hold the same runs — same (material, rpm)
rows with identical samples, stats, convergence and provenance — ignoring created_utc (the build date).
Used by the MPI test (2 ranks vs 1 process)."""
import sqlite3
import sys

COLUMNS = ("material, rpm, source, sample_count, record_layout, record_bytes, samples, scene_hash, scene_text, "
           "effects, dt_contact_s, dt_flight_s, particle_count, software_version, stats_json, convergence_json")


def runs(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    rows = db.execute(f"SELECT {COLUMNS} FROM runs ORDER BY material, rpm").fetchall()
    db.close()
    return rows


a, b = runs(sys.argv[1]), runs(sys.argv[2])
if not a:
    sys.exit(f"{sys.argv[1]}: no runs")
if len(a) != len(b):
    sys.exit(f"run count differs: {len(a)} vs {len(b)}")
names = [c.strip() for c in COLUMNS.split(",")]
for ra, rb in zip(a, b):
    for name, va, vb in zip(names, ra, rb):
        if va != vb:
            sys.exit(f"run {ra[0]} @ {ra[1]} rpm: column {name} differs")
print(f"{len(a)} runs identical (created_utc ignored)")
