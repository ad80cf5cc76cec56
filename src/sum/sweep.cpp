// Sums with lower-dimensional convex sets (see sweep.hpp, docs/sweeps.md).
//
// The fast route for a polytope A and a segment or polygon S: thicken S into
// a full-dimensional prism P = S ⊕ Z (Z one or two unit segments along
// coordinate axes, chosen so that P spans 3D), compute X = A ⊕ P by the walk
// (output-sensitive), then remove Z again.  X = M ⊕ Z with M = A ⊕ S, and
// every facet of X with outer normal n is face_M(n) ⊕ face_Z(n); the walk
// records each vertex of X as (vertex v of A, vertex p of P), and p = s + z
// for one vertex s of S, so v + s is a point of M.  Mapping every vertex of X
// to its (v, s) turns a facet of X into the vertex loop of face_M(n) with
// repetitions (a 2D Minkowski sum's boundary visits each summand's vertices
// in order): collapsing them gives M's facets, and the facets of X that
// collapse to fewer than three points (face_M(n) an edge or a vertex) are the
// ones Z added.  The result is validated exactly by the polytope builder
// (ConvexPolytope::from_mesh), so a defect would be an error, never a wrong
// answer.
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/sweep.hpp>

#include <chrono>
#include <unordered_map>

namespace minksum {

namespace {

bool takes_lower_dimensional(Method m) {
  return m == Method::automatic || m == Method::walk || m == Method::chms;
}

// The exact hull of every a_i + b_j (the chms oracle, in any dimension).
ConvexSet pairwise_hull(const ConvexSet& a, const ConvexSet& b) {
  const std::vector<Point3>& va = a.vertices();
  const std::vector<Point3>& vb = b.vertices();
  std::vector<Point3> sums;
  sums.reserve(va.size() * vb.size());
  for (const Point3& p : va)
    for (const Point3& q : vb) sums.push_back(p + q);
  return ConvexSet::hull(sums, "chms");
}

Point3 axis(int k) {
  Point3 e(Rational(0), Rational(0), Rational(0));
  e[k] = 1;
  return e;
}

// The axes of Z for S: the drop axis of a polygon's normal (not in its
// plane); for a segment d, the two axes other than the one of the largest
// |d_k| (d, e_i, e_j are then independent).
std::vector<Point3> thickening(const ConvexSet& s) {
  auto largest = [](const Point3& n) {
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (cmp(abs(n[i]), abs(n[k])) > 0) k = i;
    return k;
  };
  if (s.dimension() == 2) return {axis(largest(s.normal()))};
  const int k = largest(s.vertices()[1] - s.vertices()[0]);
  return {axis((k + 1) % 3), axis((k + 2) % 3)};
}

// The prism of a strictly convex polygon (loop counter-clockwise about n) and
// the segment [0, g], g not parallel to the polygon's plane: its faces are
// known, so it is built from its mesh (validated) rather than by a hull.
// Point 2i is loop[i], point 2i + 1 is loop[i] + g (the order the hull of
// `prism` below would number them).
ConvexPolytope polygon_prism(const std::vector<Point3>& loop, const Point3& n, const Point3& g) {
  const std::size_t k = loop.size();
  Mesh m;
  for (const Point3& p : loop) {
    m.points.push_back(p);
    m.points.push_back(p + g);
  }
  // Walk the loop counter-clockwise about the side g points to.
  const bool up = sgn(dot(g, n)) > 0;
  auto at = [&](std::size_t i) { return Index(up ? i % k : (k - i % k) % k); };
  std::vector<Index> bottom, top;
  for (std::size_t i = 0; i < k; ++i) {
    const Index a = at(i), b = at(i + 1);
    m.faces.push_back({2 * a, 2 * b, 2 * b + 1, 2 * a + 1});
    top.push_back(2 * a + 1);
    bottom.push_back(2 * at(k - 1 - i));
  }
  m.faces.push_back(top);
  m.faces.push_back(bottom);
  return ConvexPolytope::from_mesh(m, "sweep");
}

ConvexPolytope sweep(const ConvexPolytope& a, const ConvexSet& s, const SumOptions& options) {
  // Z's vertices: the sums of subsets of its generators.
  std::vector<Point3> z{Point3(Rational(0), Rational(0), Rational(0))};
  for (const Point3& g : thickening(s)) {
    const std::size_t n = z.size();
    for (std::size_t i = 0; i < n; ++i) z.push_back(z[i] + g);
  }
  const std::vector<Point3>& sv = s.vertices();
  std::vector<Point3> prism;
  prism.reserve(sv.size() * z.size());
  for (const Point3& p : sv)
    for (const Point3& q : z) prism.push_back(p + q);
  const ConvexPolytope p = s.dimension() == 2 ? polygon_prism(sv, s.normal(), z[1]) : ConvexPolytope::hull(prism, "sweep");
  const SumResult x = minkowski_sum_walk(a, p, options);
  options.report("sweep", -1);

  // Vertices of X to points of M, by (vertex of A, vertex of S).
  const std::size_t ns = sv.size();
  std::unordered_map<std::uint64_t, Index> id;
  std::vector<Index> vertex_id(x.polytope.num_vertices());
  Mesh m;
  for (Index v = 0; v < x.polytope.num_vertices(); ++v) {
    const auto [va, vp] = x.vertex_origin[v];
    const std::size_t si = p.source_vertex(vp) / z.size();
    const std::uint64_t key = std::uint64_t(va) * ns + si;
    const auto [it, fresh] = id.emplace(key, Index(m.points.size()));
    if (fresh) m.points.push_back(a.point(va) + sv[si]);
    vertex_id[v] = it->second;
  }
  for (Index f = 0; f < x.polytope.num_facets(); ++f) {
    std::vector<Index> loop;
    for (Index v : x.polytope.facet_vertices(f))
      if (loop.empty() || loop.back() != vertex_id[v]) loop.push_back(vertex_id[v]);
    while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    if (loop.size() >= 3) m.faces.push_back(std::move(loop));
  }
  return ConvexPolytope::from_mesh(m, "sweep");
}

}  // namespace

SetSumResult minkowski_sum_sets(const ConvexSet& a, const ConvexSet& b, Method method, const SumOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  SetSumResult r;
  if (a.full() && b.full()) {
    SumResult s = minkowski_sum(a.polytope(), b.polytope(), method, options);
    r.set = ConvexSet(std::move(s.polytope));
    r.method = s.method;
    r.route = "polytopes";
    r.seconds = s.seconds;
    return r;
  }
  if (!takes_lower_dimensional(method)) {
    const ConvexSet& low = a.full() ? b : a;
    throw UsageError(std::string("method '") + method_name(method) + "' takes 3-dimensional polytopes only, and " +
                     "one operand is a " + dimension_name(low.dimension()) +
                     "; 'walk' (the default) and 'chms' sum points, segments and polygons");
  }
  r.method = method == Method::chms ? Method::chms : Method::walk;
  options.report(method_name(r.method), -1);
  if (r.method == Method::chms) {
    r.route = "hull";
    r.set = pairwise_hull(a, b);
  } else if (a.dimension() == 0 || b.dimension() == 0) {
    r.route = "translation";
    r.set = a.dimension() == 0 ? b.translated(a.vertices()[0]) : a.translated(b.vertices()[0]);
  } else if (a.full() || b.full()) {
    r.route = "sweep";
    r.set = a.full() ? ConvexSet(sweep(a.polytope(), b, options)) : ConvexSet(sweep(b.polytope(), a, options));
  } else {
    r.route = "hull";
    r.set = pairwise_hull(a, b);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace minksum
