"""collide_rigid and distance_rigid: collision and distance under rigid motion for N poses in one call, against the exact Obstacle."""

from fractions import Fraction

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


def rotated(polytope, r):
    """The polytope r·polytope, exactly: r a float (3, 3) matrix taken exactly."""
    m = [[Fraction(x) for x in row] for row in r]
    return minksum.Polytope.hull([tuple(sum(m[i][k] * v[k] for k in range(3)) for i in range(3))
                                  for v in polytope.exact_vertices()])


def check_distances(got, ref, t_rel, seed, what):
    """got: distance_rigid(..., exact=True); ref: the Obstacle's exact answers at the translations t_rel."""
    n = len(ref)
    for key in ("status", "distance", "lower", "upper"):
        assert got[key].shape == (n,), (key, seed)
    assert got["point_a"].shape == got["point_b"].shape == (n, 3)
    for i, r in enumerate(ref):
        where = f"seed {seed}, {what}, pose {i}, t = {t_rel[i]}"
        assert minksum.STATUS[got["status"][i]] == r.status, where
        sq = got["squared_distance"][i]
        assert isinstance(sq, Fraction) and sq == r.squared_distance, where
        # The certified enclosure holds the exact distance.
        lo, hi = Fraction(float(got["lower"][i])), Fraction(float(got["upper"][i]))
        assert 0 <= lo <= hi and lo * lo <= sq <= hi * hi, where
        assert got["lower"][i] <= got["distance"][i] <= got["upper"][i], where
        # The exact closest points are sq apart; the doubles of a separate
        # answer are near them.  When the bodies meet both are common points
        # (not necessarily the same one: they are not unique).
        pa, pb = got["exact_point_a"][i], got["exact_point_b"][i]
        assert sum((x - y) ** 2 for x, y in zip(pa, pb)) == sq, where
        if r.status == "separate":
            assert np.allclose(got["point_a"][i], [float(x) for x in pa], rtol=0, atol=1e-9), where
            assert np.allclose(got["point_b"][i], [float(x) for x in pb], rtol=0, atol=1e-9), where
        else:
            assert pa == pb and (got["point_a"][i] == got["point_b"][i]).all(), where


def test_distance_with_quaternions_equals_the_exact_obstacle():
    rng = np.random.default_rng(SEED + 2)
    a, b = minksum.RigidBody("cube"), minksum.RigidBody("random:50:3")
    seen = set()
    for qa, qb in [((1, 0, 0, 0), (1, 2, 3, 4)), ((2, -1, 0, 3), (0, 1, 1, 0)), ((3, 1, 4, 1), (5, -2, 0, 1))]:
        t_a = rng.uniform(-1, 1, size=(100, 3))
        t_b = rng.uniform(-4, 4, size=(100, 3))
        got = minksum.distance_rigid(a, b, t_b, np.array([qb] * 100), t_a, np.array(qa), exact=True, threads=2)
        o = minksum.Obstacle("cube@rot:%d,%d,%d,%d" % qa, "random:50:3@rot:%d,%d,%d,%d" % qb)
        t_rel = [tuple(Fraction(float(y)) - Fraction(float(x)) for x, y in zip(ta, tb)) for ta, tb in zip(t_a, t_b)]
        check_distances(got, o.distance(t_rel, exact=True), t_rel, SEED + 2, (qa, qb))
        seen |= set(got["status"].tolist())
    assert {0, 2} <= seen


def test_distance_with_float_matrices_equals_the_exact_obstacle():
    rng = np.random.default_rng(SEED + 3)
    p, q = minksum.load("sphere:2"), minksum.load("random:50:4")
    a, b = minksum.RigidBody(p), minksum.RigidBody(q)
    seen = set()
    for r_a, r_b in zip(random_matrices(rng, 2), random_matrices(rng, 2)):
        t_b = rng.uniform(-3.5, 3.5, size=(120, 3))
        got = minksum.distance_rigid(a, b, t_b, r_b, None, r_a, exact=True)
        o = minksum.Obstacle(rotated(p, r_a), rotated(q, r_b))
        t_rel = [tuple(Fraction(float(x)) for x in t) for t in t_b]
        check_distances(got, o.distance(t_rel, exact=True), t_rel, SEED + 3, "matrices")
        seen |= set(got["status"].tolist())
    assert {0, 2} <= seen


def test_distance_exact_contacts_and_the_plain_arrays():
    c = minksum.RigidBody("cube")
    # Two cubes [-1, 1]³: face, face, edge and vertex contacts; 1 and √2 apart; overlapping.
    t = np.array([[2.0, 0, 0], [2.0, 0.5, 0], [2.0, 2.0, 1.0], [2.0, 2.0, 2.0], [3.0, 0, 0], [3.0, 3.0, 0], [0.5, 0, 0]])
    got = minksum.distance_rigid(c, c, t, exact=True)
    assert [minksum.STATUS[s] for s in got["status"]] == ["touching"] * 4 + ["separate"] * 2 + ["penetrating"]
    assert got["squared_distance"] == [0, 0, 0, 0, 1, 2, 0]
    assert got["exact_point_a"][3] == got["exact_point_b"][3] == (1, 1, 1)
    assert got["distance"][4] == 1.0 and got["lower"][4] <= 1.0 <= got["upper"][4]
    assert Fraction(float(got["lower"][5])) ** 2 <= 2 <= Fraction(float(got["upper"][5])) ** 2
    assert (got["distance"][[0, 1, 2, 3, 6]] == 0).all() and (got["lower"][[0, 1, 2, 3, 6]] == 0).all()
    plain = minksum.distance_rigid(c, c, t, threads=1)
    assert set(plain) == {"status", "distance", "lower", "upper", "point_a", "point_b"}
    for key in plain:
        assert (plain[key] == got[key]).all(), key


