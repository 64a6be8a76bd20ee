#!/usr/bin/env python3
"""Charts of the magBench studies: accuracy-cost (log-log, Pareto front),
divergence (force and error vs gap), switch error, and the timing studies
table1 (paper Table 1), table2 (whole cases) and scaling (ms per step vs
number of magnets). PNGs in expected/; a study without its CSV is skipped."""
import csv
import math
import pathlib
import sys

import matplotlib.pyplot as plt

here = pathlib.Path(__file__).resolve().parent
post, out = here / "postProcessing", here / "expected"
out.mkdir(exist_ok=True)


def rows(name):
    path = post / f"{name}.csv"
    return list(csv.DictReader(open(path))) if path.exists() else []


def accuracy_cost():
    data = rows("accuracyCost")
    if not data:
        return
    configs = list(dict.fromkeys(r["configuration"] for r in data))
    methods = list(dict.fromkeys(r["method"] for r in data))
    cols = 3
    fig, axes = plt.subplots(math.ceil(len(configs) / cols), cols, figsize=(15, 4.2 * math.ceil(len(configs) / cols)))
    axes = axes.flatten()
    for ax, conf in zip(axes, configs):
        pts = []
        for m in methods:
            sel = [r for r in data if r["configuration"] == conf and r["method"] == m]
            t = [1e6 * float(r["seconds"]) for r in sel]
            e = [max(float(r["relError"]), 1e-16) for r in sel]
            ax.loglog(t, e, "o-", ms=3, label=m)
            pts += list(zip(t, e))
        # Pareto front: no other point both cheaper and more accurate.
        front = sorted(p for p in pts if not any(q[0] <= p[0] and q[1] < p[1] for q in pts if q != p))
        ax.loglog([p[0] for p in front], [p[1] for p in front], "k--", lw=1, alpha=0.6, label="Pareto front")
        ax.set_title(conf)
        ax.set_xlabel("CPU time per force evaluation [us]")
        ax.set_ylabel("relative force error")
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[len(configs):]:
        ax.axis("off")
    axes[0].legend(fontsize=8)
    fig.suptitle("Accuracy vs cost: two 1 cm cubes, 1 T (error vs exact)")
    fig.tight_layout()
    fig.savefig(out / "accuracyCost.png", dpi=90)


def divergence():
    data = rows("divergence")
    if not data:
        return
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(13, 4.5))
    keys = list(dict.fromkeys((r["method"], r["n"]) for r in data))
    first = [r for r in data if (r["method"], r["n"]) == keys[0]]
    ax.plot([100 * float(r["gap"]) for r in first], [float(r["exactFz"]) for r in first], "k:", lw=2,
            label="exact (Akoun-Yonnet)")
    for m, n in keys:
        sel = [r for r in data if (r["method"], r["n"]) == (m, n)]
        g = [100 * float(r["gap"]) for r in sel]
        f = [float(r["Fz"]) for r in sel]
        ax.plot(g, f, lw=1, label=f"{m} n={n}")
        pos = [(x, float(r["relError"])) for x, r in zip(g, sel) if x > 0]
        ax2.semilogy([p[0] for p in pos], [max(p[1], 1e-16) for p in pos], lw=1, label=f"{m} n={n}")
    ax.set_ylim(-150, 150)
    ax.set_xlabel("gap d [cm]")
    ax.set_ylabel("Fz on the upper cube [N]")
    ax.set_title("Force through contact and overlap (paper Fig. 4b/4d)")
    ax.legend(fontsize=7)
    ax2.set_xlabel("gap d [cm]")
    ax2.set_ylabel("relative error")
    ax2.set_title("Error for d > 0 (paper Fig. 4c)")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "divergence.png", dpi=90)


