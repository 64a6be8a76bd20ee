"""System.field against the closed-form field of a uniformly magnetized cuboid
(oracles.cuboid_B, numpy) at 1000 random points, inside and outside."""
import numpy as np

import magfoam as mf
from oracles import MU0, cuboid_B

SIZE = [0.01, 0.006, 0.004]  # m, a 10 x 6 x 4 mm block
BR = 1.2                     # T


def rotation(axis, degrees):
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    t = np.radians(degrees)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(t) * K + (1 - np.cos(t)) * K @ K, np.r_[np.cos(t / 2), np.sin(t / 2) * a]


def relative_error(B, Bo):
    # per point, against |B| with a floor of 1 mT where the field nearly vanishes
    return np.linalg.norm(B - Bo, axis=1) / np.maximum(np.linalg.norm(Bo, axis=1), 1e-3)


def test_box_field_equals_the_closed_form_at_1000_points():
    rng = np.random.default_rng(20)
    # 700 points within 8 mm of the centre (about 40 of them inside), 300 up to 2 cm
    P = np.r_[rng.uniform(-0.008, 0.008, (700, 3)), rng.uniform(-0.02, 0.02, (300, 3))]
    direction = np.array([0.3, -0.5, 0.8])
    R, q = rotation([1, 2, 3], 35)
    centre = np.array([0.001, -0.002, 0.0005])
    s = mf.System(field={"type": "MBM"})
    s.add_body("m", box=SIZE, Br=BR, magnetization=direction, position=centre, quaternion=q)
    B = s.field(P)
    M = R @ (direction / np.linalg.norm(direction)) * BR / MU0  # world frame, A/m
    Bo = cuboid_B(P, SIZE, M, centre, R)
    inside = np.all(np.abs((P - centre) @ R) < 0.5 * np.array(SIZE), axis=1)
    assert 20 < inside.sum() < 200  # both regions are sampled
    # Both are closed forms in double precision: MBM's polyhedron integrals and
    # the charge-sheet sums of the oracle (measured 4e-14 here). 1e-11 allows
    # their rounding nearer an edge (logarithms of small differences), and is
    # far below any quadrature error (1e-4).
    err = relative_error(B, Bo)
    print(f"field vs cuboid closed form: max relative error {err.max():.2e} over {len(P)} points")
    assert err.max() < 1e-11
    assert B.shape == (1000, 3) and np.isfinite(B).all()


def test_field_keeps_the_shape_and_gives_A_and_H():
    s = mf.System()
    s.add_body("m", box=SIZE, Br=BR, magnetization=[0, 0, 1])
    grid = np.stack(np.meshgrid(np.linspace(0.01, 0.02, 4), [0.0, 0.003], [0.001]), axis=-1)  # (2, 4, 1, 3)
    B, A, H = s.field(grid, A=True, H=True)
    assert B.shape == A.shape == H.shape == grid.shape
    np.testing.assert_array_equal(B.reshape(-1, 3), s.field(grid.reshape(-1, 3)))
    # outside the magnet B = mu0 H
    np.testing.assert_allclose(B, MU0 * H, rtol=1e-12, atol=1e-18)
    assert s.field([0.0, 0.0, 0.0]).shape == (3,)


def test_field_is_finite_on_and_near_edges():
    # 1e-9 m from an edge and exactly on a face: finite (the charge model's
    # B is bounded there; on a face it is the mean of the two sides).
    s = mf.System()
    s.add_body("m", box=[0.01] * 3, Br=1.0, magnetization=[0, 0, 1])
    P = np.array([[0.005 + 1e-9, 0.005 + 1e-9, 0.0], [0.0, 0.0, 0.005], [0.005 + 1e-9, 0.0, 0.005 + 1e-9]])
    assert np.isfinite(s.field(P)).all()


def test_mesh_and_file_geometry_equal_the_box(tmp_path, monkeypatch):
    # The same 10 x 6 x 4 mm block as arrays, as an OBJ file (relative to the
    # working folder, both forms) and as box=: one closed form, so the fields
    # agree to rounding (the file is read in single precision: 1e-7).
    h = 0.5 * np.array(SIZE)
    V = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * h
    F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    monkeypatch.chdir(tmp_path)
    with open("block.obj", "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    P = np.random.default_rng(5).uniform(-0.02, 0.02, (200, 3))
    ref = mf.System()
    ref.add_body("m", box=SIZE, Br=BR, magnetization=[0, 0, 1])
    for kwargs, tol in [({"mesh": (V, F)}, 1e-12), ({"file": "block.obj"}, 1e-6),
                        ({"geometry": {"file": "block.obj"}}, 1e-6)]:
        s = mf.System()
        s.add_body("m", Br=BR, magnetization=[0, 0, 1], **kwargs)
        assert relative_error(s.field(P), ref.field(P)).max() < tol, kwargs


def test_compound_field_is_the_sum_of_its_parts_closed_forms():
    # A compound (parts=) of a block and a second block turned 90 deg about z,
    # of different remanence, the whole body turned and moved: its field is the
    # two cuboids' closed forms, each placed where the body puts it.
    rng = np.random.default_rng(21)
    P = rng.uniform(-0.02, 0.02, (400, 3))
    s = mf.System(field={"type": "MBM"}, materials={"A": {"model": "permanent", "Br": 1.2, "density": 7500},
                                                   "B": {"model": "permanent", "Br": 0.8, "density": 2500}})
    R, q = rotation([1, -1, 2], 40)
    Rz, qz = rotation([0, 0, 1], 90)
    layout = [np.array([-0.006, 0.0, 0.0]), np.array([0.006, 0.001, 0.0])]
    s.add_body("pair", parts=[
        {"geometry": {"box": {"size": SIZE}}, "material": "A", "magnetization": [0, 0, 1], "position": list(layout[0])},
        {"geometry": {"box": {"size": SIZE}}, "material": "B", "magnetization": [1, 0, 0], "position": list(layout[1]),
         "orientation": {"quaternion": list(qz)}}],
        position=[0.001, 0.002, -0.001], quaternion=q)
    # The body's position is the compound's centre of mass (masses 7500 : 2500).
    com = (7500 * layout[0] + 2500 * layout[1]) / 10000
    centre = np.array([0.001, 0.002, -0.001])
    Bo = (cuboid_B(P, SIZE, R @ np.array([0, 0, 1.2 / MU0]), centre + R @ (layout[0] - com), R) +
          cuboid_B(P, SIZE, R @ Rz @ np.array([0.8 / MU0, 0, 0]), centre + R @ (layout[1] - com), R @ Rz))
    err = relative_error(s.field(P), Bo)
    print(f"compound field vs two cuboid closed forms: max relative error {err.max():.2e}")
    assert err.max() < 1e-11  # as for one cuboid above
