// writable_polytope (io.hpp): the polytope that a format writes exactly, so
// that every file write_polytope makes reads back as a valid convex polytope.
//
// Rounding each vertex of an exact polytope to the nearest double (or, for
// binary STL, float) moves it by less than half an ulp, but a facet with four
// or more vertices is then in general no longer exactly planar, and an edge
// between two almost coplanar facets can turn reflex: a reader that checks
// exactly refuses the file.  So the rounded mesh is validated exactly like a
// file being read (ConvexPolytope::from_mesh), unless the rounded points
// with p's structure are certified locally (PolytopeBuilder::moved, the
// common case: linear, filtered predicates on the doubles); when it is not
// a convex polytope, the exact convex hull of the rounded points is written
// instead:
// its facets are exactly planar and its edges convex by construction, and it
// is within the largest rounding displacement of the exact solid.
#include "io/readers.hpp"
#include "mesh/builder.hpp"

#include <minksum/io.hpp>
#include <minksum/predicates.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <unordered_set>

namespace minksum {

using namespace io_detail;

bool io_detail::holds_exactly(const ConvexPolytope& p, Format format, const WriteOptions& options) {
  if (options.exact && format_info(format).exact) return true;
  return !(format == Format::stl && options.binary) && p.coordinates().all_doubles();
}

namespace {

// Coordinate k of point i minus d, to double precision (for the report), or 0
// when d is exactly the coordinate.
double difference(const PointList& c, std::size_t i, int k, double d) {
  switch (c.form()) {
    case PointList::Form::doubles: return c.approx(i)[k] - d;
    case PointList::Form::double_pairs: return (c.approx(i)[k] - d) + c.low(i)[k];
    case PointList::Form::rationals: {
      const Rational& q = c.exact_ref(i)[k];
      if (q == Rational(d)) return 0;
      const double e = to_double(q - Rational(d));
      return e != 0 ? e : std::copysign(std::numeric_limits<double>::denorm_min(), to_double(q) - d);
    }
  }
  return 0;
}

struct BitsHash {
  std::size_t operator()(const Vec3d& v) const {
    std::uint64_t h = 0;
    for (int k = 0; k < 3; ++k) {
      std::uint64_t u;
      const double d = v[k];
      std::memcpy(&u, &d, 8);
      h = (h ^ u) * 0x9e3779b97f4a7c15ULL;
    }
    return std::size_t(h ^ (h >> 31));
  }
};
struct BitsEqual {
  bool operator()(const Vec3d& a, const Vec3d& b) const { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

// Append facet `poly` (rounded points, counter-clockwise from outside) to
// m: as it is when its rounded points are still exactly coplanar, else split
// into the triangles (polygons) of the upper side of their own hull, whose
// folds are convex by construction: a quadrilateral along the diagonal that
// folds outwards, a larger polygon by the facets of its points' exact hull
// facing the way it faces.  Whether the result is a convex polytope is
// decided afterwards, exactly, by validation.
void split_if_not_planar(Mesh& m, std::vector<Index> poly, std::size_t& split) {
  const auto& v = m.points.approx();
  const std::size_t k = poly.size();
  bool planar = true;
  for (std::size_t i = 3; i < k && planar; ++i) planar = orient3d(v[poly[0]], v[poly[1]], v[poly[2]], v[poly[i]]) == 0;
  if (planar) {
    m.faces.push_back(std::move(poly));
    return;
  }
  ++split;
  if (k == 4) {
    const Index a = poly[0], b = poly[1], c = poly[2], d = poly[3];
    if (orient3d(v[a], v[b], v[c], v[d]) < 0) {  // d below the plane of a, b, c: fold along a-c
      m.faces.push_back({a, b, c});
      m.faces.push_back({a, c, d});
    } else {
      m.faces.push_back({b, c, d});
      m.faces.push_back({b, d, a});
    }
    return;
  }
  PointList points;
  for (Index i : poly) points.push_back(v[i]);
  ConvexPolytope h;
  try {
    h = ConvexPolytope::hull(points);
  } catch (const InputError&) {
    m.faces.push_back(std::move(poly));  // validation will refuse it: the hull of everything follows
    return;
  }
  for (Index g = 0; g < h.num_facets(); ++g) {
    std::vector<Index> loop = h.facet_vertices(g);
    if (normals_dot_sign(h.approx(loop[0]), h.approx(loop[1]), h.approx(loop[2]), v[poly[0]], v[poly[1]],
                         v[poly[2]]) <= 0)
      continue;
    for (Index& i : loop) i = poly[h.source_vertex(i)];
    m.faces.push_back(std::move(loop));
  }
}

}  // namespace

ConvexPolytope writable_polytope(const ConvexPolytope& p, Format format, const WriteOptions& options,
                                 RoundingReport* report) {
  RoundingReport r;
  if (report) *report = r;
  if (io_detail::holds_exactly(p, format, options)) return p;
  const bool floats = format == Format::stl && options.binary;
  const PointList& c = p.coordinates();

  const std::size_t n = c.size();
  Mesh m;
  m.points.reserve(n);
  if (!floats && c.form() == PointList::Form::double_pairs) {
    // A sum of double operands (doubles themselves are written as they
    // are, above), without the per-coordinate dispatch below: the nearest
    // double is approx(i), the displacement low(i).
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3d& h = c.approx(i);
      m.points.push_back(Vec3d{h.x + 0.0, h.y + 0.0, h.z + 0.0});
      const Vec3d& e = c.low(i);
      const int moved = (e.x != 0) + (e.y != 0) + (e.z != 0);
      if (moved == 0) continue;
      r.coordinates += std::size_t(moved);
      // hypot(e) ≤ √3 · max |e_k| < 2 · max |e_k|: no larger than the
      // largest displacement so far when twice that is not.
      if (2 * std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z)}) > r.max_displacement)
        r.max_displacement = std::max(r.max_displacement, std::hypot(e.x, e.y, e.z));
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      double v[3], e[3];
      for (int k = 0; k < 3; ++k) {
        // + 0.0: a coordinate that rounds to -0 is written as 0.
        v[k] = (floats ? double(coordinate_float(c, i, k)) : coordinate_double(c, i, k)) + 0.0;
        e[k] = difference(c, i, k, v[k]);
        if (e[k] != 0) ++r.coordinates;
      }
      r.max_displacement = std::max(r.max_displacement, std::hypot(e[0], e[1], e[2]));
      m.points.push_back(Vec3d{v[0], v[1], v[2]});
    }
  }
  if (r.coordinates == 0) {
    if (report) *report = r;
    return p;
  }
  // The common case, certified locally in linear time: p's structure on the
  // rounded points (docs/data-model.md, "Writing rounded coordinates").
  if (std::optional<ConvexPolytope> q = PolytopeBuilder::moved(p, m.points, &r.split)) {
    if (report) *report = r;
    return std::move(*q);
  }
  {
    std::unordered_set<Vec3d, BitsHash, BitsEqual> seen;
    seen.reserve(n);
    for (const Vec3d& v : m.points.approx()) r.merged += !seen.insert(v).second;
  }
  // With no two vertices rounded together, the mesh below keeps every facet
  // of p whose rounded corners are still exactly coplanar as it is, so an
  // edge between two such facets that the rounding made strictly reflex
  // stays in it, and the validation refuses it as not convex: the hull
  // follows, whatever the splits.  Such an edge is looked for first,
  // exactly: orient3d(p, q, c, d) for the edge p->q, the corner c after q
  // in its facet and the corner d after p in the other facet is > 0 when d
  // lies strictly above the plane of p, q, c, which is the first facet's
  // (or, when that facet is no longer convex at q, the validation refuses
  // it too).
  bool doomed = false;
  if (r.merged == 0) {
    const auto& v = m.points.approx();
    std::vector<char> planar(p.num_facets(), 1);
    for (Index f = 0; f < p.num_facets(); ++f) {
      const std::vector<Index> c = p.facet_vertices(f);
      for (std::size_t i = 3; i < c.size() && planar[f]; ++i)
        planar[f] = orient3d(v[c[0]], v[c[1]], v[c[2]], v[c[i]]) == 0;
    }
    for (Index h = 0; h < p.num_halfedges() && !doomed; h += 2)
      if (planar[p.facet(h)] && planar[p.facet(h ^ 1u)])
        doomed = orient3d(v[p.origin(h)], v[p.target(h)], v[p.target(p.next(h))], v[p.target(p.next(h ^ 1u))]) > 0;
  }
  // A rounded surface that is no longer convex (the usual failure) is told
  // by the probe without an exception (a process's first one costs
  // milliseconds: builder.hpp); other defects throw.  Either way the exact
  // hull of the rounded points follows.
  std::optional<ConvexPolytope> built;
  if (!doomed) {
    m.faces.reserve(p.num_facets());
    for (Index f = 0; f < p.num_facets(); ++f) split_if_not_planar(m, p.facet_vertices(f), r.split);
    try {
      built = PolytopeBuilder::build_if_convex(m, "");
    } catch (const InputError&) {
    }
  }
  ConvexPolytope q;
  if (built) {
    q = std::move(*built);
  } else {
    r.split = 0;
    r.hull = true;
    try {
      q = ConvexPolytope::hull(m.points);
    } catch (const InputError& e) {
      // Would the doubles of every other format do?  (Binary STL only.)
      bool doubles_would_do = false;
      if (floats) try {
          writable_polytope(p, Format::stl, {}, nullptr);
          doubles_would_do = true;
        } catch (const UnrepresentableError&) {
        }
      std::string why = e.problem();
      if (why.rfind("degenerate: ", 0) == 0) why.erase(0, 12);
      throw UnrepresentableError(std::string("rounded to the nearest ") +
                                     (floats ? "32-bit floats (binary STL)" : "doubles") +
                                     ", the vertices no longer make a solid: " + why,
                                 doubles_would_do);
    }
  }
  r.dropped = n - r.merged - q.num_vertices();
  if (report) *report = r;
  return q;
}

}  // namespace minksum
