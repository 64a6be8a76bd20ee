"""sweep: many poses in one call equal the same poses one at a time, bit for
bit, and leave the system as it was; evaluations release the GIL."""
import threading
import time

import numpy as np

import magfoam as mf


def scene():
    s = mf.System(field={"type": "MBM"}, threads=1)
    s.add_body("ring", cylinder=(0.01, 0.005), Br=1.3, magnetization=[0, 0, 1], fixed=True)
    s.add_body("ball", sphere=0.003, Br=1.3, magnetization=[1, 0, 0], position=[0, 0, 0.01])
    return s


def test_sweep_equals_one_pose_at_a_time():
    s = scene()
    rng = np.random.default_rng(1)
    P = np.c_[rng.uniform(-0.01, 0.01, (12, 2)), rng.uniform(0.008, 0.02, 12)]
    Q = rng.normal(size=(12, 4))
    F, T = s.sweep("ball", positions=P, quaternions=Q)
    pose = s.pose("ball")
    for k in range(len(P)):
        t = mf.System(field={"type": "MBM"})
        t.add_body("ring", cylinder=(0.01, 0.005), Br=1.3, magnetization=[0, 0, 1], fixed=True)
        t.add_body("ball", sphere=0.003, Br=1.3, magnetization=[1, 0, 0], position=P[k], quaternion=Q[k])
        f, tq = t.wrench("ball")
        np.testing.assert_array_equal(F[k], f)
        np.testing.assert_array_equal(T[k], tq)
    # unchanged afterwards
    np.testing.assert_array_equal(s.pose("ball")[0], pose[0])
    np.testing.assert_array_equal(s.pose("ball")[1], pose[1])
    # orientations only: the position stays
    F2, _ = s.sweep("ball", quaternions=Q[:3])
    assert F2.shape == (3, 3)


def test_threads_give_the_same_bits():
    s = scene()
    P = np.random.default_rng(2).uniform(-0.02, 0.02, (2000, 3))
    one = s.field(P)
    four = mf.System(threads=4)
    four.add_body("ring", cylinder=(0.01, 0.005), Br=1.3, magnetization=[0, 0, 1], fixed=True)
    four.add_body("ball", sphere=0.003, Br=1.3, magnetization=[1, 0, 0], position=[0, 0, 0.01])
    np.testing.assert_array_equal(four.field(P), one)


def test_field_releases_the_gil():
    s = scene()
    P = np.random.default_rng(3).uniform(-0.02, 0.02, (200000, 3))
    ticks = [0]
    running = threading.Event()
    stop = threading.Event()

    def count():
        running.set()
        while not stop.is_set():
            ticks[0] += 1

    t = threading.Thread(target=count)
    t.start()
    running.wait()
    t0, before = time.perf_counter(), ticks[0]
    s.field(P)
    seconds, during = time.perf_counter() - t0, ticks[0] - before
    stop.set()
    t.join()
    # With the GIL held for the whole call the counter could not move at all
    # (beyond one switch interval, 5 ms, of the conversion); released, it
    # counts all along. At least 1000 ticks per 50 ms is far below a loaded core's rate.
    assert seconds > 0.02
    assert during > 1000 * seconds / 0.05
