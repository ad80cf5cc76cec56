// minkowski_sum_nonconvex: convex pieces, pairwise walks, exact union
// (docs/nonconvex.md).
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/parallel.hpp>
#include <minksum/predicates.hpp>
#include <minksum/sweep.hpp>

#include "nonconvex/nef.hpp"
#include "nonconvex/sweep.hpp"
#include "nonconvex/union.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>

namespace minksum {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

std::vector<ConvexPolytope> convex_decomposition(const Solid& s) {
  if (s.convex) return {*s.convex};
  return nonconvex_detail::nef_convex_pieces(s.triangles);
}

namespace {

// Hachenberger's method: both operands decomposed, every pair of pieces
// summed, the union of the pair sums.
NonconvexSum sum_by_decomposition(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads,
                                  Method method) {
  NonconvexSum out;
  out.method = "decomposition";
  out.pair_method = method;
  auto t0 = Clock::now();
  // The fraction of the operands decomposed (each one CGAL call).
  options.report("decompose", 0.0);
  const std::vector<ConvexPolytope> pa = convex_decomposition(a);
  options.report("decompose", 0.5);
  const std::vector<ConvexPolytope> pb = convex_decomposition(b);
  options.report("decompose", 1.0);
  out.pieces_a = pa.size();
  out.pieces_b = pb.size();
  out.seconds_decompose = since(t0);

  // Pair sums (by the walk unless told otherwise), in parallel; progress and cancellation between
  // batches, on this thread.
  t0 = Clock::now();
  const std::size_t n = pa.size() * pb.size();
  std::vector<ConvexPolytope> sums(n);
  const unsigned workers = parallel_threads(threads, n);
  const std::size_t batch = std::max<std::size_t>(1, std::size_t(workers) * 8);
  options.report("pairs", 0.0);
  for (std::size_t start = 0; start < n; start += batch) {
    const std::size_t count = std::min(batch, n - start);
    parallel_for(count, workers, [&](std::size_t k) {
      const std::size_t i = start + k;
      sums[i] = minkowski_sum(pa[i / pb.size()], pb[i % pb.size()], method).polytope;
    });
    options.report("pairs", double(start + count) / double(n));
  }
  out.pairs = n;
  for (const auto& s : sums) {
    out.pair_vertices += s.num_vertices();
    out.pair_facets += s.num_facets();
  }
  out.candidate_facets = out.pair_facets;
  out.seconds_pairs = since(t0);

  nonconvex_detail::union_boundary(sums, options, out, threads);
  if (options.volume) out.volume = mesh_volume(out.mesh);
  return out;
}

// The boundary sweep (docs/nonconvex.md, "Method"): S the swept solid, O the
// other, b a point inside O.  A point x of S ⊕ O has x - O meeting S; x - O
// is connected, so it either meets the surface of S (x is in ∂S ⊕ O, the
// union of the pieces t ⊕ O_j) or lies inside S (x - b is in S).  So
// S ⊕ O = (S + b) ∪ ⋃ (t ⊕ O_j), and as b is inside O the surface of S + b
// lies inside the pieces' union: the boundary of S ⊕ O is the part of the
// union's boundary that is not inside S + b.
NonconvexSum sum_by_sweep(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads,
                          Method method) {
  NonconvexSum out;
  out.method = "sweep";
  const bool sweep_a = !a.convex && (b.convex || a.triangles.faces.size() >= b.triangles.faces.size());
  const Solid& s = sweep_a ? a : b;
  const Solid& o = sweep_a ? b : a;
  out.swept = sweep_a ? 'a' : 'b';
  auto t0 = Clock::now();
  options.report("decompose", 0.0);
  const std::vector<ConvexPolytope> po = convex_decomposition(o);
  options.report("decompose", 1.0);
  std::vector<ConvexSet> pieces;
  if (method == Method::chms) {
    pieces.reserve(po.size());
    for (const ConvexPolytope& p : po) pieces.emplace_back(p);
  }
  nonconvex_detail::SurfaceCones cones(s.triangles);
  // The pieces P ⊕ O_j from the Gaussian maps (triangle_sum.cpp), P a convex
  // polygon of S's surface (coplanar triangles merged: SurfaceCones::
  // merge_coplanar); with --method chms, t ⊕ O_j for each triangle t by the
  // pairwise hull and the candidate test on each facet (a second,
  // independent construction the tests compare it with).
  const bool by_hull = method == Method::chms;
  if (!by_hull) cones.merge_coplanar();
  // O's surface, when O is not convex: a facet of t ⊕ O_j is a candidate
  // only if its face of O_j can touch O's surface with its normal in O's
  // local cone there (SweptPolytope::on_surface).
  std::optional<nonconvex_detail::SurfaceCones> o_cones;
  if (!o.convex) o_cones.emplace(o.triangles);
  // b: the centroid of the first piece's vertices, inside it (a full-dimensional convex polytope).
  Point3 inner(Rational(0), Rational(0), Rational(0));
  for (const Point3& p : po.front().points()) inner = inner + p;
  inner = Rational(1, long(po.front().num_vertices())) * inner;
  const std::size_t nt = by_hull ? cones.triangles() : cones.polygons();
  out.pieces_a = sweep_a ? nt : po.size();
  out.pieces_b = sweep_a ? po.size() : nt;
  out.seconds_decompose = since(t0);

  t0 = Clock::now();
  const std::size_t n = nt * po.size();
  std::vector<nonconvex_detail::Piece> sums(n);
  out.pair_method = by_hull ? Method::chms : Method::walk;
  out.pieces_from_maps = !by_hull;
  std::vector<nonconvex_detail::SweptPolytope> swept;
  if (!by_hull) {
    swept.reserve(po.size());  // (the pieces point into them: no reallocation)
    for (const ConvexPolytope& p : po) swept.emplace_back(p, o_cones ? &*o_cones : nullptr);
  }
  // The lazy planes' doubles per point of S and facet of O_j, made once
  // for the triangles sharing the point, when the table is small enough
  // (up to 2^24 entries over all pieces, 9 bytes each).
  if (!by_hull) {
    std::size_t facets = 0;
    for (const auto& sp : swept) facets += sp.facets();
    if (facets * cones.points() <= (std::size_t(1) << 24))
      for (auto& sp : swept) sp.prepare(cones, threads);
  }
  const unsigned workers = parallel_threads(threads, n);
  const std::size_t batch = std::max<std::size_t>(64, std::size_t(workers) * 64);
  options.report("pairs", 0.0);
  for (std::size_t start = 0; start < n; start += batch) {
    const std::size_t count = std::min(batch, n - start);
    parallel_for(count, workers, [&](std::size_t k) {
      const std::size_t i = start + k;
      const Index t = Index(i / po.size());
      if (!by_hull) {
        sums[i] = swept[i % po.size()].sum(cones, t);
        return;
      }
      const auto& c = cones.triangle(t);
      const ConvexSet tri = ConvexSet::polygon({cones.point(c[0]), cones.point(c[1]), cones.point(c[2])});
      const ConvexPolytope sum = minkowski_sum_sets(tri, pieces[i % po.size()], Method::chms).set.release_polytope();
      std::vector<char> flags(sum.num_facets());
      for (Index f = 0; f < sum.num_facets(); ++f) {
        const Plane& h = sum.plane(f);
        const Point3 u(Rational(h.a), Rational(h.b), Rational(h.c));
        const Vec3d approx = to_double(u);
        flags[f] = cones.candidate(t, RoundedPoint3{u, approx}) ? 1 : 0;
      }
      sums[i] = nonconvex_detail::piece_of(sum, &flags);
    });
    options.report("pairs", double(start + count) / double(n));
  }
  out.pairs = n;
  for (auto& sp : swept) sp.release();  // (the tables serve the pieces' construction only)
  for (const auto& s : sums) {
    out.pair_facets += s.num_planes();
    out.candidate_facets += s.candidates.size();
  }
  out.culled_facets = out.pair_facets - out.candidate_facets;
  out.seconds_pairs = since(t0);

  nonconvex_detail::union_boundary(sums, options, out, threads,
                                   [&](const Point3& p) {
                                     // (For the complement of a solid, its inside is the solid's outside.)
                                     return cones.strictly_inside(p - inner) != s.complement;
                                   });
  // The pieces' millions of exact integers freed by the caller's release
  // (while it does other work), or on every thread rather than one by one
  // on return.
  if (options.release)
    options.release(std::make_shared<std::vector<nonconvex_detail::Piece>>(std::move(sums)));
  else
    parallel_for(n, workers, [&](std::size_t i) { sums[i] = nonconvex_detail::Piece(); });
  if (options.volume) out.volume = mesh_volume(out.mesh);
  return out;
}

}  // namespace

NonconvexSum minkowski_sum_nonconvex(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads,
                                     Method method, NonconvexMethod how) {
  if (how == NonconvexMethod::decomposition || (a.convex && b.convex))
    return sum_by_decomposition(a, b, options, threads, method);
  return sum_by_sweep(a, b, options, threads, method);
}

}  // namespace minksum