def switch_error():
    data = rows("switchError")
    if not data:
        return
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    for t in list(dict.fromkeys(r["threshold"] for r in data)):
        sel = [r for r in data if r["threshold"] == t]
        ax.semilogy([100 * float(r["gap"]) for r in sel], [max(float(r["relError"]), 1e-16) for r in sel], "o-",
                    ms=3, label=f"threshold {t}")
    ax.set_xscale("log")
    ax.set_xlabel("gap d [cm]")
    ax.set_ylabel("relative force error")
    ax.set_title("Hybrid error vs gap, per switch threshold")
    ax.legend(fontsize=7)
    ts = list(dict.fromkeys(r["threshold"] for r in data))
    worst = [max(float(r["relError"]) for r in data if r["threshold"] == t) for t in ts]
    cost = [sum(1e6 * float(r["seconds"]) for r in data if r["threshold"] == t) /
            len([r for r in data if r["threshold"] == t]) for t in ts]
    ax2.semilogy([float(t) for t in ts], worst, "o-", label="worst error over gaps")
    ax2.set_xlabel("switch threshold [bounding radii]")
    ax2.set_ylabel("worst relative error")
    ax3 = ax2.twinx()
    ax3.plot([float(t) for t in ts], cost, "s--", color="tab:red", label="mean time [us]")
    ax3.set_ylabel("mean time per evaluation [us]", color="tab:red")
    ax2.set_title("Switch threshold: error vs cost")
    fig.tight_layout()
    fig.savefig(out / "switchError.png", dpi=90)


def table1():
    data = rows("table1")
    if not data:
        return
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ns = list(dict.fromkeys(r["n"] for r in data))
    threads = list(dict.fromkeys(r["threads"] for r in data))
    width = 0.8 / (len(threads) + 1)
    x = range(len(ns))
    for k, t in enumerate(threads):
        ms = [next(float(r["msPerStep"]) for r in data if r["n"] == n and r["threads"] == t) for n in ns]
        ax.bar([i + k * width for i in x], ms, width, label=f"magFoam, {t} thread(s)")
    paper = [next(float(r["paperMs"]) for r in data if r["n"] == n) for n in ns]
    ax.bar([i + len(threads) * width for i in x], paper, width, color="0.6", label="paper, one core")
    ax.set_yscale("log")
    ax.set_xticks([i + 0.4 - width / 2 for i in x])
    ax.set_xticklabels([f"n={float(n):g}\n({next(r['samples'] for r in data if r['n'] == n)} samples)" for n in ns])
    ax.set_ylabel("ms per step (magnetic part)")
    ax.set_title("Table 1: Fig. 6 cubes, MBM regular n x n per face")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "table1.png", dpi=90)


