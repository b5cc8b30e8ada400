"""Compares the failed joints of two runs of the same mesh
(target/scene/out/<run>/failures.csv): how many failed in both, matched by
their mid-plane centroids at failure within 0.3 mm (the faces of the 4 mm
mesh lie millimetres apart; the bodies move tens of µm before the split),
and where they lie. Usage: pattern.py full-r1 band6-r1"""
import csv
import sys


def load(run):
    rows = csv.DictReader(open(f"target/scene/out/{run}/failures.csv"))
    return [(float(r["x"]), float(r["y"]), float(r["z"]), float(r["time"])) for r in rows]


a, b = load(sys.argv[1]), load(sys.argv[2])
for name, fs in ((sys.argv[1], a), (sys.argv[2], b)):
    ys = [f[1] * 1e3 for f in fs]
    print(f"{name}: {len(fs)} failed, max |x| {max(abs(f[0]) for f in fs) * 1e3:.2f} mm, "
          f"y from {min(ys):.1f} to {max(ys):.1f} mm, first at {min(f[3] for f in fs) * 1e6:.1f} µs")
near = lambda f, g: sum((f[k] - g[k]) ** 2 for k in range(3)) < 0.3e-3**2
both = sum(any(near(f, g) for g in b) for f in a)
print(f"in both: {both} ({both / len(a):.0%} of {sys.argv[1]}'s, {both / len(b):.0%} of {sys.argv[2]}'s)")
