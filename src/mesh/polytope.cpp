// ConvexPolytope: validation of polygon meshes, coplanar merging, half-edge
// connectivity.  Every decision is the sign of an exact rational expression.
//
// Why the checks below prove convexity: after merging coplanar facets, the
// builder checks (1) the surface is a closed, connected, consistently oriented
// 2-manifold with V - E + F = 2; (2) every facet is a convex polygon turning
// counter-clockwise exactly once around its outward normal; (3) every edge is
// strictly convex; (4) around every vertex the edge directions, projected
// along an axis inside the would-be tangent cone, turn strictly
// counter-clockwise and wind exactly once, so the surface near the vertex is
// the graph of a piecewise-linear function over a plane, convex across each
// edge by (3).  A compact connected surface that is locally convex everywhere
// bounds a convex body (Hadamard; van Heijenoort), so (1)-(4) are equivalent
// to the mesh being the boundary of a convex polytope.
#include "mesh/builder.hpp"

#include <minksum/error.hpp>

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace minksum {

namespace {

std::string vtx(Index v) { return "vertex " + std::to_string(v); }
std::string fct(Index f) { return "facet " + std::to_string(f); }

struct Graph {
  std::vector<Index> origin, facet, next, prev, facet_he, vertex_he;
  Index num_halfedges() const { return Index(origin.size()); }
};

// Link polygons (vertex ids 0..nv-1, every id used) into half-edges.
// `vname` / `fname` translate internal ids into the user's numbering.
Graph link(Index nv, const std::vector<std::vector<Index>>& faces, const std::string& source,
           const std::vector<Index>& vname, const std::vector<Index>& fname) {
  struct EdgeUse {
    Index count = 0;
    Index face0 = kNoIndex, face1 = kNoIndex;
    unsigned dirs = 0;  // bit 0: min->max seen, bit 1: max->min seen
    bool same_direction = false;
  };
  std::unordered_map<std::uint64_t, Index> edge_id;
  std::size_t total = 0;
  for (const auto& f : faces) total += f.size();
  edge_id.reserve(total);
  std::vector<EdgeUse> uses;
  uses.reserve(total / 2 + 1);
  std::vector<std::pair<Index, Index>> ends;  // (min, max) per edge
  auto key = [](Index u, Index v) {
    return (std::uint64_t(std::min(u, v)) << 32) | std::uint64_t(std::max(u, v));
  };
  for (Index f = 0; f < faces.size(); ++f) {
    const auto& poly = faces[f];
    for (std::size_t i = 0; i < poly.size(); ++i) {
      Index u = poly[i], v = poly[(i + 1) % poly.size()];
      auto [it, inserted] = edge_id.try_emplace(key(u, v), Index(uses.size()));
      if (inserted) {
        uses.emplace_back();
        ends.emplace_back(std::min(u, v), std::max(u, v));
      }
      EdgeUse& e = uses[it->second];
      unsigned bit = u < v ? 1u : 2u;
      if (e.dirs & bit) e.same_direction = true;
      e.dirs |= bit;
      if (e.count == 0) e.face0 = f; else if (e.count == 1) e.face1 = f;
      ++e.count;
    }
  }
  auto edge_name = [&](Index e) {
    return "edge " + std::to_string(vname[ends[e].first]) + "-" + std::to_string(vname[ends[e].second]);
  };
  for (Index e = 0; e < uses.size(); ++e)
    if (uses[e].count > 2)
      throw InputError(source, edge_name(e),
                       "non-manifold edge shared by " + std::to_string(uses[e].count) + " facets");
  for (Index e = 0; e < uses.size(); ++e)
    if (uses[e].same_direction)
      throw InputError(source, edge_name(e),
                       "inconsistent orientation: " + fct(fname[uses[e].face0]) + " and " +
                           fct(fname[uses[e].face1]) + " traverse this edge in the same direction");
  for (Index e = 0; e < uses.size(); ++e)
    if (uses[e].count == 1)
      throw InputError(source, edge_name(e),
                       "open mesh: the edge belongs to " + fct(fname[uses[e].face0]) + " only");

  Graph g;
  Index nh = Index(uses.size() * 2);
  g.origin.assign(nh, kNoIndex);
  g.facet.assign(nh, kNoIndex);
  g.next.assign(nh, kNoIndex);
  g.prev.assign(nh, kNoIndex);
  g.facet_he.assign(faces.size(), kNoIndex);
  g.vertex_he.assign(nv, kNoIndex);
  std::vector<Index> hs;
  for (Index f = 0; f < faces.size(); ++f) {
    const auto& poly = faces[f];
    hs.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      Index u = poly[i], v = poly[(i + 1) % poly.size()];
      Index e = edge_id.find(key(u, v))->second;
      Index h = 2 * e + (u < v ? 0u : 1u);
      g.origin[h] = u;
      g.facet[h] = f;
      if (g.vertex_he[u] == kNoIndex) g.vertex_he[u] = h;
      hs.push_back(h);
    }
    for (std::size_t i = 0; i < hs.size(); ++i) {
      g.next[hs[i]] = hs[(i + 1) % hs.size()];
      g.prev[hs[(i + 1) % hs.size()]] = hs[i];
    }
    g.facet_he[f] = hs[0];
  }
  // Vertex manifoldness: the facets around each vertex form a single fan.
  std::vector<Index> outdeg(nv, 0);
  for (Index h = 0; h < nh; ++h) ++outdeg[g.origin[h]];
  for (Index v = 0; v < nv; ++v) {
    Index h = g.vertex_he[v], steps = 0;
    do {
      h = g.prev[h] ^ 1u;
      ++steps;
    } while (h != g.vertex_he[v] && steps <= outdeg[v]);
    if (steps != outdeg[v])
      throw InputError(source, vtx(vname[v]),
                       "non-manifold vertex: its facets form more than one fan");
  }
  // Connected, sphere topology.
  std::vector<char> seen(faces.size(), 0);
  std::vector<Index> stack{0};
  seen[0] = 1;
  std::size_t reached = 1;
  while (!stack.empty()) {
    Index f = stack.back();
    stack.pop_back();
    Index h = g.facet_he[f];
    do {
      Index other = g.facet[h ^ 1u];
      if (!seen[other]) {
        seen[other] = 1;
        ++reached;
        stack.push_back(other);
      }
      h = g.next[h];
    } while (h != g.facet_he[f]);
  }
  if (reached != faces.size()) {
    Index first = Index(std::find(seen.begin(), seen.end(), 0) - seen.begin());
    throw InputError(source, fct(fname[first]),
                     "the mesh has more than one connected component (this facet is not connected to " +
                         fct(fname[0]) + ")");
  }
  long chi = long(nv) - long(uses.size()) + long(faces.size());
  if (chi != 2)
    throw InputError(source, "",
                     "the surface is not a topological sphere (V - E + F = " + std::to_string(chi) +
                         ", genus " + std::to_string((2 - chi) / 2) + ")");
  return g;
}

// Newell normal (twice the vector area) of a polygon: sum (p_i - p_0) x (p_{i+1} - p_0).
Point3 polygon_normal(const std::vector<Point3>& pts, const std::vector<Index>& poly) {
  Point3 n(Rational(0), Rational(0), Rational(0));
  const Point3& o = pts[poly[0]];
  Point3 prev = pts[poly[1]] - o;
  for (std::size_t i = 2; i < poly.size(); ++i) {
    Point3 cur = pts[poly[i]] - o;
    Point3 c = cross(prev, cur);
    n.x += c.x;
    n.y += c.y;
    n.z += c.z;
    prev = std::move(cur);
  }
  return n;
}

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(Index n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

Plane negate(const Plane& p) { return Plane{-p.a, -p.b, -p.c, -p.d}; }

}  // namespace

int sign_det(const Point3& a, const Point3& b, const Point3& c) { return sgn(dot(a, cross(b, c))); }

long check_fan(const Point3& a, const std::vector<Point3>& d) {
  const std::size_t k = d.size();
  for (std::size_t i = 0; i < k; ++i)
    if (sign_det(a, d[i], d[(i + 1) % k]) <= 0) return long(i);
  // Regions relative to the reference ray R = d[0], seen along a:
  // Z same direction as R, P counter-clockwise within (0, pi), O opposite, N within (pi, 2pi).
  const Point3 ra = cross(a, d[0]);  // det(a, R, x) = <a x R, x>
  const Rational aa = dot(a, a), Ra = dot(d[0], a);
  enum Region { Z, P, O, N };
  auto region = [&](const Point3& x) {
    int c = sgn(dot(ra, x));
    if (c > 0) return P;
    if (c < 0) return N;
    // Collinear with R in projection: same or opposite direction.
    int s = sgn(dot(x, d[0]) * aa - dot(x, a) * Ra);
    return s > 0 ? Z : O;
  };
  // Each step turns by an angle in (0, pi); it passes (or lands on) the
  // reference ray exactly when it goes from N into Z or P.
  long winding = 0;
  Region prev = Z;
  for (std::size_t j = 1; j <= k; ++j) {
    Region r = j == k ? Z : region(d[j]);
    if (prev == N && (r == Z || r == P)) ++winding;
    if (j < k && r == Z) ++winding;  // landing on R before the end: a second turn
    prev = r;
  }
  return winding == 1 ? -1 : long(k);
}

Plane PolytopeBuilder::canonical_plane(const Point3& n, const Point3& p) {
  Rational d = dot(n, p);
  Integer l = 1;
  for (const Rational* q : std::initializer_list<const Rational*>{&n.x, &n.y, &n.z, &d})
    mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), q->get_den_mpz_t());
  Plane pl;
  Integer* out[4] = {&pl.a, &pl.b, &pl.c, &pl.d};
  const Rational* in[4] = {&n.x, &n.y, &n.z, &d};
  Integer g = 0;
  for (int i = 0; i < 4; ++i) {
    Integer t;
    mpz_divexact(t.get_mpz_t(), l.get_mpz_t(), in[i]->get_den_mpz_t());
    *out[i] = in[i]->get_num() * t;
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), out[i]->get_mpz_t());
  }
  if (g != 1 && g != 0)
    for (int i = 0; i < 4; ++i) mpz_divexact(out[i]->get_mpz_t(), out[i]->get_mpz_t(), g.get_mpz_t());
  return pl;
}

