"""minksum: exact Minkowski sums of polyhedra in 3D (convex and non-convex), and exact proximity queries.

    >>> import minksum
    >>> s = minksum.minkowski_sum(minksum.load("cube"), minksum.load("tetra"))
    >>> s.num_vertices, s.num_facets, s.volume()

Every computation is exact: coordinates are rationals (a float64 input is the
exact value of each double), every geometric decision is the sign of an exact
polynomial.  Exact results are Python ints and fractions.Fraction; the float64
array ``Polytope.vertices`` holds the nearest doubles, without a copy.

Sweeps: ``ConvexSet(points)`` or ``ConvexSet.load("segment:0,0,0:1,0,0")`` (a
point, a segment or a flat polygon) as an operand of ``minkowski_sum``.

Non-convex solids: ``Solid(vertices, faces)`` or ``Solid.load("tube")``;
``minkowski_sum`` with a ``Solid`` operand (or a name that is not a convex
polytope) returns a ``SolidSum``; so do ``erode``, ``opening`` (also
``minksum.open``) and ``closing`` (also ``minksum.close``) of a solid by a
convex polytope.

Collision, separation distance and penetration depth under rigid motion:
``collide_rigid(RigidBody(a), RigidBody(b), t_b, r_b)``, ``distance_rigid(...)``
and ``depth_rigid(...)`` for N poses (quaternions or rotation matrices) in one
call.

Many sums: ``minkowski_sum_many`` runs them on a pool of C++ threads;
``minksum.dask`` spreads them over a Dask cluster.
"""

from ._errors import InputError, NotConvexError
from ._minksum import (
    METHODS,
    STATUS,
    CollisionResult,
    ConvexSet,
    DepthResult,
    DirectionalDepthResult,
    DistanceResult,
    Obstacle,
    Polytope,
    RigidBody,
    Solid,
    SolidSum,
    Sum,
    Witness,
    closing,
    collide_rigid,
    depth_rigid,
    distance_rigid,
    erode,
    load,
    minkowski_sum,
    minkowski_sum_many,
    opening,
)

#: ``minksum.open`` and ``minksum.close`` are ``opening`` and ``closing``
#: (``open`` is left out of ``__all__``: ``from minksum import *`` would hide
#: the builtin).
open = opening  # noqa: A001
close = closing

__all__ = [
    "METHODS",
    "STATUS",
    "CollisionResult",
    "ConvexSet",
    "DepthResult",
    "DirectionalDepthResult",
    "DistanceResult",
    "InputError",
    "NotConvexError",
    "Obstacle",
    "Polytope",
    "RigidBody",
    "Solid",
    "SolidSum",
    "Sum",
    "Witness",
    "close",
    "closing",
    "collide_rigid",
    "depth_rigid",
    "distance_rigid",
    "erode",
    "load",
    "minkowski_sum",
    "minkowski_sum_many",
    "opening",
]
