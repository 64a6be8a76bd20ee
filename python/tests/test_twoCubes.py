"""Two 1 cm cubes, Br = 1 T along +z, coaxial: the force at the reference gaps
of docs/physics.md#reference-values against Akoun-Yonnet (oracles.py)."""
import numpy as np
import pytest

import magfoam as mf
from oracles import akoun_yonnet_force

EDGE = 0.01
GAPS = [0.0002, 0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05]  # m, the reference table
# The published values of the same table, as printed: a check of the oracle itself.
PUBLISHED = ["28.4021", "24.703", "20.360", "14.673", "6.568", "2.251", "0.4635", "0.02929"]


def two_cubes(field=None):
    s = mf.System(field=field or {"type": "MBM"})
    s.add_body("a", box=[EDGE] * 3, Br=1.0, magnetization=[0, 0, 1], fixed=True)
    s.add_body("b", box=[EDGE] * 3, Br=1.0, magnetization=[0, 0, 1], position=[0, 0, EDGE + GAPS[0]])
    return s


def test_oracle_reproduces_the_published_table():
    F = akoun_yonnet_force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, [[0, 0, EDGE + d] for d in GAPS], 1, 1)
    for f, text in zip(-F[:, 2], PUBLISHED):
        # within the rounding of the printed value: half a unit of its last digit
        decimals = len(text.split(".")[1])
        assert abs(f - float(text)) <= 0.5 * 10.0 ** -decimals, (f, text)


@pytest.mark.parametrize("gap", GAPS)
def test_force_against_akoun_yonnet(gap):
    s = two_cubes()
    s.set_pose("b", position=[0, 0, EDGE + gap])
    F, T = s.wrench("b")
    exact = akoun_yonnet_force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, [0, 0, EDGE + gap], 1, 1)[0]
    # MBM's default adaptive rule promises 1e-4 relative per pair
    # (docs/physics.md, quadrature.tolerance); 2e-4 leaves room for the
    # estimate being an estimate. The lateral force and the torque vanish by
    # symmetry; the adaptive rule is not symmetric, so they are quadrature
    # error too: within the same 1e-4 of |F| (and of |F| x edge).
    assert abs(F[2] / exact[2] - 1) < 2e-4
    assert np.abs(F[:2]).max() < 1e-4 * abs(exact[2])
    assert np.abs(T).max() < 1e-4 * abs(exact[2]) * EDGE


def test_sweep_against_akoun_yonnet_and_newton():
    s = two_cubes()
    P = np.array([[0, 0, EDGE + d] for d in GAPS])
    F, T = s.sweep("b", positions=P)
    exact = akoun_yonnet_force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, P, 1, 1)
    np.testing.assert_allclose(F[:, 2], exact[:, 2], rtol=2e-4)  # as above
    # the fixed cube feels the opposite force (pair wrenches are antisymmetric)
    s.set_pose("b", position=P[2])
    W = s.wrenches()
    np.testing.assert_array_equal(W["a"][0], -W["b"][0])


def test_offset_cubes_reference_value():
    # docs/physics.md#reference-values: the upper cube at (5, 0, 12) mm:
    # F = (-6.586, 0, -7.904) N, Ty = 0.019754 N m (4-5 digits).
    s = two_cubes()
    s.set_pose("b", position=[0.005, 0, 0.012])
    F, T = s.wrench("b")
    exact = akoun_yonnet_force([EDGE] * 3, [0, 0, 0], [EDGE] * 3, [0.005, 0, 0.012], 1, 1)[0]
    np.testing.assert_allclose(F[[0, 2]], exact[[0, 2]], rtol=2e-4)
    np.testing.assert_allclose(F, [-6.586, 0, -7.904], rtol=1e-3, atol=1e-9)
    assert T[1] == pytest.approx(0.019754, rel=1e-3)
