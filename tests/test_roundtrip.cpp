// Every catalog polytope through every format and back, exactly: the same
// vertex set and the same facet planes after validation.
//   * OFF, OBJ, VRML with exact = true hold any rational;
//   * OFF, OBJ, VRML, PLY (ascii and binary) and ascii STL with doubles are
//     exact when every coordinate is a double;
//   * binary STL stores 32-bit floats: exact when every coordinate is a float.
#include <minksum/catalog.hpp>
#include <minksum/io.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "test_support.hpp"

using namespace minksum;
using namespace minksum::testing;

namespace {

std::vector<std::string> all_specs() {
  std::vector<std::string> specs;
  for (const auto& e : catalog_entries()) {
    std::string name = e.syntax.substr(0, e.syntax.find_first_of(" |"));
    if (name.find(':') == std::string::npos && name[0] != '@') specs.push_back(name);
  }
  for (const char* s : {"sphere:1", "sphere:2", "sphere:3", "dioctagonal:9", "random:50:3", "zonotope:5:2",
                        "box:1:1/3:1e-12", "cube@rot:1,2,3,4", "dodecahedron@rot:77", "sphere:2@rot:5",
                        "octahedron@scale:1e150", "tetra@scale:1e-150", "cube@translate:1/3,-2,5"})
    specs.push_back(s);
  return specs;
}

bool all_floats(const ConvexPolytope& p) {
  for (const auto& q : p.points())
    for (int k = 0; k < 3; ++k) {
      if (!is_double(q[k])) return false;
      double d = to_double(q[k]);
      if (double(float(d)) != d || std::isinf(float(d))) return false;
    }
  return true;
}

int g_round_trips = 0;

void round_trip(const ConvexPolytope& p, Format f, const WriteOptions& w, const std::string& label) {
  ++g_round_trips;
  SCOPED_TRACE(label + " as " + format_name(f) + (w.exact ? " exact" : "") + (w.binary ? " binary" : ""));
  std::stringstream buf;
  write_mesh(buf, p.to_mesh(), f, w);
  std::istringstream in(buf.str());
  ConvexPolytope q = ConvexPolytope::from_mesh(read_mesh(in, f, label), label);
  EXPECT_TRUE(same_polytope(p, q));
}

}  // namespace

TEST(RoundTrip, EveryCatalogPolytopeThroughEveryFormat) {
  const auto specs = all_specs();
  ASSERT_GT(specs.size(), 40u);
  int with_doubles = 0, with_floats = 0;
  for (const auto& spec : specs) {
    ConvexPolytope p = catalog_polytope(spec);
    for (Format f : {Format::off, Format::obj, Format::wrl}) round_trip(p, f, {.exact = true}, spec);
    if (!p.coordinates_are_doubles()) continue;
    ++with_doubles;
    with_floats += all_floats(p);
    for (Format f : {Format::off, Format::obj, Format::wrl, Format::ply, Format::stl})
      round_trip(p, f, {.exact = false}, spec);
    round_trip(p, Format::ply, {.exact = false, .binary = true}, spec);
    if (all_floats(p)) round_trip(p, Format::stl, {.exact = false, .binary = true}, spec);
  }
  EXPECT_GT(with_doubles, 20);
  EXPECT_GT(with_floats, 3);
  EXPECT_EQ(g_round_trips, int(3 * specs.size()) + 6 * with_doubles + with_floats);
}