int Plane::side(const Point3& p) const {
  Rational s = Rational(a) * p.x + Rational(b) * p.y + Rational(c) * p.z - Rational(d);
  return sgn(s);
}

bool operator<(const Plane& p, const Plane& q) {
  if (int c = cmp(p.a, q.a)) return c < 0;
  if (int c = cmp(p.b, q.b)) return c < 0;
  if (int c = cmp(p.c, q.c)) return c < 0;
  return cmp(p.d, q.d) < 0;
}

ConvexPolytope PolytopeBuilder::build(const Mesh& mesh, const std::string& source) {
  const Index n_in = Index(mesh.points.size());
  if (n_in == 0) throw InputError(source, "", "no vertices");
  if (mesh.faces.empty())
    throw InputError(source, "",
                     "no facets, only " + std::to_string(n_in) +
                         " points (use --hull to take the convex hull of a point cloud)");

  // 1. Index range, facet sizes.
  for (Index f = 0; f < mesh.faces.size(); ++f) {
    const auto& poly = mesh.faces[f];
    if (poly.size() < 3)
      throw InputError(source, fct(f), "has " + std::to_string(poly.size()) + " vertices (needs at least 3)");
    for (Index v : poly)
      if (v >= n_in)
        throw InputError(source, fct(f),
                         "refers to vertex " + std::to_string(v) + " but there are only " +
                             std::to_string(n_in) + " vertices");
  }

  // 2. Weld exactly equal points; number the used vertices in input order.
  std::vector<Index> canon(n_in, kNoIndex);
  {
    std::vector<char> used(n_in, 0);
    for (const auto& poly : mesh.faces)
      for (Index v : poly) used[v] = 1;
    std::unordered_map<Point3, Index, Point3Hash> first;
    first.reserve(n_in);
    for (Index v = 0; v < n_in; ++v)
      if (used[v]) canon[v] = first.try_emplace(mesh.points[v], v).first->second;
  }
  std::vector<Index> new_id(n_in, kNoIndex), vname;
  std::vector<Point3> pts;
  for (Index v = 0; v < n_in; ++v)
    if (canon[v] == v) {
      new_id[v] = Index(pts.size());
      pts.push_back(mesh.points[v]);
      vname.push_back(v);
    }
  std::vector<std::vector<Index>> faces(mesh.faces.size());
  std::vector<Index> fname(mesh.faces.size());
  for (Index f = 0; f < mesh.faces.size(); ++f) {
    fname[f] = f;
    faces[f].reserve(mesh.faces[f].size());
    for (Index v : mesh.faces[f]) faces[f].push_back(new_id[canon[v]]);
    std::vector<Index> sorted = faces[f];
    std::sort(sorted.begin(), sorted.end());
    auto dup = std::adjacent_find(sorted.begin(), sorted.end());
    if (dup != sorted.end())
      throw InputError(source, fct(f), "visits " + vtx(vname[*dup]) + " twice");
  }

  // 3. Topology: closed, manifold, consistently oriented, connected sphere.
  Graph g = link(Index(pts.size()), faces, source, vname, fname);

  // 4. Planar facets (exactly) and their outward planes.
  std::vector<Point3> normals(faces.size());
  for (Index f = 0; f < faces.size(); ++f) {
    normals[f] = polygon_normal(pts, faces[f]);
    if (is_zero(normals[f])) throw InputError(source, fct(fname[f]), "has zero area");
    const Point3& o = pts[faces[f][0]];
    for (Index v : faces[f])
      if (sgn(dot(normals[f], pts[v] - o)) != 0)
        throw InputError(source, fct(fname[f]),
                         "is not planar (" + vtx(vname[v]) + " is off the plane of the others)");
  }

  // 5. Orientation from the sign of the volume; flip a consistently inward mesh.
  Rational six_vol = 0;
  {
    const Point3& o = pts[0];
    for (Index f = 0; f < faces.size(); ++f) six_vol += dot(pts[faces[f][0]] - o, normals[f]);
  }
  if (sgn(six_vol) == 0)
    throw InputError(source, "", "zero volume: the solid is flat (all its points are coplanar)");
  if (sgn(six_vol) < 0) {
    for (auto& poly : faces) std::reverse(poly.begin(), poly.end());
    for (auto& n : normals) n = -n;
    g = link(Index(pts.size()), faces, source, vname, fname);
  }
  std::vector<Plane> planes(faces.size());
  for (Index f = 0; f < faces.size(); ++f) planes[f] = canonical_plane(normals[f], pts[faces[f][0]]);

  // 6. Merge adjacent coplanar facets.
  UnionFind uf(Index(faces.size()));
  bool any_merge = false;
  for (Index h = 0; h < g.num_halfedges(); h += 2) {
    Index f = g.facet[h], o = g.facet[h + 1];
    if (planes[f] == planes[o]) {
      uf.unite(f, o);
      any_merge = true;
    } else if (planes[f] == negate(planes[o])) {
      throw InputError(source, fct(fname[f]),
                       "lies back to back with " + fct(fname[o]) + " (zero thickness)");
    }
  }
  std::vector<std::vector<Index>> merged;
  std::vector<Plane> merged_planes;
  std::vector<Index> merged_name;
  if (!any_merge) {
    merged = std::move(faces);
    merged_planes = std::move(planes);
    merged_name = fname;
  } else {
    std::vector<Index> group_of(g.facet_he.size());
    std::vector<Index> group_id(g.facet_he.size(), kNoIndex);
    for (Index f = 0; f < g.facet_he.size(); ++f) {
      Index r = uf.find(f);
      if (group_id[r] == kNoIndex) {
        group_id[r] = Index(merged.size());
        merged.emplace_back();
        merged_planes.push_back(planes[r]);
        merged_name.push_back(fname[r]);
      }
      group_of[f] = group_id[r];
    }
    // Boundary halfedges of each group, keyed by (group, origin).
    std::unordered_map<std::uint64_t, Index> out;
    std::vector<Index> boundary_count(merged.size(), 0), start(merged.size(), kNoIndex);
    for (Index h = 0; h < g.num_halfedges(); ++h) {
      Index gr = group_of[g.facet[h]];
      if (gr == group_of[g.facet[h ^ 1u]]) continue;
      auto [it, ok] = out.try_emplace((std::uint64_t(gr) << 32) | g.origin[h], h);
      if (!ok)
        throw InputError(source, fct(merged_name[gr]),
                         "coplanar facets around " + vtx(vname[g.origin[h]]) +
                             " do not form one convex polygon (the solid is not convex)");
      ++boundary_count[gr];
      if (start[gr] == kNoIndex) start[gr] = h;
    }
    for (Index gr = 0; gr < merged.size(); ++gr) {
      Index h = start[gr];
      if (h == kNoIndex)
        throw InputError(source, fct(merged_name[gr]), "all facets are coplanar (zero volume)");
      do {
        merged[gr].push_back(g.origin[h]);
        h = out.find((std::uint64_t(gr) << 32) | g.origin[h ^ 1u])->second;
      } while (h != start[gr] && merged[gr].size() <= boundary_count[gr]);
      if (merged[gr].size() != boundary_count[gr])
        throw InputError(source, fct(merged_name[gr]),
                         "coplanar facets form a polygon with a hole (the solid is not convex)");
    }
  }

  // 7. Drop vertices of degree 2 (in the middle of an edge) and vertices that
  //    vanished inside merged facets; renumber.
  std::vector<Index> degree(pts.size(), 0);
  for (const auto& poly : merged)
    for (Index v : poly) ++degree[v];
  std::vector<Index> final_id(pts.size(), kNoIndex);
  std::vector<Point3> fpts;
  std::vector<Index> fname_v;
  fpts.reserve(pts.size());
  for (Index v = 0; v < pts.size(); ++v)
    if (degree[v] >= 3) {
      final_id[v] = Index(fpts.size());
      fpts.push_back(std::move(pts[v]));
      fname_v.push_back(vname[v]);
    }
  for (Index f = 0; f < merged.size(); ++f) {
    auto& poly = merged[f];
    std::vector<Index> kept;
    kept.reserve(poly.size());
    for (Index v : poly)
      if (final_id[v] != kNoIndex) kept.push_back(final_id[v]);
    if (kept.size() < 3)
      throw InputError(source, fct(merged_name[f]), "degenerates to fewer than 3 corners");
    poly = std::move(kept);
  }
  Graph fg = link(Index(fpts.size()), merged, source, fname_v, merged_name);

  // 8. Convexity: facets, edges, vertices (see the comment at the top).
  std::vector<Point3> fnormal(merged.size());
  for (Index f = 0; f < merged.size(); ++f) fnormal[f] = merged_planes[f].normal();
  std::vector<Point3> dirs;
  for (Index f = 0; f < merged.size(); ++f) {
    const auto& poly = merged[f];
    dirs.clear();
    for (std::size_t i = 0; i < poly.size(); ++i)
      dirs.push_back(fpts[poly[(i + 1) % poly.size()]] - fpts[poly[i]]);
    if (check_fan(fnormal[f], dirs) >= 0)
      throw InputError(source, fct(merged_name[f]), "is not a convex polygon (the solid is not convex)");
  }
  for (Index h = 0; h < fg.num_halfedges(); h += 2) {
    Index f = fg.facet[h], o = fg.facet[h + 1];
    Point3 e = fpts[fg.origin[h + 1]] - fpts[fg.origin[h]];
    if (sgn(dot(cross(fnormal[f], fnormal[o]), e)) <= 0)
      throw InputError(source,
                       "edge " + std::to_string(fname_v[fg.origin[h]]) + "-" +
                           std::to_string(fname_v[fg.origin[h + 1]]),
                       "reflex edge between " + fct(merged_name[f]) + " and " + fct(merged_name[o]) +
                           " (the solid is not convex)");
  }
  for (Index v = 0; v < fpts.size(); ++v) {
    dirs.clear();
    Point3 sum(Rational(0), Rational(0), Rational(0));
    Index h = fg.vertex_he[v];
    do {
      dirs.push_back(fpts[fg.origin[h ^ 1u]] - fpts[v]);
      sum = sum + dirs.back();
      h = fg.prev[h] ^ 1u;
    } while (h != fg.vertex_he[v]);
    if (is_zero(sum) || check_fan(-sum, dirs) >= 0)
      throw InputError(source, vtx(fname_v[v]), "the solid is not convex around this vertex");
  }

  // 9. The polytope.
  ConvexPolytope p;
  p.points_ = std::move(fpts);
  p.approx_.reserve(p.points_.size());
  for (const auto& q : p.points_) {
    p.approx_.push_back(to_double(q));
    if (p.all_double_ && !is_double(q)) p.all_double_ = false;
  }
  p.source_vertex_ = std::move(fname_v);
  p.planes_ = std::move(merged_planes);
  p.he_origin_ = std::move(fg.origin);
  p.he_facet_ = std::move(fg.facet);
  p.he_next_ = std::move(fg.next);
  p.he_prev_ = std::move(fg.prev);
  p.facet_he_ = std::move(fg.facet_he);
  p.vertex_he_ = std::move(fg.vertex_he);
  return p;
}

