// Assembly of a Minkowski sum from facet candidates: group by exact normal
// direction, planar convex hull per group, validated polytope.
#include <minksum/error.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "sum/faces.hpp"

namespace minksum {

std::array<Integer, 3> primitive_direction(const Point3& n) {
  Integer l = 1;
  for (int k = 0; k < 3; ++k) mpz_lcm(l.get_mpz_t(), l.get_mpz_t(), n[k].get_den_mpz_t());
  std::array<Integer, 3> d;
  Integer g = 0;
  for (int k = 0; k < 3; ++k) {
    Integer t;
    mpz_divexact(t.get_mpz_t(), l.get_mpz_t(), n[k].get_den_mpz_t());
    d[k] = n[k].get_num() * t;
    mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), d[k].get_mpz_t());
  }
  if (g != 0 && g != 1)
    for (auto& x : d) mpz_divexact(x.get_mpz_t(), x.get_mpz_t(), g.get_mpz_t());
  return d;
}

namespace {

// Indices of the convex hull of coplanar points (plane normal n), counter-
// clockwise about n, without collinear points.  Andrew's monotone chain on
// the projection that drops the coordinate where n is largest; exact.
std::vector<std::size_t> planar_hull(const std::vector<Point3>& pts, const Point3& n) {
  int k = 0;
  for (int t = 1; t < 3; ++t)
    if (cmp(abs(n[t]), abs(n[k])) > 0) k = t;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  std::vector<std::size_t> idx(pts.size());
  for (std::size_t t = 0; t < idx.size(); ++t) idx[t] = t;
  auto less = [&](std::size_t p, std::size_t q) {
    int c = cmp(pts[p][i], pts[q][i]);
    return c != 0 ? c < 0 : cmp(pts[p][j], pts[q][j]) < 0;
  };
  std::sort(idx.begin(), idx.end(), less);
  idx.erase(std::unique(idx.begin(), idx.end(),
                        [&](std::size_t p, std::size_t q) { return pts[p][i] == pts[q][i] && pts[p][j] == pts[q][j]; }),
            idx.end());
  auto turn = [&](std::size_t o, std::size_t p, std::size_t q) {
    Rational v = (pts[p][i] - pts[o][i]) * (pts[q][j] - pts[o][j]) - (pts[p][j] - pts[o][j]) * (pts[q][i] - pts[o][i]);
    return sgn(v);
  };
  if (idx.size() < 3) return idx;
  std::vector<std::size_t> h(2 * idx.size());
  std::size_t m = 0;
  for (std::size_t t = 0; t < idx.size(); ++t) {
    while (m >= 2 && turn(h[m - 2], h[m - 1], idx[t]) <= 0) --m;
    h[m++] = idx[t];
  }
  for (std::size_t t = idx.size() - 1, lower = m + 1; t-- > 0;) {
    while (m >= lower && turn(h[m - 2], h[m - 1], idx[t]) <= 0) --m;
    h[m++] = idx[t];
  }
  h.resize(m - 1);
  if (sgn(n[k]) < 0) std::reverse(h.begin(), h.end());
  return h;
}

}  // namespace

SumResult assemble_sum(const ConvexPolytope& a, const ConvexPolytope& b, std::vector<FacetCandidate> candidates,
                       Method method) {
  struct Group {
    Point3 normal;
    std::vector<std::pair<Index, Index>> pairs;
    FacetProvenance prov;
    int facet_case;
  };
  std::map<std::array<Integer, 3>, std::size_t> by_direction;
  std::vector<Group> groups;
  for (auto& c : candidates) {
    auto [it, fresh] = by_direction.try_emplace(primitive_direction(c.normal), groups.size());
    if (fresh) {
      groups.push_back({c.normal, std::move(c.points), c.provenance, c.facet_case});
      continue;
    }
    Group& g = groups[it->second];
    g.pairs.insert(g.pairs.end(), c.points.begin(), c.points.end());
    // The face of each operand is the largest one any piece saw.
    if (c.provenance.a.dim > g.prov.a.dim) g.prov.a = c.provenance.a;
    if (c.provenance.b.dim > g.prov.b.dim) g.prov.b = c.provenance.b;
  }

  Mesh mesh;
  std::vector<std::pair<Index, Index>> origin;
  std::unordered_map<Point3, Index, Point3Hash> index_of;
  std::vector<Point3> pts;
  for (const Group& g : groups) {
    pts.clear();
    for (auto [i, j] : g.pairs) pts.push_back(a.point(i) + b.point(j));
    std::vector<std::size_t> hull = planar_hull(pts, g.normal);
    if (hull.size() < 3)
      throw std::logic_error(std::string(method_name(method)) + ": a facet candidate has fewer than 3 corners");
    std::vector<Index> poly;
    for (std::size_t t : hull) {
      auto [it, fresh] = index_of.try_emplace(pts[t], Index(mesh.points.size()));
      if (fresh) {
        mesh.points.push_back(pts[t]);
        origin.push_back(g.pairs[t]);
      }
      poly.push_back(it->second);
    }
    mesh.faces.push_back(std::move(poly));
  }

  SumResult r;
  r.method = method;
  try {
    r.polytope = ConvexPolytope::from_mesh(mesh, std::string(method_name(method)) + " result");
  } catch (const InputError& e) {
    throw std::logic_error(std::string("the assembled sum is not a valid polytope: ") + e.what());
  }
  if (r.polytope.num_facets() != groups.size())
    throw std::logic_error(std::string(method_name(method)) + ": assembled facets were merged or lost");
  r.vertex_origin.reserve(r.polytope.num_vertices());
  for (Index v = 0; v < r.polytope.num_vertices(); ++v) r.vertex_origin.push_back(origin[r.polytope.source_vertex(v)]);
  r.facet_provenance.reserve(groups.size());
  for (const Group& g : groups) r.facet_provenance.push_back(g.prov);
  if (std::any_of(groups.begin(), groups.end(), [](const Group& g) { return g.facet_case >= 0; })) {
    r.facet_case.reserve(groups.size());
    for (const Group& g : groups) r.facet_case.push_back(static_cast<std::uint8_t>(std::max(g.facet_case, 0)));
  }
  return r;
}

}  // namespace minksum
