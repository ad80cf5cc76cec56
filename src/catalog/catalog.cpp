// The catalog spec parser and dispatcher: base ( '@' transform )*.
#include "catalog/catalog_internal.hpp"

#include <algorithm>
#include <functional>
#include <sstream>

namespace minksum {

using namespace catalog_detail;

namespace {

// ---------------------------------------------------------------------------
// Families and transforms: syntax and description (fixed solids come from
// fixed_solids()).
struct Form {
  const char* name;
  const char* syntax;
  const char* description;
};

const Form kFamilies[] = {
    {"sphere", "sphere:L",
     "geodesic sphere of level L (1..9): 20·4^(L-1) triangles, vertices on the unit sphere (doubles)"},
    {"dioctagonal", "dioctagonal:N",
     "squashed pyramid with N facets (4..100000): regular (N-1)-gon base at z=0, apex (0,0,1/8)"},
    {"random", "random:N:SEED", "exact hull of N (4..10^6) pseudo-random unit vectors (doubles), 64-bit SEED"},
    {"zonotope", "zonotope:N:SEED",
     "sum of N (3..256) random integer segments in general position: N(N-1)+2 vertices, N(N-1) facets"},
    {"zonotope", "zonotope:X,Y,Z:...", "sum of the segments [-g,g] for 1..16 explicit generators g=(X,Y,Z)"},
    {"box", "box:X:Y:Z", "axis-aligned box centred at the origin with side lengths X, Y, Z > 0"},
    {"ball", "ball:N",
     "latitude/longitude ball (2..1000): N bands, 2N meridians, 2N(N-1)+2 vertices on the unit sphere"},
    {"prism", "prism:N", "prism over the regular N-gon (3..100000) of circumradius 1, z in [-1, 1]: a cylinder"},
};

// Lower-dimensional sets (docs/sweeps.md): operands of sweeps, not solids.
const Form kFlat[] = {
    {"point", "point:X,Y,Z", "the point (X, Y, Z): a translation when summed"},
    {"segment", "segment:X,Y,Z:X,Y,Z", "the segment between two distinct points: a sweep along it when summed"},
    {"polygon", "polygon:N", "regular N-gon (3..100000) in the plane z=0, vertices on the unit circle (doubles)"},
    {"square", "square", "the square [-1/2, 1/2]^2 in the plane z=0"},
};

bool is_flat(const std::string& name) {
  for (const Form& f : kFlat)
    if (name == f.name) return true;
  return false;
}

const Form kTransforms[] = {
    {"rot", "@rot:SEED", "exact rational rotation of a pseudo-random integer quaternion (64-bit SEED)"},
    {"rot", "@rot:A,B,C,D", "exact rational rotation of the integer quaternion A+Bi+Cj+Dk (not all 0)"},
    {"scale", "@scale:S", "exact scaling by S > 0 about the origin"},
    {"scale", "@scale:X,Y,Z", "exact axis-aligned scaling by X, Y, Z > 0"},
    {"translate", "@translate:X,Y,Z", "exact translation by (X, Y, Z)"},
    {"neg", "@neg", "point reflection through the origin (the solid -P)"},
};

// Non-convex solids (nonconvex.cpp): catalog_mesh() builds them;
// catalog_polytope() refuses them with a NotConvexError.
const Form kNonconvex[] = {
    {"tube", "tube", "the cube [-1,1]^3 with a square hole of side 1 along z (genus 1)"},
    {"tube", "tube:H", "the cube [-1,1]^3 with a square hole of side H (0 < H < 2) along z"},
    {"lshape", "lshape", "prism of height 1 over an L of three unit squares"},
    {"ring", "ring:N", "prism of height 1/2 over the ring between regular N-gons (3..10000) of radii 1 and 1/2"},
    {"star", "star:N", "prism of height 1/2 over an N-pointed star (3..10000), radii 1 and 1/2"},
    {"gear", "gear:N", "prism of height 1/2 over a gear of N teeth (3..10000), radii 3/4 and 1, bore 1/4"},
    {"torus", "torus:M:N", "triangulated torus, core radius 1, tube radius 1/3: M x N vertices (3..1024 each), 2MN triangles"},
};

bool is_nonconvex_name(const std::string& name) {
  for (const Form& f : kNonconvex)
    if (name == f.name) return true;
  return false;
}

bool is_family(const std::string& name) {
  for (const Form& f : kFamilies)
    if (name == f.name) return true;
  return is_nonconvex_name(name);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string::npos ? std::string::npos : pos - start));
    if (pos == std::string::npos) return parts;
    start = pos + 1;
  }
}

