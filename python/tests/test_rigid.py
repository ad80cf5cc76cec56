"""collide_rigid: collision under rigid motion for N poses in one call, against the exact Obstacle."""

import numpy as np
import pytest

import minksum

SEED = 39


def random_matrices(rng, n):
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    a, b, c, d = q.T
    return np.stack([
        np.stack([a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)], axis=1),
        np.stack([2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)], axis=1),
        np.stack([2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d], axis=1),
    ], axis=1)


@pytest.mark.parametrize("threads", [1, 2, None])
def test_quaternion_batch_equals_the_exact_obstacle(threads):
    rng = np.random.default_rng(SEED)
    a, b = minksum.RigidBody("cube"), minksum.RigidBody("tetra")
    q = rng.integers(-4, 5, size=(60, 4))
    q[np.all(q == 0, axis=1)] = (1, 0, 0, 0)
    t = rng.uniform(-2.5, 2.5, size=(60, 3))
    codes = minksum.collide_rigid(a, b, t, q, threads=threads)
    assert codes.dtype == np.int8 and codes.shape == (60,)
    for i in range(60):
        # The rotation of Q by an integer quaternion is exact: the Obstacle of
        # the rotated tetrahedron answers the same pose.
        o = minksum.Obstacle("cube", "tetra@rot:%d,%d,%d,%d" % tuple(q[i]))
        assert minksum.STATUS[codes[i]] == o.collide(t[i]).status, (SEED, i)
    assert {0, 2} <= set(codes.tolist())


def test_matrices_one_pose_for_all_and_errors():
    rng = np.random.default_rng(SEED + 1)
    a, b = minksum.RigidBody("sphere:2"), minksum.RigidBody("random:50:3")
    r = random_matrices(rng, 500)
    t = rng.uniform(-3, 3, size=(500, 3))
    codes = minksum.collide_rigid(a, b, t, r)
    assert codes.shape == (500,)
    # One rotation for all poses equals the same rotation repeated.
    one = minksum.collide_rigid(a, b, t, r[0])
    same = minksum.collide_rigid(a, b, t, np.repeat(r[:1], 500, axis=0))
    assert (one == same).all()
    # Moving both bodies by the same translation changes nothing.
    moved = minksum.collide_rigid(a, b, t + 1.0, r, t_a=np.ones(3))
    assert (moved == codes).all()
    # An exactly touching pose: two cubes face to face.
    c = minksum.RigidBody("cube")
    assert minksum.STATUS[minksum.collide_rigid(c, c, [[2, 0, 0]])[0]] == "touching"
    assert minksum.STATUS[minksum.collide_rigid(c, c, [[2, 0.5, 0]], [[1, 0, 0, 0]])[0]] == "touching"
    with pytest.raises(ValueError, match="positive determinant"):
        minksum.collide_rigid(a, b, t[:1], np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(TypeError, match="quaternions must be integers"):
        minksum.collide_rigid(a, b, t[:1], np.array([[1.0, 0, 0, 0]]))
    with pytest.raises(ValueError, match="counts must agree"):
        minksum.collide_rigid(a, b, t[:3], r[:2])
    with pytest.raises(ValueError, match="zero quaternion"):
        minksum.collide_rigid(a, b, t[:1], np.zeros((1, 4), dtype=np.int64))
