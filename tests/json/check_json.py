"""Test json.schema: every command's --json against one schema (docs/json.md).

Runs each command that has --json on operands of every kind (convex
polytopes, points, segments, polygons, non-convex solids; rounded and exact
output; batches with failing lines; trajectories), parses every line with
Python's strict json module (no NaN or Infinity, no duplicate keys), and
checks each object against the schema below: every key the schema requires
is there with its type, and no key is there that the schema does not name.
Every key of the schema is documented in docs/json.md, in backticks.

Usage: check_json.py --minksum BIN --doc docs/json.md --work DIR
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys

# ---------------------------------------------------------------- the schema
# A type is one of the names below, or a tuple:
#   ("enum", v1, v2, ...)      one of these values
#   ("list", T)                a JSON array of T
#   ("triple", T)              an array of three T
#   ("nullable", T)            null or T
#   ("map", T)                 an object, any keys, every value a T
#   ("one_of", T1, T2, ...)    the first that fits
#   an Obj                     an object with these keys
EXACT = re.compile(r"^-?[0-9]+(/[0-9]+)?$")  # an exact rational as text: an integer or p/q, q > 1


class Obj:
    def __init__(self, name, required, optional=None):
        self.name, self.required, self.optional = name, dict(required), dict(optional or {})

    def extend(self, name, required=None, optional=None):
        return Obj(name, {**self.required, **(required or {})}, {**self.optional, **(optional or {})})


def merge(name, *parts, optional=None):
    req, opt = {}, {}
    for p in parts:
        req.update(p.required)
        opt.update(p.optional)
    opt.update(optional or {})
    return Obj(name, req, opt)


COUNTS = Obj("counts", {"vertices": "int", "edges": "int", "facets": "int"})
KIND = Obj("kind", {"dimension": ("enum", 0, 1, 2, 3),
                    "kind": ("enum", "point", "segment", "polygon", "polytope", "solid")})
VOLUME = Obj("volume", {"volume": "exact", "volume_double": ("nullable", "number")})
OPERAND = merge("operand", Obj("", {"name": "string"}), COUNTS, KIND)
SOLID_OPERAND = OPERAND.extend("solid operand", {"convex": "bool", "pieces": "int"})
ROUNDING_POLYTOPE = Obj("rounding (polytope)", {"coordinates": "int", "max_displacement": "number", "split": "int",
                                               "hull": "bool", "merged": "int", "dropped": "int"})
ROUNDING_SOLID = Obj("rounding (solid)", {"coordinates": "int", "max_displacement": "number", "grid": "number"})
FEATURE = Obj("feature", {"type": ("enum", "vertex", "edge", "facet"), "index": "int"})
WITNESS = Obj("witness", {"facet": "int", "m": FEATURE, "p": FEATURE, "q": FEATURE})
STATUS = ("enum", "separate", "touching", "penetrating")
METHODS = ("enum", "walk", "cvms", "essdms", "mssd", "chms", "cgm")

SUM = merge("sum", COUNTS, KIND, VOLUME, Obj("", {
    "method": "string", "seconds": "number", "phases": ("map", "number"), "operands": ("list", OPERAND),
    "output": ("nullable", "string")}))
SUM_POLYTOPE = SUM.extend("sum (polytope)", {"method": METHODS, "rounding": ("nullable", ROUNDING_POLYTOPE)},
                          {"a": OPERAND, "b": OPERAND, "facet_types": ("map", "int"), "facet_cases": ("map", "int"),
                           "counters": ("map", "int")})
SUM_SET = SUM.extend("sum (sweep)", {"method": METHODS, "route": "string",
                                     "rounding": ("nullable", ROUNDING_POLYTOPE)},
                     {"a": OPERAND, "b": OPERAND})
SUM_SOLID = SUM.extend("sum (solid)", {
    "operation": ("enum", "sum", "erosion", "opening", "closing"), "empty": "bool",
    "method": ("enum", "nonconvex"), "pair_method": "string", "nonconvex_method": ("enum", "sweep", "decomposition"),
    "swept": ("nullable", ("enum", "a", "b")), "pieces": Obj("pieces", {"a": "int", "b": "int"}),
    "pairs": "int", "pair_vertices": ("nullable", "int"), "pair_facets": "int", "candidate_facets": "int",
    "culled_facets": "int",
    "union": Obj("union", {"clips": "int", "shells": "int", "non_manifold_edges": "int", "dropped_components": "int"}),
    "a": SOLID_OPERAND, "b": SOLID_OPERAND, "rounding": ("nullable", ROUNDING_SOLID)})

STATS_COMMON = merge("stats", Obj("", {"name": "string"}), COUNTS, KIND, VOLUME,
                     Obj("", {"coordinates_are_doubles": "bool", "phases": ("map", "number")}))
STATS_POLYTOPE = STATS_COMMON.extend("stats (polytope)", {"max_facet_degree": "int", "max_vertex_degree": "int"})
BOX = Obj("bounding_box", {"min": ("triple", "exact"), "max": ("triple", "exact"),
                           "min_double": ("triple", "number"), "max_double": ("triple", "number")})
STATS_SOLID = STATS_COMMON.extend("stats (solid)", {"convex": "bool", "genus": "int", "shells": "int",
                                                    "bounding_box": BOX})

CONVERT = merge("convert", Obj("", {"name": "string", "output": "string", "format": "string"}), COUNTS, KIND)
CONVERT_POLYTOPE = CONVERT.extend("convert (polytope)", {"rounding": ("nullable", ROUNDING_POLYTOPE)})
CONVERT_SOLID = CONVERT.extend("convert (solid)", {"convex": "bool", "rounding": ("nullable", ROUNDING_SOLID)})

QUERY = Obj("query", {"query": ("enum", "collide", "distance", "depth", "ddepth"), "status": STATUS,
                      "seconds": "number"})
QUERY_COLLIDE = QUERY.extend("query collide", {"witness": WITNESS})
QUERY_DISTANCE = QUERY.extend("query distance", {
    "squared_distance": "exact", "distance": ("nullable", "number"), "direction": ("triple", "exact"),
    "point_p": ("triple", "number"), "point_p_exact": ("triple", "exact"), "point_q": ("triple", "number"),
    "point_q_exact": ("triple", "exact"), "witness": WITNESS})
CERTIFICATE = ("enum", "separating_plane", "simplex", "exact", "closest_points", "nearest_facet", "exit_facet",
               "feature_plane")
QUERY_RIGID_COLLIDE = QUERY.extend("query collide (rotation)", {"certificate": CERTIFICATE})
QUERY_RIGID_DISTANCE = QUERY.extend("query distance (rotation)", {
    "squared_distance": "exact", "distance": ("nullable", "number"), "direction": ("triple", "exact"),
    "point_p": ("triple", "number"), "point_p_exact": ("triple", "exact"), "point_q": ("triple", "number"),
    "point_q_exact": ("triple", "exact"), "certificate": CERTIFICATE})
QUERY_RIGID_DEPTH = QUERY.extend("query depth (rotation)", {
    "squared_depth": "exact", "depth": ("nullable", "number"), "direction": ("triple", "exact"),
    "certificate": CERTIFICATE})
QUERY_RIGID_DDEPTH = QUERY.extend("query ddepth (rotation)", {
    "t": "exact", "depth": ("nullable", "number"), "direction": ("triple", "exact"), "certificate": CERTIFICATE})
QUERY_DEPTH = QUERY.extend("query depth", {"squared_depth": "exact", "depth": ("nullable", "number"),
                                           "direction": ("triple", "exact"), "witness": WITNESS})
QUERY_DDEPTH = QUERY.extend("query ddepth", {"t": "exact", "depth": ("nullable", "number"),
                                             "direction": ("triple", "exact"), "witness": WITNESS})
QUERY_SET = QUERY.extend("query (sweep)", {"obstacle": merge("obstacle", COUNTS, KIND)},
                         {"squared_distance": "exact", "squared_depth": "exact", "t": "exact",
                          "distance": ("nullable", "number"), "depth": ("nullable", "number")})

CGM_MAP = Obj("map", {"id": "int", "vertices": "int", "halfedges": "int", "faces": "int",
                      "real_vertices": "int", "real_edges": "int"})
CGM = merge("cgm", Obj("", {"name": "string", "maps": ("list", CGM_MAP)}), COUNTS, KIND,
            optional={"seconds": "number"})

FRAME = Obj("simulate frame", {"frame": "int", "orientation": "int", "rotation": "string", "rebuilt": "bool",
                               "translation": ("triple", "exact"), "status": STATUS, "certificate": CERTIFICATE,
                               "query_seconds": "number", "build_seconds": "number"},
            {"squared_distance": "exact", "squared_depth": "exact"})

BATCH_LINE = Obj("", {"line": "int", "a": "string", "b": "string"})
BATCH_RESULT = merge("batch result", BATCH_LINE, COUNTS, KIND, VOLUME,
                     Obj("", {"method": ("enum", *METHODS[1:], "nonconvex"), "seconds": "number"}))
ERROR = BATCH_LINE.extend("batch error", {"error": "string", "status": ("enum", 2, 3)})

VIEW = Obj("view", {"page": ("enum", "polytope", "solid", "sum", "scene"), "output": "string"})
VIEW_ONE = merge("view (one operand)", VIEW, Obj("", {"name": "string"}), COUNTS, KIND,
                 optional={"volume": "exact", "convex": "bool"})
VIEW_SUM = merge("view (sum)", VIEW, COUNTS, KIND, Obj("", {"method": "string", "volume": "exact",
                                                           "a": OPERAND, "b": OPERAND}),
                 optional={"route": "string"})
VIEW_SCENE = VIEW.extend("view (scene)", {"name": "string", "shapes": ("list", merge(
    "shape", Obj("", {"kind": ("enum", "polytope", "cgm"), "name": "string"}), COUNTS))})


def check(value, t, where, problems):
    def bad(what):
        problems.append(f"{where}: {what}, got {json.dumps(value)[:120]}")

    if isinstance(t, Obj):
        if not isinstance(value, dict):
            return bad(f"expected an object ({t.name})")
        for k, sub in t.required.items():
            if k not in value:
                problems.append(f"{where}: missing key \"{k}\" ({t.name})")
            else:
                check(value[k], sub, f"{where}.{k}", problems)
        for k, v in value.items():
            if k in t.optional:
                check(v, t.optional[k], f"{where}.{k}", problems)
            elif k not in t.required:
                problems.append(f"{where}: key \"{k}\" is not in the schema of {t.name}")
        return
    if isinstance(t, tuple):
        tag = t[0]
        if tag == "enum":
            if value not in t[1:] or isinstance(value, bool):
                bad(f"expected one of {list(t[1:])}")
        elif tag == "nullable":
            if value is not None:
                check(value, t[1], where, problems)
        elif tag in ("list", "triple"):
            if not isinstance(value, list) or (tag == "triple" and len(value) != 3):
                return bad("expected an array" + (" of three" if tag == "triple" else ""))
            for i, v in enumerate(value):
                check(v, t[1], f"{where}[{i}]", problems)
        elif tag == "map":
            if not isinstance(value, dict):
                return bad("expected an object")
            for k, v in value.items():
                check(v, t[1], f"{where}.{k}", problems)
        elif tag == "one_of":
            for alt in t[1:]:
                trial = []
                check(value, alt, where, trial)
                if not trial:
                    return
            bad("fits none of its alternatives")
        return
    ok = {
        "int": lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= 0,
        "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
        "string": lambda v: isinstance(v, str),
        "bool": lambda v: isinstance(v, bool),
        "exact": lambda v: isinstance(v, str) and EXACT.match(v) is not None,
    }[t]
    if not ok(value):
        bad(f"expected {t}")


def keys_of(t, out):
    if isinstance(t, Obj):
        for k, sub in list(t.required.items()) + list(t.optional.items()):
            out.add(k)
            keys_of(sub, out)
    elif isinstance(t, tuple) and t[0] != "enum":
        for sub in t[1:]:
            keys_of(sub, out)


# ---------------------------------------------------------------- the runs
def strict_loads(text, where):
    def no_constant(name):
        raise ValueError(f"{where}: {name} is not JSON")

    def unique(pairs):
        keys = [k for k, _ in pairs]
        dup = {k for k in keys if keys.count(k) > 1}
        if dup:
            raise ValueError(f"{where}: key {sorted(dup)} twice in one object")
        return dict(pairs)

    return json.loads(text, parse_constant=no_constant, object_pairs_hook=unique)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--minksum", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    work = os.path.abspath(args.work)
    args.minksum = os.path.abspath(args.minksum)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    w = lambda name: os.path.join(work, name)  # noqa: E731

    with open(w("poses.txt"), "w") as f:
        f.write("5,0,0\n0.5,0,0 0,0,0\n# a comment\n1,1,1 rp=1,1,0,0\n")
    with open(w("pairs.jsonl"), "w") as f:
        f.write('{"a": "cube", "b": "tetra"}\n{"a": "cube", "b": "nosuch"}\n{"a": "tube", "b": "cube"}\n'
                '{"a": "sphere:1", "b": "tetra", "method": "chms"}\n{"a": "tube", "b": "cube", "hull": true}\n'
                '{"a": "cube", "b": "segment:0,0,0:1,0,0"}\n{"a": "segment:0,0,0:1,0,0", "b": "point:1,2,3"}\n')

    # (arguments, schema of each line, at least this many lines, exit status)
    runs = [
        (["sum", "cube", "tetra"], SUM_POLYTOPE),
        (["sum", "cube", "tetra", "octahedron"], SUM_POLYTOPE),
        (["sum", "cube", "sphere:2@scale:1/3", "-o", w("r.off")], SUM_POLYTOPE),
        (["sum", "cube", "sphere:2@scale:1/3", "--exact", "-o", w("r_exact.off")], SUM_POLYTOPE),
        (["sum", "dodecahedron", "cube", "--method", "cgm"], SUM_POLYTOPE),
        (["sum", "dodecahedron", "cube", "--method", "essdms"], SUM_POLYTOPE),
        (["sum", "cube", "segment:0,0,0:1,1,1"], SUM_SET),
        (["sum", "point:1,2,3", "segment:0,0,0:1,1,1"], SUM_SET),
        (["sum", "square", "polygon:4"], SUM_SET),
        (["sum", "cube", "segment:0,0,0:1,1,1", "point:1,1,1"], SUM_SET),
        (["sum", "tube", "cube@scale:1/4", "-o", w("t.off")], SUM_SOLID),
        (["sum", "lshape", "cube@scale:1/3", "-o", w("third.off")], SUM_SOLID),
        (["sum", "tube", "cube", "--nonconvex-method", "decomposition"], SUM_SOLID),
        (["erode", "lshape", "cube@scale:1/4", "-o", w("eroded.stl")], SUM_SOLID),
        (["erode", "cube", "cube@scale:3"], SUM_SOLID),
        (["open", "tube", "sphere:1@scale:1/8", "-o", w("opened.off")], SUM_SOLID),
        (["close", "lshape", "cube@scale:1/4"], SUM_SOLID),
        (["erode", "dodecahedron", "sphere:2@scale:1/10", "-o", w("eroded_convex.stl"), "--binary"], SUM_SOLID),
        (["open", "dodecahedron", "sphere:2@scale:1/10", "-o", w("opened_convex.stl"), "--binary"], SUM_SOLID),
        (["stats", "cube"], STATS_POLYTOPE),
        (["stats", w("r.off")], STATS_POLYTOPE),
        (["stats", "tube"], STATS_SOLID),
        (["stats", w("t.off")], STATS_SOLID),
        (["stats", "tube", "--hull"], STATS_POLYTOPE),
        (["convert", w("r.off"), "-o", w("r.obj")], CONVERT_POLYTOPE),
        (["convert", w("r_exact.off"), "-o", w("r.stl"), "--binary"], CONVERT_POLYTOPE),
        (["convert", w("t.off"), "-o", w("t.obj")], CONVERT_SOLID),
        (["convert", w("third.off"), "-o", w("third.stl"), "--binary"], CONVERT_SOLID),
        (["query", "collide", "cube", "tetra"], QUERY_COLLIDE),
        (["query", "distance", "cube", "tetra", "--translate-q", "5,1/3,0"], QUERY_DISTANCE),
        (["query", "depth", "cube", "tetra"], QUERY_DEPTH),
        (["query", "ddepth", "cube", "tetra", "--direction", "1,2,0"], QUERY_DDEPTH),
        # The last pose turns P: answered on the placed bodies (a certificate, no witness).
        (["query", "distance", "cube", "tetra", "--trajectory", w("poses.txt")],
         ("one_of", QUERY_DISTANCE, QUERY_RIGID_DISTANCE), 3),
        (["query", "collide", "cube", "tube", "--hull", "--trajectory", w("poses.txt")],
         ("one_of", QUERY_COLLIDE, QUERY_RIGID_COLLIDE), 3),
        (["query", "collide", "cube", "dodecahedron", "--rotate-q", "1,2,3,4", "--translate-q", "2,1/3,0"],
         QUERY_RIGID_COLLIDE),
        (["query", "distance", "cube", "dodecahedron", "--rotate-q", "1,2,3,4", "--translate-q", "4,1/3,0"],
         QUERY_RIGID_DISTANCE),
        (["query", "depth", "cube", "dodecahedron", "--rotate-q", "1,2,3,4", "--translate-q", "1/2,1/3,0"],
         QUERY_RIGID_DEPTH),
        (["query", "ddepth", "cube", "dodecahedron", "--rotate-q", "1,2,3,4", "--translate-q", "1/2,1/3,0",
          "--direction", "1,2,0"], QUERY_RIGID_DDEPTH),
        (["query", "distance", "cube", "segment:0,0,0:1,1,1", "--translate-q", "5,0,0"], QUERY_SET),
        (["query", "collide", "cube", "segment:3,0,0:5,0,0"], QUERY_SET),
        (["query", "depth", "cube", "point:1/2,0,0"], QUERY_SET),
        (["query", "ddepth", "cube", "square", "--direction", "0,0,1"], QUERY_SET),
        (["cgm", "cube"], CGM),
        (["cgm", "cube", "tetra", "-o", w("scene.wrl")], CGM),
        (["cgm", "tube", "--hull"], CGM),
        (["simulate", "--frames", "6"], FRAME, 6),
        (["simulate", "--frames", "8", "--obstacle", "tube", "--hull"], FRAME, 8),
        (["batch", w("pairs.jsonl"), "--threads", "2"], ("one_of", BATCH_RESULT, ERROR), 7, 2),
        (["view", "cube", "-o", w("v1.html")], VIEW_ONE),
        (["view", "tube", "-o", w("v2.html")], VIEW_ONE),
        (["view", "point:1,2,3", "-o", w("v3.html")], VIEW_ONE),
        (["view", "cube", "tetra", "-o", w("v4.html")], VIEW_SUM),
        (["view", "tube", "cube@scale:1/4", "-o", w("v5.html")], VIEW_SUM),
        (["view", "cube", "segment:0,0,0:1,1,1", "-o", w("v6.html")], VIEW_SUM),
        (["view", w("scene.wrl"), "-o", w("v7.html")], VIEW_SCENE),
    ]
    problems, lines_checked, seen_kinds = [], 0, set()
    for run in runs:
        argv, schema = run[0], run[1]
        at_least = run[2] if len(run) > 2 else 1
        status = run[3] if len(run) > 3 else 0
        cmd = [args.minksum] + argv + ([] if argv[0] == "batch" else ["--json"])
        p = subprocess.run(cmd, capture_output=True, text=True, cwd=work)
        name = "minksum " + " ".join(argv)
        if p.returncode != status:
            problems.append(f"{name}: exit status {p.returncode}, expected {status}: {p.stderr.strip()}")
            continue
        lines = [line for line in p.stdout.split("\n") if line]
        if len(lines) < at_least:
            problems.append(f"{name}: {len(lines)} JSON lines, expected at least {at_least}")
        for i, line in enumerate(lines):
            try:
                obj = strict_loads(line, f"{name}, line {i + 1}")
            except ValueError as e:
                problems.append(f"{name}, line {i + 1}: not strict JSON: {e}: {line[:200]}")
                continue
            check(obj, schema, f"{name}, line {i + 1}", problems)
            lines_checked += 1
            if isinstance(obj, dict) and "kind" in obj:
                seen_kinds.add(obj["kind"])
    for kind in ("point", "segment", "polygon", "polytope", "solid"):
        if kind not in seen_kinds:
            problems.append(f"no result of kind {kind} was checked")

    # Every key of the schema is documented.
    with open(args.doc, encoding="utf-8") as f:
        doc = f.read()
    keys = set()
    for t in [SUM_POLYTOPE, SUM_SET, SUM_SOLID, STATS_POLYTOPE, STATS_SOLID, CONVERT_POLYTOPE, CONVERT_SOLID,
              QUERY_COLLIDE, QUERY_DISTANCE, QUERY_RIGID_COLLIDE, QUERY_RIGID_DISTANCE, QUERY_RIGID_DEPTH, QUERY_RIGID_DDEPTH, QUERY_DEPTH, QUERY_DDEPTH, QUERY_SET, CGM, FRAME, BATCH_RESULT,
              ERROR, VIEW_ONE, VIEW_SUM, VIEW_SCENE]:
        keys_of(t, keys)
    for k in sorted(keys):
        if f"`{k}`" not in doc:
            problems.append(f"{args.doc}: the key `{k}` is not documented")

    if problems:
        print("\n".join(problems))
        print(f"json.schema: {len(problems)} problems in {lines_checked} JSON lines of {len(runs)} commands")
        sys.exit(1)
    shutil.rmtree(work)
    print(f"json.schema: {lines_checked} JSON lines of {len(runs)} commands fit the schema; "
          f"{len(keys)} keys, each documented")


if __name__ == "__main__":
    main()