std::string base_name(const std::string& spec) { return spec.substr(0, spec.find_first_of(":@")); }

// ---------------------------------------------------------------------------
// Errors: "catalog spec 'SPEC': PROBLEM".
[[noreturn]] void fail(const std::string& spec, const std::string& problem) {
  throw UsageError("catalog spec '" + spec + "': " + problem);
}

// Levenshtein distance, for "did you mean".
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::vector<std::string> all_base_names() {
  std::vector<std::string> names;
  for (const FixedSolid& s : fixed_solids()) {
    names.push_back(s.name);
    for (const std::string& a : s.aliases) names.push_back(a);
  }
  for (const Form& f : kFamilies)
    if (std::find(names.begin(), names.end(), f.name) == names.end()) names.push_back(f.name);
  for (const Form& f : kNonconvex)
    if (std::find(names.begin(), names.end(), f.name) == names.end()) names.push_back(f.name);
  for (const Form& f : kFlat) names.push_back(f.name);
  return names;
}

[[noreturn]] void unknown_name(const std::string& spec, const std::string& name) {
  std::string msg = "unknown catalog name '" + name + "'";
  const std::string best = closest_catalog_name(name);
  if (!best.empty()) msg += " (did you mean '" + best + "'?)";
  msg += "; see 'minksum gen --help' for the names";
  fail(spec, msg);
}

// Parameter parsing.  `form` is the allowed form, e.g. "sphere:L".
Rational number(const std::string& spec, const std::string& form, const std::string& what, const std::string& tok) {
  std::string why;
  const auto q = parse_number(tok, &why);
  if (!q) fail(spec, form + " needs a number " + what + ", got '" + tok + "' (" + why + ")");
  return *q;
}

Integer integer(const std::string& spec, const std::string& form, const std::string& what, const std::string& tok) {
  const Rational q = number(spec, form, what, tok);
  if (q.get_den() != 1) fail(spec, form + " needs an integer " + what + ", got '" + tok + "'");
  return q.get_num();
}

std::uint64_t bounded(const std::string& spec, const std::string& form, const std::string& what,
                      const std::string& tok, std::uint64_t lo, std::uint64_t hi) {
  const Integer z = integer(spec, form, what, tok);
  if (z < Integer(std::to_string(lo)) || z > Integer(std::to_string(hi)))
    fail(spec, form + " needs " + std::to_string(lo) + " <= " + what + " <= " + std::to_string(hi) + ", got " + tok);
  return std::stoull(z.get_str());
}

std::uint64_t seed(const std::string& spec, const std::string& form, const std::string& tok) {
  const Integer z = integer(spec, form, "SEED", tok);
  if (sgn(z) < 0 || z > Integer("18446744073709551615"))
    fail(spec, form + " needs 0 <= SEED <= 18446744073709551615, got " + tok);
  return std::stoull(z.get_str());
}

Rational positive(const std::string& spec, const std::string& form, const std::string& what, const std::string& tok) {
  Rational q = number(spec, form, what, tok);
  if (sgn(q) <= 0) fail(spec, form + " needs " + what + " > 0, got " + tok);
  return q;
}

