#!/usr/bin/env python3
"""Checks of etc/plotScene.py (tests/CMakeLists.txt: plotScene.*).

    checkPlot.py CHECK WORK_DIR [MAGFOAM]

Each check runs plotScene as a user does and fails (exit 1, saying why) when
the output is missing or wrong: the bodies' printed extents against the sizes
and poses of the cases here, the chart's pixels, the movie's frame count.
Exit 77 (skipped) where a check needs ffprobe and it is not on PATH.
"""
import pathlib
import re
import shutil
import subprocess
import sys

from PIL import Image

HERE = pathlib.Path(__file__).resolve().parent
PLOT = HERE.parents[1] / "etc/plotScene.py"
EXTENT = re.compile(r"^  (\S+): \[(\S+), (\S+)\] x \[(\S+), (\S+)\] x \[(\S+), (\S+)\] mm", re.M)

# x, y, z extents in mm, from the sizes and poses of constant/bodies.yaml
C30, S30 = 3 ** 0.5 / 2, 0.5
PRIMITIVES = {
    # 10 x 6 x 4 mm box turned 30 deg about z, at (-20, 0, 10)
    "brick": (-20 - (10 * C30 + 6 * S30) / 2, -20 + (10 * C30 + 6 * S30) / 2,
              -(10 * S30 + 6 * C30) / 2, (10 * S30 + 6 * C30) / 2, 8, 12),
    "ball": (-4, 4, -4, 4, 6, 14),  # radius 4 mm at (0, 0, 10)
    "rod": (17, 23, -6, 6, 7, 13),  # radius 3, height 12, axis turned onto y, at (20, 0, 10)
    # two 10 mm cubes side by side (7500 and 1500 kg/m3), their centre of mass at (0, 40, 10)
    "pair": (-10 + 10 / 3, 10 + 10 / 3, 35, 45, 5, 15),
}
R2 = 50 * 2 ** 0.5 / 10  # half the diagonal of a 10 mm face
MESHES = {
    "stlAscii": (-5, 5, -5, 5, 5, 15),
    "stlBinary": (20 - R2, 20 + R2, -R2, R2, 5, 15),  # 45 deg about z
    "obj": (35, 45, -5, 5, 5, 15),
    "plyAscii": (57.5, 67.5, -2.5, 7.5, 7.5, 17.5),  # corner at -2.5 from the centre of mass
    "plyBinary": (75, 85, -R2, R2, 10 - R2, 10 + R2),  # 45 deg about x
    "off": (97.5, 107.5, -2.5, 7.5, 7.5, 17.5),
}


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def plot(*args, ok=True):
    r = subprocess.run([sys.executable, str(PLOT), *map(str, args)], capture_output=True, text=True)
    print(r.stdout + r.stderr)
    if ok and r.returncode != 0:
        fail(f"plotScene {' '.join(map(str, args))} exited {r.returncode}")
    return r


def check_extents(out, expected, tol=0.002):
    found = {m[0]: tuple(float(x) for x in m[1:]) for m in EXTENT.findall(out)}
    for name, ext in expected.items():
        if name not in found:
            fail(f"no extents printed for body '{name}'")
        if max(abs(a - b) for a, b in zip(found[name], ext)) > tol:
            fail(f"body '{name}': extents {found[name]} mm, expected {tuple(round(e, 3) for e in ext)}")
    if set(found) != set(expected):
        fail(f"bodies {sorted(found)}, expected {sorted(expected)}")


def check_chart(png, fixed_bodies=True):
    """Bodies are drawn: blue (dynamic) and, where the scene has them, red (fixed) faces."""
    im = Image.open(png).convert("RGB")
    px = list(im.getdata())
    blue = sum(1 for r, g, b in px if b > r + 60 and b > g + 20)
    red = sum(1 for r, g, b in px if r > b + 80 and r > g + 80)
    print(f"{png}: {im.size[0]} x {im.size[1]}, {blue} blue and {red} red pixels")
    if blue < 500 or (fixed_bodies and red < 200):
        fail(f"{png}: the bodies are not drawn ({blue} blue, {red} red pixels)")


def run_case(work, magfoam):
    """A copy of the primitives case, run by magFoam: 24 written times."""
    case = work / "primitives"
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(HERE / "primitives", case)
    r = subprocess.run([magfoam, "-case", str(case)], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"magFoam on {case}: exit {r.returncode}\n{r.stdout[-2000:]}{r.stderr}")
    return case


def gif_frames(path):
    im = Image.open(path)
    frames = []
    for k in range(im.n_frames):
        im.seek(k)
        frames.append(im.convert("RGB"))
    return frames


