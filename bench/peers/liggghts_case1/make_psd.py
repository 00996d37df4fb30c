#!/usr/bin/env python3
"""Discretises the Case-1 granule size distribution for LIGGGHTS: lognormal with arithmetic mean 3.2 mm,
sd 0.6 mm, truncated to exp(m ± 3s) as libspread's inlet does, into 7 equal-width diameter classes.
Prints the particletemplate/particledistribution lines (weights = mass fractions)."""
import math
mean, sd, n = 3.2e-3, 0.6e-3, 7
s2 = math.log(1 + (sd / mean) ** 2); s = math.sqrt(s2); m = math.log(mean) - s2 / 2
lo, hi = math.exp(m - 3 * s), math.exp(m + 3 * s)
pdf = lambda d: math.exp(-(math.log(d) - m) ** 2 / (2 * s2)) / (d * s * math.sqrt(2 * math.pi))
PRIMES = [15485863, 15485867, 32452867, 49979687, 49979693, 67867967, 67867979]  # LIGGGHTS seeds must be primes > 10000
w = (hi - lo) / n
cls = []
for k in range(n):
    a = lo + k * w; num = mass = 0.0
    for j in range(200):  # midpoint integration within the class
        d = a + (j + 0.5) * w / 200; p = pdf(d) * w / 200; num += p; mass += p * d ** 3
    cls.append(((mass / num) ** (1 / 3), num, mass))
tm = sum(c[2] for c in cls)
lines = []
for k, (d, num, mass) in enumerate(cls):
    lines.append("fix pts%d all particletemplate/sphere %d atom_type 1 density constant 1800 radius constant %.6e" % (k + 1, PRIMES[k], d / 2))
lines.append("fix pdd all particledistribution/discrete 32452843 %d " % n + " ".join("pts%d %.6f" % (k + 1, c[2] / tm) for k, c in enumerate(cls)))
print("\n".join(lines))
print("# dmax %.4e m, number-mean d %.4e m" % (hi, sum(c[0] * c[1] for c in cls) / sum(c[1] for c in cls)))
