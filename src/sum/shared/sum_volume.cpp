// The exact volume of A ⊕ B from its operands and its facets' provenance,
// by mixed volumes, without the sum's own coordinates.
//
// vol(A ⊕ B) = V(A) + 3 V(A, A, B) + 3 V(A, B, B) + V(B), and
// 3 V(A, A, B) = Σ over the facets F of A of h_B(u_F) area(F), where u_F is
// F's outer unit normal and h_B(u) = max over B of <x, u> (the mixed volume
// as an integral of a support function over a surface area measure, for
// polytopes; R. Schneider, "Convex Bodies: The Brunn-Minkowski Theory",
// Cambridge University Press, 2nd ed. 2014, chapter 5); likewise with A and
// B swapped.  With M_F, the Newell vector
// of F (twice its area along u_F), and b_F any vertex of face_B(u_F) (the
// provenance of the sum's facet whose face of A is F):
//   6 vol(A ⊕ B) = Σ_F <p_F − o_A + 3 b_F, M_F> + Σ_G <q_G − o_B + 3 a_G, M_G>,
// p_F a corner of F and o_A any point (6 V(A) = Σ_F <p_F − o_A, M_F>).
// One cross product per corner of each operand's facets and one dot product
// per facet, on the operands' coordinates (53-bit integers after one common
// scaling when they are doubles), instead of a determinant per triangle of
// the sum on its coordinates (pairs of doubles: twice the bits).
#include <minksum/sum_result.hpp>

#include "kernel/plane.hpp"  // ScaledIntegers

namespace minksum {

Rational sum_volume(const ConvexPolytope& a, const ConvexPolytope& b, const SumResult& r) {
  const std::vector<FacetProvenance>& prov = r.facet_provenance;
  if (prov.size() != r.polytope.num_facets() || !a.coordinates().all_doubles() || !b.coordinates().all_doubles())
    return r.polytope.volume();
  // b_F for every facet F of A, a_G for every facet G of B.
  auto some_vertex = [](const ConvexPolytope& p, Feature x) -> Index {
    switch (x.dim) {
      case FeatureDim::vertex: return x.index;
      case FeatureDim::edge: return p.origin(2 * x.index);
      case FeatureDim::facet: return p.origin(p.facet_halfedge(x.index));
    }
    return kNoIndex;
  };
  std::vector<Index> support_a(a.num_facets(), kNoIndex), support_b(b.num_facets(), kNoIndex);
  for (const FacetProvenance& f : prov) {
    if (f.a.dim == FeatureDim::facet) support_a[f.a.index] = some_vertex(b, f.b);
    if (f.b.dim == FeatureDim::facet) support_b[f.b.index] = some_vertex(a, f.a);
  }
  for (const std::vector<Index>* s : {&support_a, &support_b})
    for (Index v : *s)
      if (v == kNoIndex) return r.polytope.volume();  // (every facet of an operand is a face of one facet of the sum)
  // Both operands' coordinates as integers with one common power of two.
  const Index na = a.num_vertices(), nb = b.num_vertices();
  std::vector<double> raw(3 * (std::size_t(na) + nb));
  for (Index v = 0; v < na; ++v)
    for (int k = 0; k < 3; ++k) raw[3 * std::size_t(v) + k] = a.approx(v)[k];
  for (Index v = 0; v < nb; ++v)
    for (int k = 0; k < 3; ++k) raw[3 * (std::size_t(na) + v) + k] = b.approx(v)[k];
  const ScaledIntegers si(raw.data(), raw.size());
  // GMP's functions on preallocated integers (addmul, submul): no
  // temporary per operation.
  Integer six = 0, m[3], e[2][3], w;
  auto part = [&](const ConvexPolytope& p, std::size_t base, std::size_t qbase, const std::vector<Index>& support) {
    auto X = [&](std::size_t b0, Index v, int k) { return si.value[3 * (b0 + v) + k].get_mpz_t(); };
    for (Index f = 0; f < p.num_facets(); ++f) {
      const Index h0 = p.facet_halfedge(f), p0 = p.origin(h0);
      // M_F = Σ (p_i − p_0) × (p_i+1 − p_0) over the fan of F.
      for (int k = 0; k < 3; ++k) mpz_set_ui(m[k].get_mpz_t(), 0);
      Index h = p.next(h0);
      for (int k = 0; k < 3; ++k) mpz_sub(e[0][k].get_mpz_t(), X(base, p.origin(h), k), X(base, p0, k));
      for (h = p.next(h); h != h0; h = p.next(h)) {
        for (int k = 0; k < 3; ++k) mpz_sub(e[1][k].get_mpz_t(), X(base, p.origin(h), k), X(base, p0, k));
        for (int k = 0; k < 3; ++k) {
          const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          mpz_addmul(m[k].get_mpz_t(), e[0][k1].get_mpz_t(), e[1][k2].get_mpz_t());
          mpz_submul(m[k].get_mpz_t(), e[0][k2].get_mpz_t(), e[1][k1].get_mpz_t());
        }
        for (int k = 0; k < 3; ++k) mpz_swap(e[0][k].get_mpz_t(), e[1][k].get_mpz_t());
      }
      // <p_F − o + 3 b_F, M_F>, o = the operand's vertex 0.
      for (int k = 0; k < 3; ++k) {
        mpz_sub(w.get_mpz_t(), X(base, p0, k), X(base, 0, k));
        mpz_addmul_ui(w.get_mpz_t(), X(qbase, support[f], k), 3);
        mpz_addmul(six.get_mpz_t(), w.get_mpz_t(), m[k].get_mpz_t());
      }
    }
  };
  part(a, 0, na, support_a);
  part(b, na, 0, support_b);
  return si.unscale(six, 3) / 6;
}

}  // namespace minksum