void arity(const std::string& spec, const std::string& form, const std::vector<std::string>& params,
           std::size_t n) {
  if (params.size() != n)
    fail(spec, form + " takes " + std::to_string(n) + " parameter" + (n == 1 ? "" : "s") + ", got " +
                   std::to_string(params.size()) + " (the form is " + form + ")");
}

// ---------------------------------------------------------------------------
// Base.

ConvexPolytope build_base(const std::string& spec, const std::string& base) {
  std::vector<std::string> parts = split(base, ':');
  const std::string name = parts[0];
  const std::vector<std::string> params(parts.begin() + 1, parts.end());

  if (const FixedSolid* s = find_fixed_solid(name)) {
    if (!params.empty()) fail(spec, "'" + name + "' takes no parameters");
    return s->build(spec);
  }
  if (name == "sphere") {
    const std::string form = "sphere:L";
    arity(spec, form, params, 1);
    return make_sphere(int(bounded(spec, form, "L", params[0], 1, kSphereMaxLevel)), spec);
  }
  if (name == "dioctagonal") {
    const std::string form = "dioctagonal:N";
    arity(spec, form, params, 1);
    return make_dioctagonal(bounded(spec, form, "N", params[0], 4, kDioctagonalMax), spec);
  }
  if (name == "random") {
    const std::string form = "random:N:SEED";
    arity(spec, form, params, 2);
    const std::uint64_t n = bounded(spec, form, "N", params[0], 4, kRandomMax);
    return make_random(n, seed(spec, form, params[1]), spec);
  }
  if (name == "zonotope") {
    const bool explicit_form = !params.empty() && params[0].find(',') != std::string::npos;
    if (!explicit_form) {
      const std::string form = "zonotope:N:SEED";
      arity(spec, form, params, 2);
      const std::uint64_t n = bounded(spec, form, "N", params[0], 3, kZonotopeMax);
      return make_zonotope(n, seed(spec, form, params[1]), spec);
    }
    const std::string form = "zonotope:X,Y,Z:X,Y,Z:...";
    if (params.size() > kZonotopeExplicitMax)
      fail(spec, form + " takes at most " + std::to_string(kZonotopeExplicitMax) + " generators, got " +
                     std::to_string(params.size()));
    std::vector<Point3> gens;
    for (const std::string& p : params) {
      const std::vector<std::string> c = split(p, ',');
      if (c.size() != 3) fail(spec, form + " needs each generator as X,Y,Z, got '" + p + "'");
      gens.emplace_back(number(spec, form, "X", c[0]), number(spec, form, "Y", c[1]), number(spec, form, "Z", c[2]));
    }
    return make_zonotope(gens, spec);
  }
  if (name == "ball") {
    const std::string form = "ball:N";
    arity(spec, form, params, 1);
    return make_ball(bounded(spec, form, "N", params[0], 2, kBallMax), spec);
  }
  if (name == "prism") {
    const std::string form = "prism:N";
    arity(spec, form, params, 1);
    return make_prism(bounded(spec, form, "N", params[0], 3, kDioctagonalMax), spec);
  }
  if (name == "box") {
    const std::string form = "box:X:Y:Z";
    arity(spec, form, params, 3);
    return make_box(positive(spec, form, "X", params[0]), positive(spec, form, "Y", params[1]),
                    positive(spec, form, "Z", params[2]), spec);
  }
  unknown_name(spec, name);
}

// The mesh of a non-convex base (kNonconvex).
Mesh nonconvex_base(const std::string& spec, const std::string& base) {
  std::vector<std::string> parts = split(base, ':');
  const std::string name = parts[0];
  const std::vector<std::string> params(parts.begin() + 1, parts.end());
  if (name == "tube") {
    if (params.empty()) return make_tube(1);
    const std::string form = "tube:H";
    arity(spec, form, params, 1);
    const Rational h = positive(spec, form, "H", params[0]);
    if (h >= 2) fail(spec, form + " needs H < 2 (the hole inside the cube's side 2), got " + params[0]);
    return make_tube(h);
  }
  if (name == "lshape") {
    if (!params.empty()) fail(spec, "'lshape' takes no parameters");
    return make_lshape();
  }
  if (name == "torus") {
    const std::string form = "torus:M:N";
    arity(spec, form, params, 2);
    return make_torus(bounded(spec, form, "M", params[0], 3, 1024), bounded(spec, form, "N", params[1], 3, 1024));
  }
  const std::string form = name + ":N";
  arity(spec, form, params, 1);
  const std::uint64_t n = bounded(spec, form, "N", params[0], 3, kNonconvexMax);
  if (name == "ring") return make_ring(n);
  if (name == "star") return make_star(n);
  return make_gear(n);
}

