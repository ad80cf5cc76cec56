// Internal to src/nonconvex/: minksum's exact union of convex polytopes
// (union.cpp, docs/nonconvex.md "Method") and the triangulation of a planar
// face with holes (holes.cpp, CGAL's constrained Delaunay triangulation, in a
// translation unit of its own).
#pragma once

#include <minksum/nonconvex.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace minksum {
struct ScaledPoint;  // kernel/plane.hpp
}

namespace minksum::nonconvex_detail {

// A convex polytope as the union needs it: the canonical plane of every
// facet (outward), the facets that are candidates of the boundary (indices
// into planes) with their vertex loops (counter-clockwise seen from
// outside), and a box that contains the nearest doubles of its points.
// `directions`, when given, indexes approximate unit normals of the first
// planes (shared by the pieces of one convex operand, whose plane k is facet
// k of that operand, moved): to reject a piece near a facet, the union
// first tries the plane whose normal points most towards the facet.
// The approximate unit normals of a convex operand's facets, with a cube
// map of the sphere of directions: each cell holds the facets whose normals
// are closest to the cell's centre, closest first, so the facets facing a
// direction are found in constant time (an order of exact tests, never a
// decision).  A cell's list is made when first asked for; best() may be
// called from several threads at once.
class DirectionIndex {
 public:
  DirectionIndex() = default;
  explicit DirectionIndex(std::vector<Vec3d> unit_normals);
  // The facets whose normals point most nearly along d (not normalised),
  // best first: sets `out` to them and returns how many (none when d is zero
  // or not finite).
  std::size_t best(const double d[3], const std::uint16_t*& out) const;
  std::size_t size() const { return normals_.size(); }

  static constexpr int kCells = 32;  // per side of each face of the cube
  static constexpr std::size_t kBest = 6;  // facets kept per cell
  // The direction at the centre of cell (i, j) of a face of the cube (face
  // 2a + s: the face (−1)^s along axis a), the direction its list is for.
  static std::array<double, 3> cell_centre(int face, int i, int j);

 private:
  void fill(int face, int i, int j, std::uint16_t* out) const;
  std::vector<Vec3d> normals_;
  std::size_t width_ = 0;
  mutable std::vector<std::uint16_t> cell_;      // 6 kCells kCells cells of width_ entries
  std::unique_ptr<std::once_flag[]> filled_;  // per cell: its list made
};

struct Piece;

// A facet plane that a piece builds only when an exact test needs it (every
// plane of the sweep's pieces t ⊕ B, most of which only ever meet the
// filter): the doubles of a positive multiple of it, (a, b, c) its primitive
// integer normal and d the offset along it (both times 2^-k when the normal
// is long: lazy_plane_doubles), each the rounding towards zero of its exact
// value (so equal planes have equal doubles, whichever piece and kind of
// facet they come from), and what its builder needs.
struct LazyPlane {
  double a = 0, b = 0, c = 0, d = 0;
  bool filtered = false;    // all four usable in the union's half-space filter
  std::uint8_t tag = 0;     // the builder's (the sweep: the kind of facet and the vertex or edge of t)
  std::int32_t exact = -1;  // the plane in Piece::lazy_exact, when the piece holds it
  std::uint32_t code = 0;   // the builder's (the sweep: the vertex or edge of B)
};

// The doubles of the lazy plane m · x = num / den (m a primitive integer
// normal, den > 0) into out: each of 2^-k m's integers and 2^-k num / den
// rounded towards zero, k = lazy_plane_scale(m), and whether the union's
// filter may use them (each zero exactly or of magnitude in [2^-480,
// 2^480)).  The one key of equal planes, whichever piece and kind of facet
// they come from.  The filter's sign is the plane's own for the same
// reasons as for plane_filter_doubles (kernel/plane.hpp): 2^-k > 0, and a
// truncation scaled by a power of two is the truncation of the scaled value
// in the normal range, which the range check keeps to.
void lazy_plane_doubles(const Integer m[3], const Integer& num, const Integer& den, LazyPlane& out);

// The k of lazy_plane_doubles: 0 when each integer of the primitive normal
// m is below 2^480 (the usual case), else L − 470 for L the bit length of
// the longest (the edge ⊕ edge planes through an erosion's vertices, of
// several hundred bits, have normals of thousands: unscaled, their doubles
// would be infinite and every test of them exact).  A function of m alone,
// so that equal planes are scaled alike.
long lazy_plane_scale(const Integer m[3]);

// Builds plane k (< piece.lazy.size()) of a piece exactly, canonical.
class PlaneBuilder {
 public:
  virtual Plane build(const Piece& piece, Index k) const = 0;
  // Whether plane k of `piece` holds the point of label `label` (a label of
  // Piece::labels of a piece of the same builder) by construction; false
  // when it cannot tell.  Exact: true only when the point is on the plane.
  virtual bool contains(const Piece& piece, Index k, std::uint64_t label) const = 0;

