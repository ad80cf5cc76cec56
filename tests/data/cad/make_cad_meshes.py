#!/usr/bin/python3
"""Write the STL files of tests/data/cad/ as OpenSCAD exports them: ascii STL,
every coordinate printed with 6 significant digits (C's %g), polygons
fan-triangulated, the solids built with OpenSCAD's own fragment rules.

    cube.stl        rotate([30, 45, 10]) cube(10, center = true);
    cylinder.stl    rotate([20, 0, 35]) cylinder(r = 5, h = 10, center = true, $fn = 48);
    sphere.stl      sphere(r = 10, $fn = 48);
    hull.stl        hull() { sphere(r = 3, $fn = 24); translate([10, 4, 2]) sphere(r = 5, $fn = 24); }

None is exactly convex once rounded to 6 digits (non-planar quads, reflex
edges between almost coplanar triangles); each is the convex hull of its
points.  Run once: python3 tests/data/cad/make_cad_meshes.py (numpy, scipy).
"""
import os

import numpy as np
from scipy.spatial import ConvexHull

HERE = os.path.dirname(os.path.abspath(__file__))


def rotation(ax, ay, az):
    """OpenSCAD's rotate([ax, ay, az]): about x, then y, then z (degrees)."""
    ax, ay, az = np.radians([ax, ay, az])
    rx = np.array([[1, 0, 0], [0, np.cos(ax), -np.sin(ax)], [0, np.sin(ax), np.cos(ax)]])
    ry = np.array([[np.cos(ay), 0, np.sin(ay)], [0, 1, 0], [-np.sin(ay), 0, np.cos(ay)]])
    rz = np.array([[np.cos(az), -np.sin(az), 0], [np.sin(az), np.cos(az), 0], [0, 0, 1]])
    return rz @ ry @ rx


def cube(size):
    h = size / 2
    pts = np.array([[x, y, z] for z in (-h, h) for y in (-h, h) for x in (-h, h)], dtype=float)
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return pts, faces


def cylinder(r, h, fn):
    a = 2 * np.pi * np.arange(fn) / fn
    ring = np.stack([r * np.cos(a), r * np.sin(a)], axis=1)
    pts = np.concatenate([np.c_[ring, np.full(fn, -h / 2)], np.c_[ring, np.full(fn, h / 2)]])
    faces = [list(range(fn - 1, -1, -1)), list(range(fn, 2 * fn))]
    faces += [[i, (i + 1) % fn, fn + (i + 1) % fn, fn + i] for i in range(fn)]
    return pts, faces


def sphere(r, fn):
    """OpenSCAD's sphere: (fn + 1) // 2 rings of fn points, at polar angles
    180 (i + 0.5) / rings; the two caps are polygons, the bands quads."""
    rings = (fn + 1) // 2
    pts = []
    for i in range(rings):
        phi = np.pi * (i + 0.5) / rings
        for j in range(fn):
            t = 2 * np.pi * j / fn
            pts.append([r * np.sin(phi) * np.cos(t), r * np.sin(phi) * np.sin(t), r * np.cos(phi)])
    faces = [list(range(fn))]  # top cap, counter-clockwise from above
    for i in range(rings - 1):
        a, b = i * fn, (i + 1) * fn
        faces += [[a + j, b + j, b + (j + 1) % fn, a + (j + 1) % fn] for j in range(fn)]
    faces.append([(rings - 1) * fn + j for j in range(fn - 1, -1, -1)])
    return np.array(pts), faces


def hull_mesh(pts):
    h = ConvexHull(pts)
    faces = []
    for tri, eq in zip(h.simplices, h.equations):
        a, b, c = pts[tri]
        if np.dot(np.cross(b - a, c - a), eq[:3]) < 0:
            tri = tri[::-1]
        faces.append(list(tri))
    return pts, faces


def outward(pts, faces):
    """Orient every polygon counter-clockwise seen from outside (the solids
    are convex and contain their centroid)."""
    centre = pts.mean(axis=0)
    out = []
    for f in faces:
        p = pts[f]
        n = np.cross(p[1] - p[0], p[2] - p[0])
        out.append(f if np.dot(n, p[0] - centre) > 0 else f[::-1])
    return out


def g(x):
    s = "%g" % x
    return "0" if s == "-0" else s


def write_stl(name, pts, faces):
    faces = outward(pts, faces)
    with open(os.path.join(HERE, name), "w") as f:
        f.write("solid OpenSCAD_Model\n")
        for poly in faces:
            for k in range(1, len(poly) - 1):
                tri = [poly[0], poly[k], poly[k + 1]]
                a, b, c = pts[tri]
                n = np.cross(b - a, c - a)
                n /= np.linalg.norm(n)
                f.write("  facet normal %s %s %s\n    outer loop\n" % tuple(g(v) for v in n))
                for v in tri:
                    f.write("      vertex %s %s %s\n" % tuple(g(x) for x in pts[v]))
                f.write("    endloop\n  endfacet\n")
        f.write("endsolid OpenSCAD_Model\n")


p, f = cube(10)
write_stl("cube.stl", p @ rotation(30, 45, 10).T, f)
p, f = cylinder(5, 10, 48)
write_stl("cylinder.stl", p @ rotation(20, 0, 35).T, f)
write_stl("sphere.stl", *sphere(10, 48))
a, _ = sphere(3, 24)
b, _ = sphere(5, 24)
write_stl("hull.stl", *hull_mesh(np.concatenate([a, b + [10, 4, 2]])))