// ---------------------------------------------------------------------------
// Transforms: parsed (and checked) before the base is built, then applied
// to the vertices of the base's mesh in order.
using Transform = std::function<void(Mesh&)>;

Transform parse_transform(const std::string& spec, const std::string& tr) {
  if (tr.empty()) fail(spec, "empty transform after '@'");
  const std::size_t colon = tr.find(':');
  const std::string name = tr.substr(0, colon);
  const std::string arg = colon == std::string::npos ? std::string() : tr.substr(colon + 1);
  const bool has_arg = colon != std::string::npos;

  if (name == "rot") {
    if (!has_arg) fail(spec, "the transform rot needs rot:SEED or rot:A,B,C,D");
    const std::vector<std::string> c = split(arg, ',');
    std::array<Integer, 4> q;
    if (c.size() == 1) {
      q = random_quaternion(seed(spec, "rot:SEED", c[0]));
    } else if (c.size() == 4) {
      for (int i = 0; i < 4; ++i) q[i] = integer(spec, "rot:A,B,C,D", std::string(1, char('A' + i)), c[i]);
      if (sgn(q[0]) == 0 && sgn(q[1]) == 0 && sgn(q[2]) == 0 && sgn(q[3]) == 0)
        fail(spec, "rot:A,B,C,D needs a non-zero quaternion, got 0,0,0,0");
    } else {
      fail(spec, "the transform rot needs rot:SEED or rot:A,B,C,D, got 'rot:" + arg + "'");
    }
    const Matrix3 r = quaternion_rotation(q);
    return [r](Mesh& mesh) {
      mesh.points.transform([&](const Point3& p) { return r * p; });
    };
  }
  if (name == "scale") {
    if (!has_arg) fail(spec, "the transform scale needs scale:S or scale:X,Y,Z");
    const std::vector<std::string> c = split(arg, ',');
    std::array<Rational, 3> s;
    if (c.size() == 1) {
      s[0] = s[1] = s[2] = positive(spec, "scale:S", "S", c[0]);
    } else if (c.size() == 3) {
      const char* what[3] = {"X", "Y", "Z"};
      for (int i = 0; i < 3; ++i) s[i] = positive(spec, "scale:X,Y,Z", what[i], c[i]);
    } else {
      fail(spec, "the transform scale needs scale:S or scale:X,Y,Z, got 'scale:" + arg + "'");
    }
    return [s](Mesh& mesh) {
      mesh.points.transform([&](Point3 p) {
        for (int i = 0; i < 3; ++i) p[i] *= s[i];
        return p;
      });
    };
  }
  if (name == "translate") {
    const std::string form = "translate:X,Y,Z";
    if (!has_arg) fail(spec, "the transform translate needs " + form);
    const std::vector<std::string> c = split(arg, ',');
    if (c.size() != 3) fail(spec, "the transform translate needs " + form + ", got 'translate:" + arg + "'");
    const Point3 t(number(spec, form, "X", c[0]), number(spec, form, "Y", c[1]), number(spec, form, "Z", c[2]));
    return [t](Mesh& mesh) {
      mesh.points.transform([&](const Point3& p) { return p + t; });
    };
  }
  if (name == "neg") {
    if (has_arg) fail(spec, "the transform neg takes no parameter");
    return [](Mesh& mesh) {
      mesh.points.negate();
      for (auto& f : mesh.faces) std::reverse(f.begin(), f.end());  // keep counter-clockwise from outside
    };
  }
  fail(spec, "unknown transform '" + name +
                 "' (known: rot:SEED, rot:A,B,C,D, scale:S, scale:X,Y,Z, translate:X,Y,Z, neg)");
}

