// The rotation section of bench_proximity (rotation.cpp) and its Python
// batch table (python_batch.cpp).
#pragma once

#include <minksum/polytope.hpp>

#include <array>
#include <random>
#include <string>
#include <vector>

// bench_proximity --rotation [--poses N] [--meshes DIR]: prints the section's
// markdown tables on stdout; returns the exit status.
int rotation_section(int argc, char** argv);

// bench_proximity --python-batch [--poses N] [--meshes DIR] [--threads T]
// [--reps R] [--python EXE] [--pythonpath DIR]: the batch API of C++ against
// Python's collide_rigid / distance_rigid on the same poses (python_batch.cpp).
int python_batch_section(int argc, char** argv);

// The pairs of the section: the catalog pairs, then the hulls of the three
// robot links found in `meshes` (a directory; empty: none).  spec_p and
// spec_q are what Python's minksum.load takes for the same polytopes (a
// catalog name, or a mesh path with hull=True).
struct RotationPair {
  std::string name_p, name_q;
  minksum::ConvexPolytope p, q;
  std::string spec_p, spec_q;
  bool hull = false;
};
std::vector<RotationPair> rotation_pairs(const std::string& meshes);

// The doubles of a random rotation matrix (row-major; a random unit
// quaternion's matrix, rounded).
std::array<double, 9> random_rotation(std::mt19937_64& g);
