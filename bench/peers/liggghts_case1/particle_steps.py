#!/usr/bin/env python3
"""Particle-steps of a LIGGGHTS log: thermo every 422 steps (= insert_every), so the atom count printed
at step 422(k+1) is the count during steps 422k+1 … 422(k+1). Prints particle-steps, loop time and rate."""
import re, sys
log = open(sys.argv[1] if len(sys.argv) > 1 else "log.case1").read()
rows = [(int(a), int(b)) for a, b in re.findall(r"^\s+(\d+)\s+(\d+)\s+\S+\s+\S+\s*$", log, re.M)]
ps, prev = 0, rows[0][0]
for step, atoms in rows[1:]:
    ps += atoms * (step - prev); prev = step
loop = float(re.search(r"Loop time of (\S+)", log).group(1))
print("steps %d particles_end %d particle_steps %d loop_wall_s %.3f particle_steps_per_s %.4g" % (prev, rows[-1][1], ps, loop, ps / loop))