def test_distance_one_pose_for_all_and_errors():
    rng = np.random.default_rng(SEED + 4)
    a, b = minksum.RigidBody("sphere:2"), minksum.RigidBody("random:50:3")
    r = random_matrices(rng, 200)
    t = rng.uniform(-3, 3, size=(200, 3))
    # One rotation, or one translation, for every pose equals it repeated.
    one = minksum.distance_rigid(a, b, t, r[0])
    same = minksum.distance_rigid(a, b, t, np.repeat(r[:1], 200, axis=0))
    for key in one:
        assert (one[key] == same[key]).all(), key
    one = minksum.distance_rigid(a, b, t[7], r, exact=True)
    same = minksum.distance_rigid(a, b, np.repeat(t[7:8], 200, axis=0), r, exact=True)
    assert one["squared_distance"] == same["squared_distance"] and (one["distance"] == same["distance"]).all()
    # A single pose of both bodies: arrays of one.
    single = minksum.distance_rigid(a, b, [3, 0, 0])
    assert single["status"].shape == (1,) and single["point_a"].shape == (1, 3)
    # The statuses are collide_rigid's.
    assert (minksum.distance_rigid(a, b, t, r)["status"] == minksum.collide_rigid(a, b, t, r)).all()
    with pytest.raises(ValueError, match="counts must agree"):
        minksum.distance_rigid(a, b, t[:3], r[:2])
    with pytest.raises(ValueError, match="poses of a and b: 2 and 3"):
        minksum.distance_rigid(a, b, t[:3], t_a=t[:2])
    with pytest.raises(ValueError, match="expected quaternions"):
        minksum.distance_rigid(a, b, t[:2], np.ones((2, 5), dtype=np.int64))
    with pytest.raises(ValueError, match="t_b"):
        minksum.distance_rigid(a, b, np.ones((2, 4)))
    with pytest.raises(ValueError, match="positive determinant"):
        minksum.distance_rigid(a, b, t[:1], np.diag([1.0, -1.0, 1.0]))
    with pytest.raises(TypeError, match="quaternions must be integers"):
        minksum.distance_rigid(a, b, t[:1], r_a=np.array([1.0, 0, 0, 0]))
    with pytest.raises(ValueError, match="threads"):
        minksum.distance_rigid(a, b, t, threads=0)


def test_depth_with_quaternions_and_matrices_equals_the_exact_obstacle():
    # Penetration depth under rigid motion: the exact squared depth and the
    # shortest translation equal those of the Obstacle of the rotated operands
    # (Obstacle's t moves Q: the translation of a is then that of P).
    rng = np.random.default_rng(SEED + 7)
    a, b = minksum.RigidBody("cube"), minksum.RigidBody("random:50:3")
    qb = (1, 2, 3, 4)
    t_b = rng.uniform(-1.2, 1.2, size=(80, 3))
    got = minksum.depth_rigid(a, b, t_b, np.array(qb), exact=True, threads=2)
    assert got["depth"].shape == (80,) and got["direction"].shape == (80, 3)
    o = minksum.Obstacle("cube", "random:50:3@rot:%d,%d,%d,%d" % qb)
    want = o.depth([tuple(Fraction(float(x)) for x in t) for t in t_b], exact=True)
    penetrating = 0
    for i in range(80):
        where = (SEED + 7, i)
        assert minksum.STATUS[got["status"][i]] == want[i].status, where
        assert got["squared_depth"][i] == want[i].squared_depth, where
        assert tuple(got["exact_direction"][i]) == tuple(want[i].direction), where
        assert Fraction(got["lower"][i]) ** 2 <= want[i].squared_depth <= Fraction(got["upper"][i]) ** 2, where
        assert got["lower"][i] <= got["depth"][i] <= got["upper"][i], where
        penetrating += want[i].status == "penetrating"
    assert penetrating > 20
    # A float matrix for b, one pose for all.
    r = random_matrices(rng, 1)[0]
    one = minksum.depth_rigid(a, b, [0.25, 0, 0], r)
    assert one["status"].shape == (1,) and minksum.STATUS[one["status"][0]] == "penetrating"
    with pytest.raises(ValueError):
        minksum.depth_rigid(a, b, np.zeros((3, 2)))


