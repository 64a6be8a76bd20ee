"""Forces on the magnets of the initial layout with the dipole pairs summed
directly and by the fast multipole method. Usage: compareForces.py DIRECT.csv MULTIPOLE.csv"""
import csv
import math
import statistics
import sys


def forces(path):
    return {r["body"]: [float(r[k]) for k in ("Fx", "Fy", "Fz")] for r in csv.DictReader(open(path))}


direct, multipole = forces(sys.argv[1]), forces(sys.argv[2])
diff = {b: math.dist(direct[b], multipole[b]) for b in direct}
largest = max(math.hypot(*f) for f in direct.values())
relative = [diff[b] / math.hypot(*direct[b]) for b in direct]
print(f"{len(direct)} magnets, forces up to {largest:.3g} N: |F_multipole - F_direct| is at most "
      f"{max(diff.values()) / largest:.1e} of the largest force; per magnet, relative to its own force, "
      f"median {statistics.median(relative):.1e}, largest {max(relative):.1e}")
# The multipole sum is held to 1e-4 of each magnet's dipole pair terms, their
# magnitudes added (tests/test_dipoleMultipole.cpp); a magnet's net force can be
# much smaller than that sum. Fail only past the dipole tier's own tolerance
# (1e-3) of the scene's largest force.
sys.exit(0 if max(diff.values()) < 1e-3 * largest else 1)