Point3 point_param(const std::string& spec, const std::string& form, const std::string& tok) {
  const std::vector<std::string> c = split(tok, ',');
  if (c.size() != 3) fail(spec, form + " needs each point as X,Y,Z, got '" + tok + "'");
  return Point3(number(spec, form, "X", c[0]), number(spec, form, "Y", c[1]), number(spec, form, "Z", c[2]));
}

// The mesh of a lower-dimensional base: its points, and for a polygon its
// loop as one face (counter-clockwise seen from +z).
Mesh flat_base(const std::string& spec, const std::string& base) {
  std::vector<std::string> parts = split(base, ':');
  const std::string name = parts[0];
  const std::vector<std::string> params(parts.begin() + 1, parts.end());
  Mesh m;
  if (name == "point") {
    arity(spec, "point:X,Y,Z", params, 1);
    m.points.push_back(point_param(spec, "point:X,Y,Z", params[0]));
  } else if (name == "segment") {
    const std::string form = "segment:X,Y,Z:X,Y,Z";
    arity(spec, form, params, 2);
    m.points.push_back(point_param(spec, form, params[0]));
    m.points.push_back(point_param(spec, form, params[1]));
    if (m.points.exact(0) == m.points.exact(1))
      fail(spec, "zero-length segment (both endpoints are equal; a point is point:X,Y,Z)");
  } else if (name == "polygon") {
    const std::string form = "polygon:N";
    arity(spec, form, params, 1);
    const std::uint64_t n = bounded(spec, form, "N", params[0], 3, kDioctagonalMax);
    std::vector<Index> face;
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto p = unit_circle_point(k, n);
      m.points.emplace_back(Rational(p[0]), Rational(p[1]), Rational(0));
      face.push_back(Index(k));
    }
    m.faces.push_back(std::move(face));
  } else {  // square
    if (!params.empty()) fail(spec, "'square' takes no parameters");
    const Rational h(1, 2);
    m.points = PointList{Point3(-h, -h, Rational(0)), Point3(h, -h, Rational(0)), Point3(h, h, Rational(0)),
                         Point3(-h, h, Rational(0))};
    m.faces.push_back({0, 1, 2, 3});
  }
  return m;
}

}  // namespace

ConvexSet catalog_convex_set(const std::string& spec) {
  if (!is_flat(base_name(spec))) return ConvexSet(catalog_polytope(spec));
  const std::vector<std::string> parts = split(spec, '@');
  std::vector<Transform> transforms;
  for (std::size_t i = 1; i < parts.size(); ++i) transforms.push_back(parse_transform(spec, parts[i]));
  Mesh mesh = flat_base(spec, parts[0]);
  for (const Transform& t : transforms) t(mesh);
  if (mesh.points.size() == 1) return ConvexSet::point(mesh.points.exact(0));
  if (mesh.points.size() == 2) return ConvexSet::segment(mesh.points.exact(0), mesh.points.exact(1), spec);
  return ConvexSet::from_mesh(mesh, spec);
}

const std::vector<CatalogEntry>& catalog_entries() {
  static const std::vector<CatalogEntry> entries = [] {
    std::vector<CatalogEntry> e;
    for (const FixedSolid& s : fixed_solids()) {
      std::string syntax = s.name;
      for (const std::string& a : s.aliases) syntax += " | " + a;
      std::ostringstream d;
      d << s.description << " [V " << s.vertices << ", E " << s.edges << ", F " << s.facets << "]";
      e.push_back({syntax, d.str()});
    }
    for (const Form& f : kFamilies) e.push_back({f.syntax, f.description});
    for (const Form& f : kTransforms) e.push_back({f.syntax, f.description});
    return e;
  }();
  return entries;
}

