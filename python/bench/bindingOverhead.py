#!/usr/bin/env python3
"""Benchmark (not a test): what the Python binding costs beside the C++ apps
on the same case, the same points and one thread (docs/python.md#performance).

- field: System.field(P, A=True, H=True) against magField's own timing of the
  same evaluation (its log: "field X ms"; B, A and H, without its files), for
  n = 1e2..1e5 random points around a 1 cm cube (tutorials/cubeField).
- sweep: System.sweep and Case.forces per pose against magForces' "ms each"
  on tutorials/twoCubes (301 poses of the upper cube).
- the binding's own cost, measured in one process so that the load of the
  machine cancels: field() on a system without bodies (conversion, GIL,
  result arrays; no physics) against field() on the cube, and Case.forces'
  wall time against the C++ loop it times inside the same call.
Each timing is the best of `--repeat` runs. An app evaluates once, on models
built for the run (MBM builds its per-shape tables on first use), so every
Python timing is the first evaluation of a freshly built system too ("warm":
a second call on the same system). Usage:
  PYTHONPATH=build/python python3 python/bench/bindingOverhead.py [--build build] [--repeat 5]
"""
import argparse
import pathlib
import re
import shutil
import subprocess
import tempfile
import time

import numpy as np

import magfoam as mf

ROOT = pathlib.Path(__file__).resolve().parents[2]


def best(make, run, repeat):
    """Best time of run(make()), make() not timed."""
    times = []
    for _ in range(repeat):
        x = make()
        t0 = time.perf_counter()
        run(x)
        times.append(time.perf_counter() - t0)
    return min(times)


def app_log(app, case, pattern, repeat):
    """Best of the app's own timings (ms) matched by `pattern` in its log."""
    values = []
    for _ in range(repeat):
        out = subprocess.run([app, "-case", str(case), "-threads", "1"], check=True, capture_output=True, text=True).stdout
        values.append(float(re.search(pattern, out).group(1)))
    return min(values)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    bin_ = pathlib.Path(args.build) / "bin"
    work = pathlib.Path(tempfile.mkdtemp(prefix="magfoam-bench-"))
    try:
        print("field: points per second, one thread; overhead = Python / magField - 1")
        print(f"{'points':>8} {'magField ms':>12} {'Python ms':>10} {'Python pts/s':>13} {'overhead':>9} {'warm ms':>9}")
        case = work / "cubeField"
        shutil.copytree(ROOT / "tutorials/cubeField", case, ignore=shutil.ignore_patterns("postProcessing", "log.*"))
        rng = np.random.default_rng(0)
        binding = []
        for n in (100, 1000, 10000, 100000):
            P = rng.uniform(-0.02, 0.02, (n, 3))
            np.savetxt(case / "points.csv", P, delimiter=",", fmt="%.17g")
            (case / "system/fieldDict.yaml").write_text("sets:\n  - {name: pts, type: points, file: points.csv}\n")
            cpp = app_log(str(bin_ / "magField"), case, r"pts: \d+ points -> .* \(field ([0-9.]+) ms", args.repeat)
            # the points as magField read them (%.17g reads back exactly)
            P = np.loadtxt(case / "points.csv", delimiter=",").reshape(-1, 3)
            def fresh():  # a case read again: new shapes, no table built yet
                return mf.Case(case, threads=1).system()

            field = lambda s: s.field(P, A=True, H=True)  # noqa: E731
            py = best(fresh, field, args.repeat) * 1e3

            def warmed():
                s = fresh()
                field(s)
                return s
            warm = best(warmed, field, args.repeat) * 1e3
            print(f"{n:>8} {cpp:>12.3f} {py:>10.3f} {n / py * 1e3:>13.4g} {py / cpp - 1:>+9.1%} {warm:>9.3f}")
            empty = best(mf.System, field, args.repeat) * 1e3
            binding.append(f"{n:>8} {empty:>10.3f} ms of {warm:.3f} ms: {empty / warm:.1%}")

        print("\nsweep: cost per pose, two 1 cm cubes (tutorials/twoCubes, 301 poses), one thread")
        case = work / "twoCubes"
        shutil.copytree(ROOT / "tutorials/twoCubes", case, ignore=shutil.ignore_patterns("postProcessing", "log.*", "*.png"))
        cpp = app_log(str(bin_ / "magForces"), case, r"(?m)^301 evaluation\(s\), ([0-9.]+) ms each", args.repeat)
        offsets = np.linspace(-0.01, 0.02, 301)  # the forcesDict's
        P = np.c_[np.zeros((301, 2)), 0.01 + offsets]

        def fresh():
            return mf.Case(case, threads=1).system()
        sweep = best(fresh, lambda s: s.sweep("top", positions=P), args.repeat) * 1e3 / 301
        forces = best(lambda: mf.Case(case, threads=1), lambda x: x.forces(), args.repeat) * 1e3 / 301
        # the C++ loop inside Case.forces, timed as magForces times its own
        loop = min(mf.Case(case, threads=1).forces()["seconds"] for _ in range(args.repeat)) * 1e3 / 301

        def wall_minus_loop():
            c = mf.Case(case, threads=1)
            t0 = time.perf_counter()
            r = c.forces()
            return time.perf_counter() - t0 - r["seconds"]
        outside = min(wall_minus_loop() for _ in range(args.repeat)) * 1e3 / 301

        def one_by_one(s):
            for p in P:
                s.set_pose("top", position=p)
                s.wrench("top")
        single = best(fresh, one_by_one, args.repeat) * 1e3 / 301
        print(f"  magForces (its own timing)       {cpp * 1e3:8.1f} us/pose")
        print(f"  System.sweep (one call)          {sweep * 1e3:8.1f} us/pose  ({sweep / cpp - 1:+.1%})")
        print(f"  Case.forces (the forcesDict)     {forces * 1e3:8.1f} us/pose  ({forces / cpp - 1:+.1%})")
        print(f"    its C++ loop, timed inside     {loop * 1e3:8.1f} us/pose  ({loop / cpp - 1:+.1%})")
        print(f"  set_pose + wrench per pose       {single * 1e3:8.1f} us/pose  ({single / cpp - 1:+.1%})")
        print("\nthe binding's own cost, in one process")
        print("  field() without bodies against field() on the cube (warm), B, A and H:")
        for line in binding:
            print("  " + line)
        print(f"  Case.forces outside its C++ loop: {outside * 1e3:.2f} us/pose "
              f"({outside / loop:.1%} of the loop)")
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