def touching_cube_poses():
    """Two cubes [-1, 1]³, b turned by an integer quaternion that maps the cube onto itself and moved to an exact
    contact: face on face, edge on edge, vertex on vertex; then the same moved by 2^-30 away and towards a."""
    quats = [(1, 0, 0, 0), (1, 1, 0, 0), (0, 0, 1, 1), (1, 1, 1, 1)]  # identity, quarter turns, a third of a turn
    contacts = [(2.0, 0.5, 0.0), (2.0, 2.0, 0.0), (2.0, 2.0, 2.0), (0.0, -2.0, 1.5), (-2.0, 0.25, -2.0)]
    q, t, want = [], [], []
    for i, c in enumerate(contacts):
        for j, h in enumerate((0.0, 2.0 ** -30, -(2.0 ** -30))):
            q.append(quats[(i + j) % len(quats)])
            t.append([x + h * np.sign(x) for x in c])
            want.append(["touching", "separate", "penetrating"][j])
    return np.array(q, dtype=np.int64), np.array(t), want


@pytest.mark.parametrize("threads", [1, 2, None])
def test_batch_equals_the_single_pose_answers_with_touching_poses(threads):
    # The batch's statuses and exact squared distances are those of one call
    # per pose (one pose of a and of b), on a fixed-seed mix of random poses
    # of both bodies (more than one run of 256 poses, quaternions and float
    # matrices) and exactly touching poses.
    rng = np.random.default_rng(SEED + 9)
    c = minksum.RigidBody("cube")
    q_touch, t_touch, want = touching_cube_poses()
    codes = minksum.collide_rigid(c, c, t_touch, q_touch, threads=threads)
    assert [minksum.STATUS[x] for x in codes] == want
    dist = minksum.distance_rigid(c, c, t_touch, q_touch, exact=True, threads=threads)
    assert (dist["status"] == codes).all()
    for i, w in enumerate(want):
        assert (dist["squared_distance"][i] == 0) == (w != "separate"), i
        if w == "separate":  # 2^-30 along one axis, or along two or three
            assert dist["squared_distance"][i] in (Fraction(k, 2 ** 60) for k in (1, 2, 3)), i

    a, b = minksum.RigidBody("sphere:2"), minksum.RigidBody("random:50:3")
    n = 600
    for r_a, r_b in [(rng.integers(-20, 21, size=(n, 4)), rng.integers(-20, 21, size=(n, 4))),
                     (random_matrices(rng, n), random_matrices(rng, n))]:
        if r_a.dtype.kind == "i":
            r_a[np.all(r_a == 0, axis=1)] = (1, 0, 0, 0)
            r_b[np.all(r_b == 0, axis=1)] = (1, 0, 0, 0)
        t_a = rng.uniform(-1, 1, size=(n, 3))
        t_b = t_a + rng.uniform(-3, 3, size=(n, 3))
        codes = minksum.collide_rigid(a, b, t_b, r_b, t_a, r_a, threads=threads)
        dist = minksum.distance_rigid(a, b, t_b, r_b, t_a, r_a, exact=True, threads=threads)
        assert (dist["status"] == codes).all()
        assert {0, 2} <= set(codes.tolist())
        for i in range(0, n, 3):
            one = minksum.collide_rigid(a, b, t_b[i], r_b[i], t_a[i], r_a[i])
            assert one.shape == (1,) and one[0] == codes[i], (SEED + 9, i)
            d = minksum.distance_rigid(a, b, t_b[i], r_b[i], t_a[i], r_a[i], exact=True)
            assert d["squared_distance"][0] == dist["squared_distance"][i], (SEED + 9, i)


def test_batch_answers_do_not_depend_on_threads_and_name_the_bad_pose():
    # Runs of consecutive poses, each warm-started along itself, whatever the
    # threads: every array is the same, bit for bit.
    rng = np.random.default_rng(SEED + 10)
    a, b = minksum.RigidBody("random:50:3"), minksum.RigidBody("cube")
    n = 3000
    r_b = random_matrices(rng, n)
    q_a = rng.integers(-9, 10, size=(n, 4))
    q_a[np.all(q_a == 0, axis=1)] = (0, 0, 0, 1)
    t_b = rng.uniform(-3, 3, size=(n, 3))
    runs = [minksum.distance_rigid(a, b, t_b, r_b, None, q_a, threads=k) for k in (1, 2, None)]
    for other in runs[1:]:
        for key in runs[0]:
            assert np.array_equal(runs[0][key], other[key]), key
    assert np.array_equal(minksum.collide_rigid(a, b, t_b, r_b, None, q_a, threads=2), runs[0]["status"])
    # A bad pose deep in a batch of many runs is named, the first one in pose order.
    bad = r_b.copy()
    bad[2500] = np.diag([1.0, 1.0, -1.0])
    bad[1700] = np.diag([-1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match=r"r_b\[1700\].*positive determinant"):
        minksum.collide_rigid(a, b, t_b, bad, threads=2)
    zero = q_a.copy()
    zero[2222] = 0
    with pytest.raises(ValueError, match=r"r_a\[2222\].*zero quaternion"):
        minksum.distance_rigid(a, b, t_b, r_b, None, zero)
