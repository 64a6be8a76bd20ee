"""magfoam.Case: the same numbers as the apps, bit for bit. forces() against
magForces' postProcessing/forces.csv (%.10g: every printed digit), run()
against magFoam's postProcessing/bodies.csv, each on its own copy of a case."""
import csv
import re
import subprocess

import numpy as np

import magfoam as mf


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def g10(x):
    return "%.10g" % x


def test_forces_equal_magForces_bit_for_bit(copy_case, app):
    python_copy, app_copy = copy_case("tutorials/twoCubes"), copy_case("tutorials/twoCubes", "app")
    subprocess.run([app("magForces"), "-case", str(app_copy)], check=True, capture_output=True)
    rows = read_csv(app_copy / "postProcessing/forces.csv")

    r = mf.Case(python_copy).forces()
    k, n = r["F"].shape[:2]
    assert len(rows) == k * n == 301 * 2
    for s in range(k):
        for b in range(n):
            row = rows[s * n + b]
            assert row["body"] == r["bodies"][b] and int(row["step"]) == r["step"][s]
            got = [*r["F"][s, b], *r["T"][s, b], *r["Tmag"][s, b], r["energy"][s, b]]
            want = [row[c] for c in ("Fx", "Fy", "Fz", "Tx", "Ty", "Tz", "TmagX", "TmagY", "TmagZ", "energy")]
            assert [g10(x) for x in got] == want, f"step {s} body {b}"


def test_forces_twice_and_system_agree(copy_case):
    c = mf.Case(copy_case("tutorials/twoCubes"))
    a, b = c.forces(), c.forces()
    np.testing.assert_array_equal(a["F"], b["F"])  # each call starts from the case's state
    # Case.system(): the case's models and bodies; the sweep's first offset
    s = c.system()
    s.set_pose("top", position=[0, 0, 0.01 + a["offset"][0]])
    np.testing.assert_array_equal(s.wrench("top")[0], a["F"][0, 1])


def test_run_equals_magFoam(copy_case, app):
    python_copy, app_copy = copy_case("tutorials/dropMagnet"), copy_case("tutorials/dropMagnet", "app")
    end = 0.02  # s: four write times of the tutorial's 0.3 s
    control = app_copy / "system/controlDict.yaml"
    control.write_text(re.sub(r"(?m)^endTime:.*$", f"endTime: {end}", control.read_text()))
    subprocess.run([app("magFoam"), "-case", str(app_copy)], check=True, capture_output=True)

    r = mf.Case(python_copy).run(end_time=end)
    # the same writer wrote both folders' files: identical bytes
    for name in ("bodies.csv", "energy.csv"):
        assert (python_copy / "postProcessing" / name).read_text() == (app_copy / "postProcessing" / name).read_text()
    # and the arrays in memory are what it wrote (ResultsWriter: %.12g poses, %.10g the rest)
    rows = read_csv(app_copy / "postProcessing/bodies.csv")
    k, n = r["position"].shape[:2]
    assert len(rows) == k * n and k == 5
    cols = [("position", "x y z", "%.12g"), ("quaternion", "qw qx qy qz", "%.12g"), ("velocity", "vx vy vz", "%.10g"),
            ("angularVelocity", "wx wy wz", "%.10g"), ("F", "Fx Fy Fz", "%.10g"), ("T", "Tx Ty Tz", "%.10g")]
    for s in range(k):
        for b in range(n):
            row = rows[s * n + b]
            assert row["body"] == r["bodies"][b] and row["time"] == g10(r["time"][s])
            for key, names, fmt in cols:
                assert [fmt % x for x in r[key][s, b]] == [row[c] for c in names.split()], (s, b, key)
    energy = read_csv(app_copy / "postProcessing/energy.csv")
    assert ["%.12g" % x for x in r["energy"]["total"]] == [e["total"] for e in energy]
