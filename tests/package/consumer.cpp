// Uses the installed headers and library: cube ⊕ (cube scaled by 1/2),
// exactly a cube of side 3, and a file written and read back.
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/operand.hpp>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const minksum::ConvexPolytope a = minksum::load_polytope("cube");
  const minksum::ConvexPolytope b = minksum::load_polytope("cube@scale:1/2");
  const minksum::SumResult s = minksum::minkowski_sum(a, b);
  minksum::write_polytope(argv[1], s.polytope, {.exact = true});
  const minksum::ConvexPolytope back = minksum::load_polytope(argv[1]);
  std::cout << back.num_vertices() << " vertices, " << back.num_facets() << " facets, volume "
            << minksum::format_exact(back.volume()) << "\n";
  return 0;
}