 protected:
  ~PlaneBuilder() = default;
};

// The facet planes: 0 .. lazy.size() − 1 are lazy (built by `builder`,
// which reads the corners), the others planes[k − lazy.size()]; a lazy plane
// that is a candidate is held exactly in lazy_exact.
struct Piece {
  std::vector<LazyPlane> lazy;
  std::vector<Plane> lazy_exact;
  const PlaneBuilder* builder = nullptr;
  // The builder's: the corners of the swept polygon over common
  // denominators, and their numbers.
  std::vector<const ScaledPoint*> scaled_corner;
  std::vector<Index> corner_id;
  std::vector<Plane> planes;
  std::vector<Index> candidates;
  std::vector<std::vector<Point3>> loops;  // one per candidate
  // Per candidate, empty or a label per point of its loop, which
  // builder->contains reads (the sweep: corner and vertex of B summed).
  std::vector<std::vector<std::uint64_t>> labels;
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  const DirectionIndex* directions = nullptr;

  std::size_t num_planes() const { return lazy.size() + planes.size(); }
  // Plane k when the piece holds it exactly (every plane that is not lazy,
  // the lazy candidates), else null.
  const Plane* held(Index k) const {
    if (k >= lazy.size()) return &planes[k - lazy.size()];
    return lazy[k].exact >= 0 ? &lazy_exact[std::size_t(lazy[k].exact)] : nullptr;
  }
  // Plane k, exactly.
  Plane plane(Index k) const {
    if (const Plane* p = held(k)) return *p;
    return builder->build(*this, k);
  }
};

// p as a Piece, with the facets flagged in `candidate` (one flag per facet;
// all when null) as its candidates.
Piece piece_of(const ConvexPolytope& p, const std::vector<char>* candidate = nullptr);

// The boundary of the union of the convex polytopes `parts` (regularised:
// the closure of the union of their interiors): maximal planar faces,
// counter-clockwise seen from outside, a face with a hole triangulated,
// cavities as inner shells, non-manifold edges kept.  Reports "union" with
// the fraction of facet planes done, then "boundary"; fills mesh, clips,
// shells, non_manifold_edges, seconds_union and seconds_boundary of `out`.
// `threads` as parallel_for's.
//
// Only the candidate facets of each part are taken as the boundary's
// candidates (every part still removes what it covers); the caller
// guarantees that the boundary of the union, within the region it cares
// about, lies on candidate facets.  `interior`, when given, is asked for one
// vertex of each connected component of the resulting boundary, and the
// components whose vertex it calls interior are dropped (with their points);
// it is called from several threads at once.
void union_boundary(const std::vector<Piece>& parts, const SumOptions& options, NonconvexSum& out,
                    unsigned threads = 0, const std::function<bool(const Point3&)>& interior = {});
// The same for polytopes, every facet a candidate.
void union_boundary(const std::vector<ConvexPolytope>& parts, const SumOptions& options, NonconvexSum& out,
                    unsigned threads = 0);

// A point of a plane in two exact coordinates (the frame of union.cpp).
struct PlanePoint {
  Rational u, v;
  Index id;  // the vertex it is in the mesh
};

// The triangles of a planar region bounded by simple loops that meet at most
// in vertices: outer loops counter-clockwise, holes clockwise, in the (u, v)
// coordinates; a loop of two vertices is a slit, a segment inside the region
// that becomes an edge of two triangles.  Triangles are counter-clockwise, made of the loops' vertices
// only (ids), covering the region exactly once.  Exact (CGAL constrained
// Delaunay triangulation, exact predicates; no point is constructed).
std::vector<std::array<Index, 3>> triangulate_region(const std::vector<std::vector<PlanePoint>>& loops);

}  // namespace minksum::nonconvex_detail