def table2():
    data = rows("table2")
    if not data:
        return
    # Per case: the magnetic part at each thread count (the case's own
    # backend's runs) and the rigid-body step on each backend (one thread),
    # on a log scale: the cases span three decades.
    cases = list(dict.fromkeys(r["case"] for r in data))
    threads = sorted({int(r["threads"]) for r in data})
    backends = list(dict.fromkeys(r.get("backend") or "" for r in data))
    series = [(f"magnetic, {t} thread{'s' if t > 1 else ''}",
               lambda c, t=t: [float(r["msMagnetic"]) for r in data if r["case"] == c and int(r["threads"]) == t])
              for t in threads]
    series += [(f"rigid body, {b}, 1 thread",
                lambda c, b=b: [float(r["msRigid"]) for r in data
                                if r["case"] == c and (r.get("backend") or "") == b and int(r["threads"]) == threads[0]])
               for b in backends]
    fig, ax = plt.subplots(figsize=(9, 4.2))
    width = 0.8 / len(series)
    for k, (label, values) in enumerate(series):
        ys = [min(values(c)) if values(c) else float("nan") for c in cases]
        ax.bar([i + (k - (len(series) - 1) / 2) * width for i in range(len(cases))], ys, width, label=label)
    ax.set_yscale("log")
    ax.set_xticks(range(len(cases)))
    ax.set_xticklabels([f"{pathlib.Path(c).name}\n{next(r['bodies'] for r in data if r['case'] == c)} bodies"
                        for c in cases], fontsize=8)
    ax.set_ylabel("ms per step (log scale)")
    ax.set_title("Cost per step of whole cases (20 steps from the start; table2)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "table2.png", dpi=90)


def scaling():
    data = rows("scaling")
    if not data:
        return
    fields = list(dict.fromkeys(r.get("field", "hybrid") for r in data))
    threads = list(dict.fromkeys(r["threads"] for r in data))
    fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 4.4))
    for fi, f in enumerate(fields):
        for ti, t in enumerate(threads):
            sel = [r for r in data if r.get("field", "hybrid") == f and r["threads"] == t]
            n = [int(r["bodies"]) for r in sel]
            ms = [float(r["msPerStep"]) for r in sel]
            style = dict(color=f"C{fi}", ls="-" if ti == 0 else "--", marker="o", ms=3)
            ax.loglog(n, ms, label=f"{f}, {t} thread(s)", **style)
            ax2.semilogx(n, [1e3 * m / k for m, k in zip(ms, n)], label=f"{f}, {t} thread(s)", **style)
            if ti == 0 and "farFieldMs" in sel[0]:
                multipole = [int(r["bodies"]) for r in sel if r.get("dipoleSum") == "multipole"]
                method = f" (multipole from N = {min(multipole)})" if multipole else ""
                ax2.semilogx(n, [1e3 * float(r["farFieldMs"]) / k for r, k in zip(sel, n)], color=f"C{fi}", ls=":",
                             lw=1.2, label=f"{f}, 1 thread: dipole sum, timed in the step{method}")
            if ti == 0 and fi == 0 and "directFarFieldMs" in sel[0]:
                ax2.semilogx(n, [1e3 * float(r["directFarFieldMs"]) / k for r, k in zip(sel, n)], color="k", ls=":",
                             lw=1.2, label=f"{f}, 1 thread: direct dipole sum (O(N^2))")
            if ti == 0:
                for key, mk in (("nearPairs", "s"), ("farPairs", "^"), ("dipolePairs", "o")):
                    ax3.loglog(n, [int(r[key]) / k or float("nan") for r, k in zip(sel, n)], color=f"C{fi}",
                               marker=mk, ms=3, label=f"{f}: {key[:-5]}")  # 0: not drawn
    first = [r for r in data if r.get("field", "hybrid") == fields[0] and r["threads"] == threads[0]]
    n = [int(r["bodies"]) for r in first]
    ref = float(first[-1]["msPerStep"])
    ax.loglog(n, [ref * (k / n[-1]) ** 2 for k in n], "k:", lw=1, label="~ N^2")
    ax.loglog(n, [ref * k / n[-1] for k in n], "k-.", lw=1, label="~ N")
    ax.set_xlabel("magnets N")
    ax.set_ylabel("ms per step (wrenches)")
    ax.set_title("Hybrid: cost per step vs number of magnets")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax2.set_xlabel("magnets N")
    ax2.set_ylabel("us per magnet per step")
    ax2.set_title("Cost per magnet (flat = linear)")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=6)
    ax3.set_xlabel("magnets N")
    ax3.set_ylabel("pairs per magnet")
    ax3.set_title("Pairs per magnet in each tier (constant density)")
    ax3.grid(True, which="both", alpha=0.3)
    ax3.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(out / "scaling.png", dpi=90)


def kernel():
    data = rows("kernel")
    if not data:
        return
    meshes = list(dict.fromkeys(r["mesh"] for r in data))
    labels = [f"{m}\n({next(r['triangles'] for r in data if r['mesh'] == m)} tri)" for m in meshes]
    # the blocked kernel in each copy timed (isa: avx2, avx512; older CSVs have none)
    isas = list(dict.fromkeys(r.get("isa") or "" for r in data if r["path"] == "fast"))

    def fast(isa):
        return f"fast {isa}".strip()

    def pick(m, o, p, isa, key):
        return next((float(r[key]) for r in data if r["mesh"] == m and r["outputs"] == o and r["path"] == p
                     and (p == "reference" or (r.get("isa") or "") == isa)), float("nan"))

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(12, 4.2))
    series = [(o, "reference", "") for o in ("A+B", "B")] + [(o, "fast", i) for o in ("A+B", "B") for i in isas]
    width = 0.8 / len(series)
    for k, (o, p, isa) in enumerate(series):
        ns = [pick(m, o, p, isa, "nsPerPoint") for m in meshes]
        label = f"{o} {p if p == 'reference' else fast(isa)}"
        ax.bar([i + (k - (len(series) - 1) / 2) * width for i in range(len(meshes))], ns, width, label=label)
    ax.set_yscale("log")
    ax.set_xticks(range(len(meshes)), labels)
    ax.set_ylabel("ns per point (one core)")
    ax.set_title("MBM field kernel: cost per point")
    ax.legend(fontsize=8)
    speedups = [(o, i) for o in ("A+B", "B") for i in isas]
    width = 0.8 / len(speedups)
    for k, (o, isa) in enumerate(speedups):
        sp = [pick(m, o, "fast", isa, "speedup") for m in meshes]
        ax2.bar([i + (k - (len(speedups) - 1) / 2) * width for i in range(len(meshes))], sp, width,
                label=f"{o} {fast(isa)}")
    ax2.set_xticks(range(len(meshes)), labels)
    ax2.set_ylabel("speed-up, fast / reference")
    ax2.set_title("SIMD kernel vs face-by-face reference")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "kernel.png", dpi=90)