// ---------------------------------------------------------------------------

ConvexPolytope ConvexPolytope::from_mesh(const Mesh& mesh, const std::string& source) {
  return PolytopeBuilder::build(mesh, source);
}

Index ConvexPolytope::facet_degree(Index f) const {
  Index n = 0, h = facet_he_[f];
  do {
    ++n;
    h = he_next_[h];
  } while (h != facet_he_[f]);
  return n;
}

Index ConvexPolytope::vertex_degree(Index v) const {
  Index n = 0, h = vertex_he_[v];
  do {
    ++n;
    h = next_around_vertex(h);
  } while (h != vertex_he_[v]);
  return n;
}

std::vector<Index> ConvexPolytope::facet_vertices(Index f) const {
  std::vector<Index> out;
  Index h = facet_he_[f];
  do {
    out.push_back(he_origin_[h]);
    h = he_next_[h];
  } while (h != facet_he_[f]);
  return out;
}

std::vector<Index> ConvexPolytope::vertex_neighbours(Index v) const {
  std::vector<Index> out;
  Index h = vertex_he_[v];
  do {
    out.push_back(target(h));
    h = next_around_vertex(h);
  } while (h != vertex_he_[v]);
  return out;
}

Rational ConvexPolytope::volume() const {
  Rational six = 0;
  const Point3& o = points_[0];
  for (Index f = 0; f < num_facets(); ++f) {
    auto vs = facet_vertices(f);
    Point3 p0 = points_[vs[0]] - o;
    for (std::size_t i = 1; i + 1 < vs.size(); ++i)
      six += dot(p0, cross(points_[vs[i]] - o, points_[vs[i + 1]] - o));
  }
  return six / 6;
}

