#!/usr/bin/env python3
"""Writes drum.data: the particles of bench/bench_drum.cpp, placed exactly as
libspread/physics/drum/drum_packing.cpp grid_packing(scene, 0.999) places them (same count, same order).
Scene: R 0.1 m, L 0.09 m, fill 0.4, bed solid fraction 0.6, one species d 4 mm, rho 2500."""
import math
R, L, fill, solid = 0.1, 0.09, 0.4, 0.6
d, rho = 0.004, 2500.0
h = 0.999 * d
rmax = 0.5 * d
v = math.pi / 6 * d**3
n = int(max(1.0, round(fill * math.pi * R * R * L * solid / v)))
rho_max = R - 0.5 * h - 1e-3 * rmax
nxy = int(math.floor(rho_max / h))
zs = []
z = 0.5 * h
while z <= L - 0.5 * h + 1e-12:
    zs.append(z); z += h
nodes = []
for i in range(-nxy, nxy + 1):
    for j in range(-nxy, nxy + 1):
        x, y = i * h, j * h
        if math.hypot(x, y) > rho_max: continue
        for z in zs: nodes.append((y, x, z))
nodes.sort()
assert n <= len(nodes)
with open("drum.data", "w") as f:
    f.write("bench_drum grid packing (make_drum_data.py)\n\n%d atoms\n1 atom types\n\n" % n)
    f.write("%g %g xlo xhi\n%g %g ylo yhi\n%g %g zlo zhi\n\nAtoms # sphere\n\n" % (-R - 0.005, R + 0.005, -R - 0.005, R + 0.005, -0.001, L + 0.001))
    for k in range(n):
        y, x, z = nodes[k]
        f.write("%d 1 %.9g %.9g %.17g %.17g %.17g\n" % (k + 1, d, rho, x, y, z))
print(n, "particles")