def tolerance():
    """Adaptive quadrature: requested tolerance vs achieved force error; then, for
    representative placements, error against samples and against time per evaluation,
    beside gauss and the paper's regular rule."""
    data = rows("tolerance")
    if not data:
        return
    colours = {"separated": "tab:blue", "near": "tab:green", "touching": "tab:red", "overlap": "tab:purple"}
    fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(18, 5.5))
    names = []
    for r in data:
        if r["placement"] not in names:
            names.append(r["placement"])
    for name in names:
        sel = [r for r in data if r["placement"] == name and r["rule"] == "adaptive"]
        kind = sel[0]["kind"]
        ax.loglog([float(r["parameter"]) for r in sel], [max(float(r["forceError"]), 1e-13) for r in sel], "o-",
                  color=colours[kind], ms=3, lw=0.8, label=f"{name} ({kind})")
    ax.loglog([1e-8, 1e-2], [1e-8, 1e-2], "k--", lw=1, label="achieved = requested")
    ax.set_xlabel("requested tolerance")
    ax.set_ylabel("achieved force error |F - F_ref| / |F_ref|")
    ax.set_title("Is the tolerance honest? (two 1 cm cubes, adaptive)")
    ax.legend(fontsize=6, ncol=2)
    ax.grid(alpha=0.3, which="both")
    shown = {"gap 1 mm": "tab:blue", "offset (3, 2) mm, gap 1 mm": "tab:cyan", "gap 1 um": "tab:green",
             "offset face (3, 2) mm": "tab:red", "rotated footprint 30 deg": "tab:orange"}
    styles = {"adaptive": "o-", "gauss": "s--", "regular": "^:"}
    for name, colour in shown.items():
        for rule in ["adaptive", "gauss", "regular"]:
            sel = sorted((r for r in data if r["placement"] == name and r["rule"] == rule),
                         key=lambda r: int(r["samples"]))
            if not sel:
                continue
            err = [max(float(r["forceError"]), 1e-13) for r in sel]
            label = f"{name}, {rule}"
            ax2.loglog([int(r["samples"]) for r in sel], err, styles[rule], color=colour, ms=3, lw=0.9, label=label)
            ax3.loglog([1e6 * float(r["secondsPerEval"]) for r in sel], err, styles[rule], color=colour, ms=3,
                       lw=0.9, label=label)
    for a, xlabel in [(ax2, "samples per pair evaluation"), (ax3, "time per pair evaluation (us, one thread)")]:
        a.axhline(1e-4, color="grey", lw=0.8, ls="-.")
        a.set_xlabel(xlabel)
        a.set_ylabel("force error")
        a.grid(alpha=0.3, which="both")
    ax2.axvline(600, color="grey", lw=0.8, ls=":")
    ax2.set_title("Accuracy against samples (adaptive: tolerance 1e-2..1e-8)")
    ax3.set_title("Accuracy against time")
    ax2.legend(fontsize=6, ncol=1)
    fig.tight_layout()
    fig.savefig(out / "tolerance.png", dpi=90)


accuracy_cost()
divergence()
switch_error()
table1()
table2()
scaling()
kernel()
tolerance()
print("charts in", out)
sys.exit(0)