Mesh ConvexPolytope::to_mesh() const {
  Mesh m;
  m.points = points_;
  m.faces.reserve(num_facets());
  for (Index f = 0; f < num_facets(); ++f) m.faces.push_back(facet_vertices(f));
  return m;
}

ConvexPolytope ConvexPolytope::translated(const Point3& t) const {
  Mesh m = to_mesh();
  for (auto& p : m.points) p = p + t;
  ConvexPolytope r = from_mesh(m);
  r.source_vertex_ = source_vertex_;
  return r;
}

ConvexPolytope ConvexPolytope::negated() const {
  Mesh m = to_mesh();
  for (auto& p : m.points) p = -p;
  for (auto& f : m.faces) std::reverse(f.begin(), f.end());
  ConvexPolytope r = from_mesh(m);
  r.source_vertex_ = source_vertex_;
  return r;
}

std::string ConvexPolytope::check_invariants() const {
  const Index nh = num_halfedges();
  if (nh % 2 != 0) return "odd number of halfedges";
  for (Index h = 0; h < nh; ++h) {
    if (he_next_[h] >= nh || he_prev_[h] >= nh) return "halfedge " + std::to_string(h) + ": bad link";
    if (he_prev_[he_next_[h]] != h) return "halfedge " + std::to_string(h) + ": prev(next(h)) != h";
    if (he_facet_[he_next_[h]] != he_facet_[h]) return "halfedge " + std::to_string(h) + ": next leaves the facet";
    if (target(h) != he_origin_[he_next_[h]]) return "halfedge " + std::to_string(h) + ": next does not start at target";
    if (target(h) == origin(h)) return "halfedge " + std::to_string(h) + ": loop";
  }
  for (Index f = 0; f < num_facets(); ++f)
    if (he_facet_[facet_he_[f]] != f) return "facet " + std::to_string(f) + ": bad halfedge";
  for (Index v = 0; v < num_vertices(); ++v)
    if (he_origin_[vertex_he_[v]] != v) return "vertex " + std::to_string(v) + ": bad halfedge";
  if (euler_characteristic() != 2) return "V - E + F != 2";
  for (Index f = 0; f < num_facets(); ++f)
    for (Index v : facet_vertices(f))
      if (planes_[f].side(points_[v]) != 0) return "facet " + std::to_string(f) + ": vertex off its plane";
  ConvexPolytope again;
  try {
    again = from_mesh(to_mesh());
  } catch (const InputError& e) {
    return std::string("revalidation failed: ") + e.what();
  }
  if (again.num_vertices() != num_vertices() || again.num_edges() != num_edges() ||
      again.num_facets() != num_facets())
    return "revalidation changed the counts (coplanar facets or degree-2 vertices left)";
  for (Index f = 0; f < num_facets(); ++f)
    if (!(again.plane(f) == planes_[f])) return "facet " + std::to_string(f) + ": plane not canonical";
  return "";
}

}  // namespace minksum