def main():
    check, work = sys.argv[1], pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    if check == "primitives":
        # not run: drawn where constant/bodies.yaml places the bodies
        r = plot(HERE / "primitives", work / "primitives.png")
        check_extents(r.stdout, PRIMITIVES)
        check_chart(work / "primitives.png")
    elif check == "meshFormats":
        # each reader: every triangle, outward (positive volume)
        sys.path.insert(0, str(PLOT.parent))
        import numpy as np
        import plotScene
        for f in sorted((HERE / "meshFormats/constant/geometry").iterdir()):
            tri = plotScene.read_mesh(f)
            vol = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6
            want = (12, 1000.0) if f.name.startswith("cube") else (4, 1000 / 6)
            print(f"{f.name}: {len(tri)} triangles, {vol:.3f} mm^3")
            if len(tri) != want[0] or abs(vol - want[1]) > 1e-9:
                fail(f"{f.name}: {len(tri)} triangles of {vol} mm^3, expected {want[0]} of {want[1]:.3f}")
        r = plot(HERE / "meshFormats", work / "meshFormats.png")
        check_extents(r.stdout, MESHES)
        check_chart(work / "meshFormats.png")
    elif check == "run":
        run_case(work, sys.argv[3])
    elif check == "results":
        # the final state, from bodies.csv and (without it) from the time folders
        case = work / "primitives"
        r = plot(case, work / "results.png")
        if "t = 0.046 s" not in r.stdout:
            fail("the chart is not of the last written time 0.046 s")
        ext = {m[0]: tuple(float(x) for x in m[1:]) for m in EXTENT.findall(r.stdout)}
        if ext["ball"] != PRIMITIVES["ball"] or abs(ext["brick"][4]) > 0.1:
            fail(f"final state: the fixed ball moved or the brick is not on the ground: {ext}")
        check_chart(work / "results.png")
        folders = work / "timeFolders"
        shutil.rmtree(folders, ignore_errors=True)
        shutil.copytree(case, folders, ignore=shutil.ignore_patterns("postProcessing"))
        r2 = plot(folders, work / "timeFolders.png")
        ext2 = {m[0]: tuple(float(x) for x in m[1:]) for m in EXTENT.findall(r2.stdout)}
        if ext2 != ext:
            fail(f"time folders give {ext2}, bodies.csv {ext}")
    elif check == "movieGif":
        case = work / "primitives"
        gif = work / "primitives.gif"
        plot(case, "--movie", gif, "--frames", 10, "--fps", 5)
        frames = gif_frames(gif)
        w, h = frames[0].size
        print(f"{gif}: {len(frames)} frames, {w} x {h}, {gif.stat().st_size} bytes")
        if len(frames) != 10:
            fail(f"{gif}: {len(frames)} frames, expected 10")
        if w % 2 or h % 2 or w > 800:
            fail(f"{gif}: {w} x {h}, expected even sizes, at most 800 wide")
        if frames[0].tobytes() == frames[-1].tobytes():
            fail(f"{gif}: the first and the last frame are the same: the bodies do not move")
        # fewer written times than frames: one frame each, up to --end
        plot(case, "--movie", work / "short.gif", "--frames", 100, "--end", 0.02)
        n = len(gif_frames(work / "short.gif"))
        if n != 11:
            fail(f"short.gif: {n} frames, expected 11 (t = 0, 0.002, ..., 0.02)")
    elif check == "movieMp4":
        case = work / "primitives"
        mp4 = work / "primitives.mp4"
        mp4.unlink(missing_ok=True)
        have_ffmpeg = shutil.which("ffmpeg") is not None
        r = plot(case, "--movie", mp4, "--frames", 10, ok=have_ffmpeg)
        if not have_ffmpeg:
            if r.returncode == 0 or "ffmpeg" not in r.stderr or ".gif" not in r.stderr or "Traceback" in r.stderr:
                fail("without ffmpeg an .mp4 must fail with one message naming ffmpeg and .gif")
            print("ffmpeg not on PATH: the .mp4 fails clearly")
            return
        if shutil.which("ffprobe") is None:
            print("ffprobe not on PATH: the file is not checked")
            sys.exit(77)
        p = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=codec_name,nb_read_frames,width,height", "-of", "default=nw=1", str(mp4)],
                           capture_output=True, text=True)
        print(p.stdout + p.stderr)
        if p.returncode != 0 or "nb_read_frames=10" not in p.stdout or "codec_name=h264" not in p.stdout:
            fail(f"ffprobe does not read 10 h264 frames from {mp4}")
    elif check == "badInput":
        # unreadable mesh: one message naming the file, no traceback
        case = work / "badMesh"
        shutil.rmtree(case, ignore_errors=True)
        shutil.copytree(HERE / "meshFormats", case)
        (case / "constant/geometry/cubeBinary.ply").write_bytes(b"ply\nformat binary_little_endian 1.0\n"
                                                                b"element vertex 8\nproperty float x\nend_header\n")
        r = plot(case, work / "bad.png", ok=False)
        if r.returncode != 1 or "cubeBinary.ply" not in r.stderr or "Traceback" in r.stderr:
            fail("a broken PLY must fail with one message naming the file")
        r = plot(HERE / "primitives", "--movie", work / "movie.avi", ok=False)
        if r.returncode != 1 or ".gif or .mp4" not in r.stderr:
            fail("--movie FILE.avi must fail naming .gif and .mp4")
    else:
        fail(f"unknown check {check}")
    print("OK")


if __name__ == "__main__":
    main()
