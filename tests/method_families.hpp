// The families of operand pairs on which every Minkowski-sum method is
// checked against the chms oracle: one definition, so that every method's
// suite sees exactly the same pairs.
#pragma once

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace minksum::testing {

// Small catalog solids: every pair of them is a test case.
inline const std::vector<std::string>& small_solids() {
  static const std::vector<std::string> solids = {
      "tetra",           "cube",           "octahedron",           "dodecahedron",
      "icosahedron",     "truncated-tetrahedron", "cuboctahedron", "truncated-cube",
      "truncated-octahedron", "rhombicuboctahedron", "triakis-tetrahedron", "rhombic-dodecahedron",
      "triakis-octahedron", "tetrakis-hexahedron", "rhombic-triacontahedron", "icosidodecahedron",
  };
  return solids;
}

// Hull of n random points of the integer lattice [-r, r]^3 (many coplanar
// and collinear points); a flat sample gets more points until it is solid.
inline ConvexPolytope random_lattice_polytope(std::mt19937_64& rng, int n, long r) {
  auto coordinate = [&] { return long(rng() % (2 * r + 1)) - r; };
  std::vector<Point3> pts;
  for (int i = 0; i < n; ++i) pts.push_back(P(coordinate(), coordinate(), coordinate()));
  for (;;) {
    try {
      return ConvexPolytope::hull(pts);
    } catch (const InputError&) {
      pts.push_back(P(coordinate(), coordinate(), coordinate()));
    }
  }
}

// Three pairs per seed, with fixed seeds: two random hulls, two lattice
// polytopes, two exact random rotations of catalog solids.  Calls
// check(a, b, label, seed) for each pair (the label names the pair and the
// seed is in a SCOPED_TRACE, so a failure prints both) and returns how many
// pairs were checked; stops early after a fatal failure.
template <class Check>
int for_each_random_pair(unsigned first_seed, unsigned last_seed, Check check) {
  const std::vector<std::string> solids = {"tetra", "cube", "octahedron", "dodecahedron", "icosahedron",
                                           "cuboctahedron", "truncated-cube", "rhombic-dodecahedron"};
  int done = 0;
  for (unsigned seed = first_seed; seed <= last_seed; ++seed) {
    std::mt19937_64 rng(seed);
    SCOPED_TRACE("seed " + std::to_string(seed));
    {
      std::string a = "random:" + std::to_string(4 + rng() % 30) + ":" + std::to_string(seed);
      std::string b = "random:" + std::to_string(4 + rng() % 30) + ":" + std::to_string(seed + 1000);
      check(catalog_polytope(a), catalog_polytope(b), a + " + " + b, seed);
    }
    {
      ConvexPolytope a = random_lattice_polytope(rng, 8 + int(rng() % 20), 2);
      ConvexPolytope b = random_lattice_polytope(rng, 8 + int(rng() % 20), 3);
      check(a, b, "lattice pair", seed);
    }
    {
      std::string a = solids[rng() % solids.size()] + "@rot:" + std::to_string(rng() % 100000);
      std::string b = solids[rng() % solids.size()] + "@rot:" + std::to_string(rng() % 100000);
      check(catalog_polytope(a), catalog_polytope(b), a + " + " + b, seed);
    }
    done += 3;
    if (::testing::Test::HasFatalFailure()) break;
  }
  return done;
}

}  // namespace minksum::testing