namespace {
template <std::size_t N>
std::vector<CatalogEntry> entries_of(const Form (&forms)[N]) {
  std::vector<CatalogEntry> e;
  for (const Form& f : forms) e.push_back({f.syntax, f.description});
  return e;
}
}  // namespace

const std::vector<CatalogEntry>& nonconvex_catalog_entries() {
  static const std::vector<CatalogEntry> entries = entries_of(kNonconvex);
  return entries;
}

const std::vector<CatalogEntry>& flat_catalog_entries() {
  static const std::vector<CatalogEntry> entries = entries_of(kFlat);
  return entries;
}

std::string closest_catalog_name(const std::string& spec) {
  // The closest name within two edits, else one the text begins.
  const std::string name = base_name(spec);
  std::string best;
  std::size_t best_d = 3;
  for (const std::string& n : all_base_names()) {
    const std::size_t d = edit_distance(name, n);
    if (d < best_d) {
      best_d = d;
      best = n;
    }
  }
  if (best.empty() && name.size() >= 3)
    for (const std::string& n : all_base_names())
      if (n.rfind(name, 0) == 0) return n;
  return best;
}

bool is_catalog_spec(const std::string& spec) {
  const std::string name = base_name(spec);
  return find_fixed_solid(name) != nullptr || is_family(name) || is_flat(name);
}

Mesh catalog_mesh(const std::string& spec) {
  if (spec.empty()) throw UsageError("empty catalog spec; see 'minksum gen --help' for the names");
  const std::vector<std::string> parts = split(spec, '@');
  std::vector<Transform> transforms;
  for (std::size_t i = 1; i < parts.size(); ++i) transforms.push_back(parse_transform(spec, parts[i]));
  Mesh mesh = is_nonconvex_name(base_name(parts[0])) ? nonconvex_base(spec, parts[0])
                                                     : build_base(spec, parts[0]).to_mesh();
  for (const Transform& t : transforms) t(mesh);
  return mesh;
}

void apply_transforms(Mesh& mesh, const std::string& spec, const std::string& transforms) {
  std::vector<Transform> parsed;
  try {
    for (const std::string& part : split(transforms, '@')) parsed.push_back(parse_transform(spec, part));
  } catch (const UsageError& e) {
    // The transform's complaint, about a file operand rather than a catalog spec.
    const std::string what = e.what(), prefix = "catalog spec '";
    throw UsageError(what.rfind(prefix, 0) == 0 ? "operand '" + what.substr(prefix.size()) : what);
  }
  for (const Transform& t : parsed) t(mesh);
}

bool is_nonconvex_catalog_spec(const std::string& spec) { return is_nonconvex_name(base_name(spec)); }

ConvexPolytope catalog_polytope(const std::string& spec) {
  if (spec.empty()) throw UsageError("empty catalog spec; see 'minksum gen --help' for the names");
  const std::vector<std::string> parts = split(spec, '@');
  if (is_nonconvex_name(base_name(parts[0]))) {
    catalog_mesh(spec);  // a bad parameter or transform is a UsageError first
    throw NotConvexError(spec, "", "a non-convex solid of the catalog (only 'minksum sum' takes it)");
  }
  std::vector<Transform> transforms;
  for (std::size_t i = 1; i < parts.size(); ++i) transforms.push_back(parse_transform(spec, parts[i]));
  if (is_flat(base_name(spec)))
    fail(spec, "'" + base_name(spec) + "' is not a solid; this command takes 3-dimensional polytopes only ('minksum sum' also takes points, segments and polygons)");
  ConvexPolytope p = build_base(spec, parts[0]);
  if (transforms.empty()) return p;
  Mesh mesh = p.to_mesh();
  for (const Transform& t : transforms) t(mesh);
  return ConvexPolytope::from_mesh(mesh, spec);
}

}  // namespace minksum
