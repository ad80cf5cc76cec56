// minkowski_sum_nonconvex: convex pieces, pairwise walks, exact union
// (docs/nonconvex.md).
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/parallel.hpp>

#include "nonconvex/nef.hpp"
#include "nonconvex/union.hpp"

#include <algorithm>
#include <chrono>

namespace minksum {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
}  // namespace

std::vector<ConvexPolytope> convex_decomposition(const Solid& s) {
  if (s.convex) return {*s.convex};
  return nonconvex_detail::nef_convex_pieces(s.triangles);
}

NonconvexSum minkowski_sum_nonconvex(const Solid& a, const Solid& b, const SumOptions& options, unsigned threads,
                                     Method method) {
  NonconvexSum out;
  auto t0 = Clock::now();
  options.report("decompose", -1.0);
  const std::vector<ConvexPolytope> pa = convex_decomposition(a);
  options.report("decompose", -1.0);
  const std::vector<ConvexPolytope> pb = convex_decomposition(b);
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
  out.seconds_pairs = since(t0);

  nonconvex_detail::union_boundary(sums, options, out, threads);
  out.volume = mesh_volume(out.mesh);
  return out;
}

}  // namespace minksum
