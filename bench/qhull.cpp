// minksum bench — Qhull (reentrant C library libqhull_r) on rounded pairwise sums.
#include "competitors.hpp"
#include "timer.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <stdexcept>
#include <vector>

namespace minksum::bench {

std::string qhull_version() { return qh_version; }

Outcome qhull_rounded(const ConvexPolytope& a, const ConvexPolytope& b) {
  std::vector<Vec3d> da(a.num_vertices()), db(b.num_vertices());
  for (Index i = 0; i < a.num_vertices(); ++i) da[i] = a.approx(i);
  for (Index i = 0; i < b.num_vertices(); ++i) db[i] = b.approx(i);
  // Qhull's input, prepared before the clock starts (as a program of its own
  // would have it before calling Qhull; bench/qhull_standalone times the same call).
  std::vector<coordT> pts;
  pts.reserve(3 * da.size() * db.size());
  for (const auto& p : da)
    for (const auto& q : db) {
      pts.push_back(p.x + q.x);
      pts.push_back(p.y + q.y);
      pts.push_back(p.z + q.z);
    }
  Outcome o;
  qhT qh_qh;
  qhT* qh = &qh_qh;
  QHULL_LIB_CHECK
  int code;
  {
    char options[] = "qhull";
    Stopwatch sw;
    qh_zero(qh, stderr);
    code = qh_new_qhull(qh, 3, int(da.size() * db.size()), pts.data(), False, options, nullptr, stderr);
    o.seconds = sw.seconds();
  }
  if (code == 0) {
    facetT* facet;
    vertexT* vertex;
    long nf = 0, nv = 0;
    FORALLfacets {
      if (!facet->visible) ++nf;
    }
    FORALLvertices {
      if (!vertex->deleted) ++nv;
    }
    o.v = nv;
    o.f = nf;
    o.e = nv + nf - 2;
    o.note = "Qhull's merged facets";
  } else {
    o.note = "qhull failed with code " + std::to_string(code);
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong, totlong;
  qh_memfreeshort(qh, &curlong, &totlong);
  return o;
}

}  // namespace minksum::bench
