// Readers and writers of src/io/include/minksum/io.hpp: round trips through every
// format, parsing details of each format, malformed input, atomic writes and
// operand resolution (<minksum/operand.hpp>).
#include <minksum/catalog.hpp>
#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/parallel.hpp>
#include <minksum/operand.hpp>
#include <minksum/predicates.hpp>
#include <minksum/scene.hpp>

#include "io/readers.hpp"  // parse_coordinate, checked_float
#include "mesh/builder.hpp"  // PolytopeBuilder::moved
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

using namespace minksum;
namespace fs = std::filesystem;

namespace {

std::string data_path(const std::string& rel) { return std::string(MINKSUM_TEST_DATA) + "/" + rel; }

// "p/q" or an integer, base 10, in lowest terms.
Rational q(const char* s) {
  Rational r(s);
  r.canonicalize();
  return r;
}

Rational pow2(int e) {
  Rational r(1);
  if (e >= 0) mpq_mul_2exp(r.get_mpq_t(), r.get_mpq_t(), e);
  else mpq_div_2exp(r.get_mpq_t(), r.get_mpq_t(), -e);
  return r;
}

Mesh cube_mesh() {
  Mesh m;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x) m.points.emplace_back(Rational(x), Rational(y), Rational(z));
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}

const std::vector<std::vector<Index>> kTetraFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

// Exact rationals that are not doubles, and huge integers.
Mesh rational_tetra() {
  Mesh m;
  m.points.emplace_back(q("1/3"), q("-22/7"), pow2(200));
  m.points.emplace_back(-pow2(200) - 1, q("5/1000000000000000000000000000000"), Rational(0));
  m.points.emplace_back(Rational(0), q("123456789012345678901234567890"), q("-1/3"));
  m.points.emplace_back(q("7/2"), Rational(1), q("1/1099511627776"));
  m.faces = kTetraFaces;
  return m;
}

// Every coordinate exactly a double, including extremes.
Mesh double_tetra() {
  Mesh m;
  m.points.emplace_back(1e-300, 5e-324, 1e300);
  m.points.emplace_back(-0.1, 2.2250738585072014e-308, -1.7976931348623157e308);
  m.points.emplace_back(0.0, 1.0 / 3.0, 4.9406564584124654e-324 * 3);
  m.points.emplace_back(123456789.125, -2.5e-3, 1e22);
  m.faces = kTetraFaces;
  return m;
}

// Every coordinate exactly a float (binary STL stores 32-bit floats).
Mesh float_tetra() {
  Mesh m;
  m.points.emplace_back(0.5, -1024.75, 3.0);
  m.points.emplace_back(double(1e-3f), 0.0, double(3.4028234663852886e38f));
  m.points.emplace_back(-7.0, double(1.17549435e-38f), 0.125);
  m.points.emplace_back(1.0, 1.0, double(1.4e-45f));
  m.faces = kTetraFaces;
  return m;
}

Mesh with_nearest_doubles(Mesh m) {
  m.points.transform([](Point3 p) {
    for (int i = 0; i < 3; ++i) p[i] = Rational(to_double(p[i]));
    return p;
  });
  return m;
}

std::string write_to_string(const Mesh& m, Format f, WriteOptions o = {}) {
  std::ostringstream out;
  write_mesh(out, m, f, o);
  return out.str();
}

Mesh read_from_string(const std::string& s, Format f, const std::string& name = "mem") {
  std::istringstream in(s);
  return read_mesh(in, f, name);
}

Mesh round_trip(const Mesh& m, Format f, WriteOptions o = {}) {
  return read_from_string(write_to_string(m, f, o), f);
}

void expect_same(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_TRUE(a.points[i] == b.points[i]) << "point " << i;
  EXPECT_EQ(a.faces, b.faces);
}

// Triangles of a mesh as coordinate triples, each rotated to start at its
// smallest point (orientation kept), sorted: equal for a mesh and its STL.
std::vector<std::array<Point3, 3>> triangles(const Mesh& m) {
  std::vector<std::array<Point3, 3>> out;
  for (const auto& f : m.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      std::array<Point3, 3> t = {m.points[f[0]], m.points[f[i]], m.points[f[i + 1]]};
      auto smallest = std::min_element(t.begin(), t.end()) - t.begin();
      std::rotate(t.begin(), t.begin() + smallest, t.end());
      out.push_back(t);
    }
  std::sort(out.begin(), out.end());
  return out;
}

// Expect InputError whose what() names the file, and has the problem phrase
// and place given.
template <class F>
void expect_input_error(F&& f, const std::string& file, const std::string& problem,
                        const std::string& place = "*") {
  try {
    f();
    ADD_FAILURE() << "no InputError for " << file << " (expected '" << problem << "')";
  } catch (const InputError& e) {
    std::string what = e.what();
    EXPECT_NE(what.find(file), std::string::npos) << what;
    EXPECT_NE(e.problem().find(problem), std::string::npos) << what;
    if (place != "*") {
      EXPECT_EQ(e.place(), place) << what;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError for " << file << ", got: " << e.what();
  }
}

void expect_bad_file(const std::string& rel, const std::string& problem, const std::string& place = "*") {
  const std::string path = data_path(rel);
  expect_input_error([&] { read_mesh(path); }, rel, problem, place);
}

// A scratch directory removed at the end of each test.
class TempDir {
 public:
  TempDir() {
    auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    dir_ = fs::temp_directory_path() / ("minksum_test_io_" + std::to_string(::getpid()) + "_" + std::to_string(stamp));
    fs::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir_)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
  }

 private:
  fs::path dir_;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A big-endian binary PLY of a mesh, built here independently of the writer.
std::string big_endian_ply(const Mesh& m) {
  std::string s = "ply\nformat binary_big_endian 1.0\nelement vertex " + std::to_string(m.points.size()) +
                  "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                  std::to_string(m.faces.size()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  auto put = [&](std::uint64_t v, int bytes) {
    for (int i = bytes - 1; i >= 0; --i) s += char((v >> (8 * i)) & 0xff);
  };
  for (const auto& p : m.points)
    for (int i = 0; i < 3; ++i) {
      double d = to_double(p[i]);
      std::uint64_t u;
      std::memcpy(&u, &d, 8);
      put(u, 8);
    }
  for (const auto& f : m.faces) {
    put(f.size(), 1);
    for (Index v : f) put(v, 4);
  }
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------

TEST(IoFormat, FromPath) {
  EXPECT_EQ(format_from_path("a.off"), Format::off);
  EXPECT_EQ(format_from_path("dir/A.OFF"), Format::off);
  EXPECT_EQ(format_from_path("x.Obj"), Format::obj);
  EXPECT_EQ(format_from_path("/tmp/y.ply"), Format::ply);
  EXPECT_EQ(format_from_path("z.stl"), Format::stl);
  EXPECT_EQ(format_from_path("scene.wrl"), Format::wrl);
  EXPECT_EQ(format_from_path("cube"), std::nullopt);
  EXPECT_EQ(format_from_path("sphere:6"), std::nullopt);
  EXPECT_EQ(format_from_path("notes.txt"), std::nullopt);
  EXPECT_EQ(format_from_path("dir.off/file"), std::nullopt);
  EXPECT_EQ(format_from_path("file."), std::nullopt);
  EXPECT_STREQ(format_name(Format::off), "OFF");
  EXPECT_STREQ(format_name(Format::wrl), "VRML");
}

// --- round trips --------------------------------------------------------------

TEST(IoRoundTrip, ExactFormatsKeepRationalsExactly) {
  for (Format f : {Format::off, Format::obj, Format::wrl}) {
    SCOPED_TRACE(format_name(f));
    for (const Mesh& m : {cube_mesh(), rational_tetra(), double_tetra()}) {
      expect_same(round_trip(m, f, {.exact = true}), m);
    }
  }
}

TEST(IoRoundTrip, DoubleTextKeepsDoublesExactly) {
  // OFF/OBJ/VRML without --exact, PLY ascii and binary, STL ascii.
  const std::vector<std::pair<Format, WriteOptions>> cases = {
      {Format::off, {}}, {Format::obj, {}}, {Format::wrl, {}}, {Format::ply, {}}, {Format::ply, {.binary = true}}};
  for (const auto& [f, o] : cases) {
    SCOPED_TRACE(std::string(format_name(f)) + (o.binary ? " binary" : " ascii"));
    expect_same(round_trip(cube_mesh(), f, o), cube_mesh());
    expect_same(round_trip(double_tetra(), f, o), double_tetra());
    // Not doubles: written as (and read back as) the nearest doubles.
    expect_same(round_trip(rational_tetra(), f, o), with_nearest_doubles(rational_tetra()));
  }
}

TEST(IoRoundTrip, BigEndianPly) {
  for (const Mesh& m : {cube_mesh(), double_tetra()}) expect_same(read_from_string(big_endian_ply(m), Format::ply), m);
}

TEST(IoRoundTrip, StlAsciiWeldsAndKeepsDoubles) {
  for (const Mesh& m : {cube_mesh(), double_tetra()}) {
    Mesh r = round_trip(m, Format::stl);
    EXPECT_EQ(r.points.size(), m.points.size());  // welded back
    EXPECT_EQ(triangles(r), triangles(m));
  }
  Mesh r = round_trip(cube_mesh(), Format::stl);
  EXPECT_EQ(r.faces.size(), 12u);  // quads fan-triangulated
  for (const auto& f : r.faces) EXPECT_EQ(f.size(), 3u);
  EXPECT_EQ(triangles(round_trip(rational_tetra(), Format::stl)), triangles(with_nearest_doubles(rational_tetra())));
}

TEST(IoRoundTrip, StlBinaryKeepsFloats) {
  for (const Mesh& m : {cube_mesh(), float_tetra()}) {
    std::string s = write_to_string(m, Format::stl, {.binary = true});
    std::size_t tris = 0;
    for (const auto& f : m.faces) tris += f.size() - 2;
    EXPECT_EQ(s.size(), 84 + 50 * tris);
    EXPECT_NE(s.substr(0, 5), "solid");
    Mesh r = read_from_string(s, Format::stl);
    EXPECT_EQ(r.points.size(), m.points.size());
    EXPECT_EQ(triangles(r), triangles(m));
  }
  // A double that is not a float is rounded to the nearest float.
  Mesh m = cube_mesh();
  m.points.set(7, Point3(Rational(1), Rational(1), q("1/3")));
  Mesh r = read_from_string(write_to_string(m, Format::stl, {.binary = true}), Format::stl);
  bool found = false;
  for (const auto& p : r.points) found |= p.z == Rational(double(1.0f / 3.0f));
  EXPECT_TRUE(found);
  // Beyond the float range: refused, not written as infinity.
  m.points.set(7, Point3(Rational(1), Rational(1), Rational(1e300)));
  EXPECT_THROW(write_to_string(m, Format::stl, {.binary = true}), UsageError);
}

TEST(IoRoundTrip, ThroughFilesForEveryFormat) {
  TempDir dir;
  for (const char* name : {"a.off", "a.obj", "a.wrl"}) {
    write_mesh(dir.path(name), rational_tetra(), {.exact = true});
    expect_same(read_mesh(dir.path(name)), rational_tetra());
  }
  for (const char* name : {"b.ply", "b.stl", "b.OFF"}) {
    for (bool binary : {false, true}) {
      write_mesh(dir.path(name), double_tetra(), {.binary = binary});
      Mesh r = read_mesh(dir.path(name));
      EXPECT_EQ(triangles(r), triangles(double_tetra())) << name;
      if (std::string(name) == "b.stl") break;  // binary STL holds floats only
    }
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.obj", "a.off", "a.wrl", "b.OFF", "b.ply", "b.stl"}));
}

TEST(IoWrite, ExactRefusedByDoubleOnlyFormats) {
  for (Format f : {Format::ply, Format::stl}) {
    try {
      write_to_string(cube_mesh(), f, {.exact = true});
      ADD_FAILURE() << "no UsageError";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("cannot store exact rationals; use .off, .obj or .wrl"), std::string::npos);
    }
  }
}

TEST(IoWrite, CoordinatesBeyondDoubleRangeNeedExact) {
  Mesh m = cube_mesh();
  m.points.set(7, Point3(pow2(2000), Rational(1), Rational(1)));
  for (Format f : {Format::off, Format::obj, Format::wrl, Format::ply, Format::stl})
    EXPECT_THROW(write_to_string(m, f), UsageError) << format_name(f);
  expect_same(round_trip(m, Format::off, {.exact = true}), m);
}

TEST(IoWrite, OffExactTextAndHeader) {
  std::string s = write_to_string(rational_tetra(), Format::off, {.exact = true});
  EXPECT_EQ(s.rfind("OFF\n", 0), 0u);
  EXPECT_NE(s.find("\n4 4 6\n"), std::string::npos);  // V F E
  EXPECT_NE(s.find("1/3 -22/7 1606938044258990275541962092341162602522202993782792835301376\n"), std::string::npos);
  std::string d = write_to_string(double_tetra(), Format::off);
  EXPECT_NE(d.find("1e-300 5e-324 1e+300\n"), std::string::npos) << d;
}

TEST(IoWrite, VrmlExactUsesExactCoordinate) {
  std::string s = write_to_string(rational_tetra(), Format::wrl, {.exact = true});
  EXPECT_EQ(s.rfind("#VRML V2.0 utf8\n", 0), 0u);
  EXPECT_NE(s.find("ExactCoordinate"), std::string::npos);
  EXPECT_NE(s.find("ratPoint"), std::string::npos);
  std::string d = write_to_string(double_tetra(), Format::wrl);
  EXPECT_NE(d.find("coord Coordinate"), std::string::npos);
  EXPECT_EQ(d.find("ExactCoordinate"), std::string::npos);
}

TEST(IoWrite, PlyWideListCountForLargeFaces) {
  Mesh m;
  for (int i = 0; i < 300; ++i) m.points.emplace_back(Rational(i), Rational(i * i), Rational(0));
  m.faces.emplace_back();
  for (Index i = 0; i < 300; ++i) m.faces[0].push_back(i);
  for (bool binary : {false, true}) {
    std::string s = write_to_string(m, Format::ply, {.binary = binary});
    EXPECT_NE(s.find("property list uint int vertex_indices"), std::string::npos);
    expect_same(read_from_string(s, Format::ply), m);
  }
  EXPECT_NE(write_to_string(cube_mesh(), Format::ply).find("property list uchar int vertex_indices"), std::string::npos);
}

TEST(IoWrite, FaceIndexOutOfRangeIsRefused) {
  Mesh m = cube_mesh();
  m.faces[0][0] = 8;
  EXPECT_THROW(write_to_string(m, Format::off), UsageError);
}

// --- parsing details ------------------------------------------------------------

TEST(IoParse, OffCommentsAndRationals) {
  Mesh m = read_mesh(data_path("io/comments_rational.off"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.points[1].x, q("1/3"));
  EXPECT_EQ(m.points[2].y, q("-22/7"));
  EXPECT_EQ(m.points[3].z, pow2(200));
  EXPECT_EQ(m.faces, kTetraFaces);
}

TEST(IoParse, OffColourVariantAndCountsOnMagicLine) {
  Mesh m = read_mesh(data_path("io/coff_inline_counts.off"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_TRUE(m.points[3] == Point3(Rational(0), Rational(0), Rational(1)));
  EXPECT_EQ(m.faces, kTetraFaces);
  // Decimal tokens mean the nearest double; the edge count may be absent.
  Mesh d = read_from_string("OFF\n3 1\n0.1 -2.5e-3 .5\n5. 1E300 0x1.8p-3\n0 0 0\n3 0 1 2\n", Format::off);
  EXPECT_EQ(d.points[0].x, Rational(0.1));
  EXPECT_EQ(d.points[0].y, Rational(-2.5e-3));
  EXPECT_EQ(d.points[0].z, q("1/2"));
  EXPECT_EQ(d.points[1].y, Rational(1e300));
  EXPECT_EQ(d.points[1].z, q("3/16"));
  // Plain OFF with extra numbers on a vertex line is an error.
  expect_input_error([] { read_from_string("OFF\n3 1 0\n0 0 0 1\n1 0 0\n0 1 0\n3 0 1 2\n", Format::off); },
                     "mem", "unexpected token '1' after vertex 0", "line 3");
}

TEST(IoParse, OffWithoutFacesIsAPointCloud) {
  Mesh m = read_from_string("OFF\n2 0 0\n1 2 3\n4 5 6\n", Format::off);
  EXPECT_EQ(m.points.size(), 2u);
  EXPECT_TRUE(m.faces.empty());
}

TEST(IoParse, ObjNegativeIndicesAndVertexTokens) {
  Mesh m = read_mesh(data_path("io/relative_indices.obj"));
  ASSERT_EQ(m.points.size(), 8u);
  EXPECT_TRUE(m.points[7] == Point3(Rational(1), Rational(1), Rational(1)));  // v 2 2 2 2 (w divides)
  expect_same(m, cube_mesh());
}

TEST(IoParse, ObjRationalsHomogeneousAndColours) {
  Mesh m = read_from_string("v 1/3 -22/7 1 3\nv 1 2 3 0.5 0.5 0.5\nv 0 0 0\nl 1 2\nf 1 2 3\n", Format::obj);
  EXPECT_EQ(m.points[0].x, q("1/9"));
  EXPECT_EQ(m.points[0].y, q("-22/21"));
  EXPECT_EQ(m.points[0].z, q("1/3"));
  EXPECT_TRUE(m.points[1] == Point3(Rational(1), Rational(2), Rational(3)));
  EXPECT_EQ(m.faces, (std::vector<std::vector<Index>>{{0, 1, 2}}));
  expect_input_error([] { read_from_string("v 1 2 3 0\n", Format::obj); }, "mem", "w = 0", "line 1");
  expect_input_error([] { read_from_string("v 0 0 0\nf -1 -2 -3\n", Format::obj); }, "mem",
                     "refers to vertex -2 but only 1 vertices are defined so far", "line 2");
  expect_input_error([] { read_from_string("v 0 0 0\nfoo 1\n", Format::obj); }, "mem", "unexpected token 'foo'",
                     "line 2");
  expect_input_error([] { read_from_string("v 0 0 0\nf 1 2\n", Format::obj); }, "mem",
                     "face 1 has 2 vertices (at least 3 needed)", "line 2");
}

// FCL's test meshes start with "648 216", the vertex and face counts: the
// message says what the line is and what to do.
TEST(IoParse, ObjStartingWithACountLineGetsAHint) {
  expect_input_error([] { read_from_string("648 216\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", Format::obj); }, "mem",
                     "unexpected token '648' (a line of numbers before the first statement, like a vertex and face "
                     "count, is not OBJ: remove that line and the rest reads as OBJ)",
                     "line 1");
  // After the first statement a number is a plain unexpected token.
  try {
    read_from_string("v 0 0 0\n648 216\n", Format::obj);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.place(), "line 2");
    EXPECT_EQ(e.problem(), "unexpected token '648'");
  }
}

TEST(IoParse, PlyExtraPropertiesAndElements) {
  Mesh m = read_mesh(data_path("io/extra_props.ply"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_TRUE(m.points[1] == Point3(1.5, 0.0, 0.0));
  EXPECT_TRUE(m.points[2] == Point3(0.0, -2.25, 0.0));
  EXPECT_EQ(m.points[3].z, Rational(1e-3));
  EXPECT_EQ(m.faces, kTetraFaces);
}

TEST(IoParse, PlyBigEndianMixedTypesAndVertexIndex) {
  Mesh m = read_mesh(data_path("io/big_endian_types.ply"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_TRUE(m.points[1] == Point3(Rational(-3), Rational(0), Rational(0)));
  EXPECT_TRUE(m.points[2] == Point3(Rational(0), Rational(70000), Rational(0)));
  EXPECT_EQ(m.points[3].z, Rational(0.1));  // the double 0.1, exactly
  EXPECT_EQ(m.faces, kTetraFaces);
}

TEST(IoParse, BinaryStlWhoseHeaderSaysSolid) {
  const std::string path = data_path("io/solid_header_binary.stl");
  EXPECT_EQ(slurp(path).substr(0, 5), "solid");
  Mesh m = read_mesh(path);
  EXPECT_EQ(m.points.size(), 4u);  // 12 vertices welded to 4
  ASSERT_EQ(m.faces.size(), 4u);
  Mesh tetra;
  tetra.points = {Point3(0., 0., 0.), Point3(1., 0., 0.), Point3(0., 1., 0.), Point3(0., 0., 1.)};
  tetra.faces = kTetraFaces;
  EXPECT_EQ(triangles(m), triangles(tetra));
}

TEST(IoParse, AsciiStlWelds) {
  Mesh m = read_mesh(data_path("bad/triangulated_cube.stl"));
  EXPECT_EQ(m.points.size(), 8u);
  EXPECT_EQ(m.faces.size(), 12u);
  EXPECT_EQ(triangles(m), triangles(cube_mesh()));
}

TEST(IoParse, VrmlExactCoordinateSample) {
  Mesh m = read_mesh(data_path("io/exact_tetra.wrl"));
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.points[1].x, q("1/3"));
  EXPECT_EQ(m.points[2].y, q("-22/7"));
  EXPECT_EQ(m.points[3].z, pow2(200));
  EXPECT_EQ(m.faces, kTetraFaces);
}

TEST(IoParse, VrmlCoordinateCcwAndUse) {
  const std::string s =
      "#VRML V2.0 utf8\n"
      "Group { children [ Shape { geometry IndexedFaceSet {\n"
      "  ccw FALSE\n"
      "  coord DEF pts Coordinate { point [ 0 0 0 1 0 0, 0 1 0, 0 0 0.5 ] }\n"
      "  coordIndex [ 0 1 2 -1 0 3 1 -1 0 2 3 -1 1 3 2 ]\n"
      "} } ] }\n";
  Mesh m = read_from_string(s, Format::wrl);
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.points[3].z, q("1/2"));
  EXPECT_EQ(m.faces, kTetraFaces);  // ccw FALSE: every polygon reversed
  expect_input_error([] { read_from_string("#VRML V1.0 ascii\n", Format::wrl); }, "mem", "VRML 1.0");
  expect_input_error([] { read_from_string("#VRML V2.0 utf8\nShape { }\n", Format::wrl); }, "mem",
                     "no IndexedFaceSet");
  expect_input_error(
      [] {
        read_from_string("#VRML V2.0 utf8\nIndexedFaceSet { coord Coordinate { point [ 0 0 0 1 ] } }\n",
                         Format::wrl);
      },
      "mem", "point list has 4 numbers, not a multiple of 3", "line 2");
  expect_input_error(
      [] {
        read_from_string("#VRML V2.0 utf8\nIndexedFaceSet {\n coord Coordinate { point [ 0 0 0 ] }\n"
                         " coordIndex [ 0 0 5 ] }\n",
                         Format::wrl);
      },
      "mem", "face 0 refers to vertex 5 but there are 1 vertices", "line 4");
  // An identity Transform is fine.
  Mesh t = read_from_string(
      "#VRML V2.0 utf8\nTransform { translation 0 0 0 rotation 1 0 0 0 scale 1 1 1 center 5 5 5\n"
      " children Shape { geometry IndexedFaceSet { coord Coordinate { point [ 0 0 0 1 0 0 0 1 0 ] }"
      " coordIndex [ 0 1 2 ] } } }\n",
      Format::wrl);
  EXPECT_EQ(t.faces.size(), 1u);
}

// parse_coordinate has a fast path for plain decimal tokens; it must mean
// exactly what parse_number means.
TEST(IoParse, CoordinateFastPathAgreesWithParseNumber) {
  std::vector<std::string> tokens = {
      "0.1", "-0.0", "0.000", "1e-400", "5e-324", "2.4703282292062327e-324", "2.4703282292062328e-324",
      "1e308", "1.7976931348623157e308", "1.7976931348623158e308", "1.7976931348623159e308", "1e309",
      ".5", "5.", "+1.5", "-1e+5", "1E5", "1e", "e5", ".", "-", "+", "1.2.3", "1e5.5", "0e0", "1-2", "+-1",
      "12345678901234567890.5", "1/3", "-22/7", "7", "0x1p-3", "nan", "-inf", "1e-5e", "--1", "1e--5", "1e+-5"};
  std::mt19937_64 rng(7);
  for (int i = 0; i < 3000; ++i) {
    std::uint64_t bits = rng();
    double d;
    std::memcpy(&d, &bits, 8);
    if (!std::isfinite(d)) continue;
    char buf[64];
    for (const char* fmt : {"%.17g", "%.3g", "%.25e", "%.20f"}) {
      std::snprintf(buf, sizeof buf, fmt, d);
      tokens.push_back(buf);
    }
  }
  for (const auto& t : tokens) {
    std::optional<Rational> fast;
    try {
      fast = io_detail::parse_coordinate(t, "x", "");
    } catch (const InputError&) {
    }
    std::optional<Rational> ref = parse_number(t);
    ASSERT_EQ(fast.has_value(), ref.has_value()) << t;
    if (ref) {
      ASSERT_EQ(*fast, *ref) << t;
    }
  }
}

// The OFF reader reads plain vertex and face lines in place and every other
// line through its tokenizer: both must give the same mesh.  Each random
// mesh is written once in plain lines and once in renderings that the fast
// path leaves (in whole or in part) to the tokenizer: a comment after every
// element, every token on a line of its own, CRLF line ends, tabs, extra
// blanks, no final newline.
TEST(IoParse, OffLineFastPathAgreesWithTheTokenizer) {
  const std::vector<std::string> samples = {
      "0", "-0", "7", "-12", "0.5", "-0.0", ".5", "5.", "1e-3", "-2.5E+2", "123456789012345",
      "1234567890123456", "-1234567890123456789", "12345678901234567890.5", "1/3", "-22/7", "0x1p-3",
      "1e-400", "5e-324", "1.7976931348623157e308", "+1.5", "0.30000000000000004", "000012", "-.25"};
  const unsigned seed = 20261123;
  std::mt19937 rng(seed);
  for (int round = 0; round < 60; ++round) {
    const int nv = 3 + int(rng() % 6), nf = 1 + int(rng() % 5);
    std::vector<std::array<std::string, 3>> pts(nv);
    for (auto& p : pts)
      for (auto& t : p) {
        if (rng() % 3 == 0) {
          t = samples[rng() % samples.size()];
        } else {
          std::uint64_t bits = (std::uint64_t(rng()) << 32) | rng();
          double d;
          std::memcpy(&d, &bits, 8);
          if (!std::isfinite(d)) d = 1.25;
          char buf[64];
          std::snprintf(buf, sizeof buf, rng() % 2 ? "%.17g" : "%.6g", d);
          t = buf;
        }
      }
    std::vector<std::vector<std::string>> faces(nf);
    for (auto& f : faces) {
      const int k = 3 + int(rng() % 4);
      f.push_back(std::to_string(k));
      for (int j = 0; j < k; ++j) f.push_back((rng() % 8 == 0 ? "0" : "") + std::to_string(rng() % nv));
    }
    // sep: between numbers; eol: the line end; each: a token on a line of its own.
    auto render = [&](const std::string& sep, const std::string& eol, const std::string& after, bool each,
                      bool final_newline) {
      std::string s = "OFF" + eol + std::to_string(nv) + " " + std::to_string(nf) + " 0" + eol;
      auto line = [&](const std::vector<std::string>& toks) {
        for (std::size_t i = 0; i < toks.size(); ++i) s += (i ? (each ? eol : sep) : "") + toks[i];
        s += after + eol;
      };
      for (const auto& p : pts) line({p[0], p[1], p[2]});
      for (const auto& f : faces) line(f);
      if (!final_newline) s.erase(s.size() - eol.size());
      return s;
    };
    const std::string plain = render(" ", "\n", "", false, true);
    const Mesh ref = read_from_string(render(" ", "\n", " # c", false, true), Format::off);
    SCOPED_TRACE("seed " + std::to_string(seed) + ", round " + std::to_string(round) + ":\n" + plain);
    ASSERT_EQ(ref.points.size(), std::size_t(nv));
    for (int i = 0; i < nv; ++i)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(ref.points[i][k], *parse_number(pts[i][k])) << pts[i][k];
    for (const std::string& variant :
         {plain, render(" ", "\r\n", "", false, true), render("\t", "\n", "", false, true),
          render("  \t ", "\n", " \t", false, true), render(" ", "\n", "", false, false),
          render(" ", "\r\n", "", false, false), render(" ", "\n", "", true, true),
          render(" ", "\n", "#", false, true)})
      expect_same(read_from_string(variant, Format::off), ref);
  }
}

// Files of parallel_items() faces or more (4096 here) have their faces read
// ahead on a second thread while the vertices are read; the reader uses them
// only when the vertices end where the faces were read from.  Every layout
// must give the tokenizer's mesh, and errors keep their lines and messages.
TEST(IoParse, OffFacesReadAheadAgreeWithTheTokenizer) {
  const minksum::testing::ParallelItems threads(4096);
  const unsigned seed = 20261124;
  std::mt19937 rng(seed);
  const int nv = 3000, nf = 9000;
  std::vector<std::string> vlines(nv), flines(nf);
  for (auto& l : vlines)
    l = std::to_string(int(rng() % 2001) - 1000) + " " + std::to_string(double(rng() % 100000) / 64) + " " +
        std::to_string(int(rng() % 7));
  for (auto& l : flines) {
    const int k = 3 + int(rng() % 4);
    l = std::to_string(k);
    for (int j = 0; j < k; ++j) l += " " + std::to_string(rng() % nv);
  }
  auto render = [&](const std::string& eol, const std::string& after, const std::string& between,
                    std::size_t blank_after_vertex, std::size_t coloured_face) {
    std::string s = "OFF" + eol + std::to_string(nv) + " " + std::to_string(nf) + " 0" + eol;
    for (std::size_t i = 0; i < vlines.size(); ++i) {
      s += vlines[i] + after + eol;
      if (i == blank_after_vertex) s += eol;
    }
    s += between;
    for (std::size_t f = 0; f < flines.size(); ++f) s += flines[f] + (f == coloured_face ? " 255 0 0" : "") + after + eol;
    return s;
  };
  constexpr std::size_t kNone = std::size_t(-1);
  SCOPED_TRACE("seed " + std::to_string(seed));
  const Mesh ref = read_from_string(render("\n", " # c", "", kNone, kNone), Format::off);
  ASSERT_EQ(ref.points.size(), std::size_t(nv));
  ASSERT_EQ(ref.faces.size(), std::size_t(nf));
  for (const std::string& variant :
       {render("\n", "", "", kNone, kNone), render("\r\n", "", "", kNone, kNone), render("\n", "\t ", "", kNone, kNone),
        render("\n", "", "# the faces\n", kNone, kNone), render("\n", "", "\n\n", kNone, kNone),
        render("\n", "", "", 1500, kNone), render("\n", "", "", kNone, 4000)}) {
    const Mesh m = read_from_string(variant, Format::off);
    expect_same(m, ref);
  }
  // Errors: in a face far down (line 2 + nv + 8001), in a vertex while the
  // faces are read ahead, and a face section cut short.
  const std::string face8000 = flines[8000];
  flines[8000] = "3 0 1 " + std::to_string(nv);
  const std::string bad_face = render("\n", "", "", kNone, kNone);
  flines[8000] = face8000;
  expect_input_error([&] { read_from_string(bad_face, Format::off); }, "mem",
                     "face 8000 refers to vertex 3000 but there are 3000 vertices",
                     "line " + std::to_string(2 + nv + 8001));
  const std::string vertex2000 = vlines[2000];
  vlines[2000] = "0 0 x";
  const std::string bad_vertex = render("\n", "", "", kNone, kNone);
  vlines[2000] = vertex2000;
  expect_input_error([&] { read_from_string(bad_vertex, Format::off); }, "mem", "expected a number, got 'x'",
                     "line " + std::to_string(2 + 2001));
  const std::string cut = render("\n", "", "", kNone, kNone);
  expect_input_error([&] { read_from_string(cut.substr(0, cut.rfind(flines[nf - 1])), Format::off); }, "mem",
                     "file ends after 8999 of 9000 faces", "line " + std::to_string(2 + nv + nf));
}

// Errors after lines read by the fast path keep their line numbers, and an
// element the fast path refuses gets the tokenizer's message.
TEST(IoBad, OffLineNumbersAfterFastLines) {
  struct Case {
    const char* text;
    const char* problem;
    const char* place;
  };
  const Case cases[] = {
      {"OFF\r\n3 1 0\r\n0 0 0\r\n1 0 0\r\n\r\n0 1 0\r\n3 0 1 3\r\n",
       "face 0 refers to vertex 3 but there are 3 vertices", "line 7"},
      {"OFF\n4 1\n0\t0\t0\n1 0 0\n# a comment\n0 1 0\n0 0 x\n3 0 1 2\n", "expected a number, got 'x'", "line 7"},
      {"OFF\n3 2\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2 x", "unexpected token 'x' after face 1", "line 7"},
      {"OFF\n3 2\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n2 0 1\n", "face 1 has 2 vertices (at least 3 needed)", "line 7"},
      {"OFF\n3 1\n0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n", "coordinate is NaN", "line 5"},
      {"OFF\n3 1\n0 0 0\n1 0 0\n0 1 -inf\n3 0 1 2\n", "coordinate is infinite", "line 5"},
      {"OFF\n3 2\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "file ends after 1 of 2 faces", "line 7"},
      {"OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 0 0\n", "unexpected token '0' after the last face", "line 7"},
      {"OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967295\n",
       "face 0 refers to vertex 4294967295 but there are 3 vertices", "line 6"},
  };
  for (const Case& c : cases)
    expect_input_error([&] { read_from_string(c.text, Format::off); }, "mem", c.problem, c.place);
}

// minksum's loops over one mesh or one text run on threads from
// parallel_items() items on (kParallelItems unless set; at least 1).  In a
// child process (which starts with one thread and no pool), reading,
// validating and writing a 20 480-facet sphere starts no thread by default,
// and starts the pool's threads once the threshold is 4096: the kernel
// threads of the process, counted in /proc/self/task, tell.
TEST(IoParallel, LoopsUseThreadsFromParallelItemsOn) {
  EXPECT_EQ(parallel_items(), kParallelItems);
  {
    const minksum::testing::ParallelItems zero(0);
    EXPECT_EQ(parallel_items(), 1u);
  }
  EXPECT_EQ(parallel_items(), kParallelItems);
  const std::string text = write_to_string(catalog_polytope("sphere:6").to_mesh(), Format::off, {});
  const pid_t child = fork();
  ASSERT_NE(child, -1);
  if (child == 0) {
    auto tasks = [] {
      int n = 0;
      for ([[maybe_unused]] const auto& e : fs::directory_iterator("/proc/self/task")) ++n;
      return n;
    };
    auto round_trip = [&] {
      const Mesh m = read_from_string(text, Format::off);
      const ConvexPolytope p = ConvexPolytope::from_mesh(m, "sphere6.off");
      return m.faces.size() == 20480 && p.num_facets() == 20480 && write_to_string(m, Format::off, {}) == text;
    };
    int code = 0;
    if (tasks() != 1) code |= 1;
    if (!round_trip()) code |= 2;
    if (tasks() != 1) code |= 4;  // below the threshold: the calling thread alone
    set_parallel_items(4096);
    if (!round_trip()) code |= 8;
    if (tasks() < 2) code |= 16;  // the pool started
    _exit(code);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: threads before, 2/8: a round trip failed, 4: a thread started below the "
                                       "threshold, 16: no thread above it";
}

// Lists of parallel_items() points or more (8192 here) are formatted on
// threads in chunks: the lines must come out in order, each the shortest
// round-trip form, in the text formats that print points as lines (OFF,
// OBJ, PLY).
TEST(IoWrite, ManyPointsAreFormattedInOrder) {
  const minksum::testing::ParallelItems threads(8192);
  const unsigned seed = 20261125;
  std::mt19937_64 rng(seed);
  Mesh m;
  const std::size_t n = 3 * 4096 * 3 + 17;  // more than one round of chunks on two threads
  std::vector<Vec3d> want(n);
  for (Vec3d& v : want) {
    auto coord = [&] {
      std::uint64_t bits = rng();
      double d;
      std::memcpy(&d, &bits, 8);
      return std::isfinite(d) ? d : 0.5;
    };
    v = {coord(), coord(), coord()};
    m.points.push_back(v);
  }
  m.faces = {{0, 1, 2}};
  SCOPED_TRACE("seed " + std::to_string(seed));
  for (Format f : {Format::off, Format::obj, Format::ply}) {
    std::ostringstream out;
    write_mesh(out, m, f);
    const Mesh back = read_from_string(out.str(), f);
    ASSERT_EQ(back.points.size(), n);
    for (std::size_t i = 0; i < n; ++i)
      ASSERT_EQ(back.points[i], m.points[i]) << "point " << i;
    if (f == Format::off) {
      std::string lines;
      for (const Vec3d& v : want) {
        char buf[96];
        char* p = std::to_chars(buf, buf + 32, v.x).ptr;
        *p++ = ' ';
        p = std::to_chars(p, p + 32, v.y).ptr;
        *p++ = ' ';
        p = std::to_chars(p, p + 32, v.z).ptr;
        *p++ = '\n';
        lines.append(buf, p);
      }
      EXPECT_NE(out.str().find(lines), std::string::npos);
    }
  }
}

// The chunks of a long file are formatted on threads and written in order
// while the next ones are formatted, at most a window of chunks ahead of the
// writer.  Written from inside jobs of a parallel_for (a batch), where the
// chunks run on the job's own thread, and from several jobs at once, every
// text is the one written on the calling thread alone, line for line
// (threads from 8192 lines here).
TEST(IoWrite, LinesWrittenFromParallelJobsAreTheSame) {
  const minksum::testing::ParallelItems threads(8192);
  Mesh m;
  const std::size_t n = 40 * 1024 + 5;  // 41 chunks: more than the window of two threads
  for (std::size_t i = 0; i < n; ++i) m.points.push_back(Vec3d{double(i) / 7, -double(i) / 3, double(i % 11) + 0.1});
  for (std::size_t f = 0; f + 2 < n; f += 3) m.faces.push_back({Index(f), Index(f + 1), Index(f + 2)});
  std::ostringstream alone;
  write_mesh(alone, m, Format::off);
  std::vector<std::string> texts(4);
  parallel_for(texts.size(), 0, [&](std::size_t j) {
    std::ostringstream out;
    write_mesh(out, m, Format::off);
    texts[j] = out.str();
  });
  for (const std::string& t : texts) EXPECT_EQ(t, alone.str());
  const Mesh back = read_from_string(alone.str(), Format::off);
  ASSERT_EQ(back.points.size(), n);
  EXPECT_EQ(back.points[n - 1], m.points[n - 1]);
  EXPECT_EQ(back.faces, m.faces);
}

// A facet whose line is longer than the writer's buffer (a prism over a
// 3000-gon: two lines of 3001 indices) is written whole, in its place,
// whether the facet lines are formatted on one thread or in chunks
// (threads from 8192 lines here).
TEST(IoWrite, FacetLinesLongerThanTheBufferAreWrittenWhole) {
  const minksum::testing::ParallelItems threads(8192);
  const ConvexPolytope prism = catalog_polytope("prism:3000");
  ASSERT_EQ(prism.num_facets(), 3002u);
  for (Format f : {Format::off, Format::ply}) {
    std::ostringstream out;
    write_polytope(out, prism, f);
    const Mesh back = read_from_string(out.str(), f);
    ASSERT_EQ(back.faces.size(), 3002u);
    std::size_t big = 0;
    for (const auto& face : back.faces) big += face.size() == 3000;
    EXPECT_EQ(big, 2u);
    EXPECT_EQ(ConvexPolytope::from_mesh(back, "back").num_facets(), 3002u);
  }
  Mesh many;  // more than two chunks of face lines, one of them long
  for (int i = 0; i < 3000; ++i) many.points.push_back(Vec3d{double(i), 0, 0});
  for (int f = 0; f < 9000; ++f) many.faces.push_back({Index(f % 3000), Index((f + 1) % 3000), Index((f + 2) % 3000)});
  many.faces[5000].clear();
  for (Index v = 0; v < 3000; ++v) many.faces[5000].push_back(v);
  std::ostringstream out;
  write_mesh(out, many, Format::off);
  const Mesh back = read_from_string(out.str(), Format::off);
  EXPECT_EQ(back.faces, many.faces);
}

TEST(IoWrite, RationalToFloatIsCorrectlyRounded) {
  // Ties and near-ties that a double rounding (rational -> double -> float) gets wrong.
  const Rational one(1);
  const Rational tie = one + pow2(-24);                   // halfway between 1 and 1 + 2^-23
  EXPECT_EQ(io_detail::checked_float(tie), 1.0f);     // ties to even
  EXPECT_EQ(io_detail::checked_float(tie + pow2(-80)), 1.0f + 0x1p-23f);  // just above: up
  EXPECT_EQ(io_detail::checked_float(q("1/3")), 1.0f / 3.0f);
  EXPECT_EQ(io_detail::checked_float(-pow2(-149)), -0x1p-149f);  // smallest subnormal
  EXPECT_EQ(io_detail::checked_float(pow2(-151)), 0.0f);         // below half of it
  EXPECT_THROW(io_detail::checked_float(pow2(128)), UsageError);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 2000; ++i) {
    double d = std::ldexp(double(rng() >> 11), int(rng() % 200) - 220);
    EXPECT_EQ(io_detail::checked_float(Rational(d)), static_cast<float>(d)) << d;
  }
}

TEST(IoParse, StreamAndFileAgree) {
  const std::string path = data_path("io/extra_props.ply");
  std::ifstream in(path, std::ios::binary);
  expect_same(read_mesh(in, Format::ply, path), read_mesh(path));
}

// --- malformed input --------------------------------------------------------------

TEST(IoBad, EveryBadFileGivesAnInputError) {
  expect_bad_file("bad/empty.off", "file is empty", "");
  expect_bad_file("bad/wrong_magic.off", "expected 'OFF' magic, got 'OFX'", "line 1");
  expect_bad_file("bad/nan.off", "coordinate is NaN", "line 4");
  expect_bad_file("bad/inf.obj", "coordinate is infinite", "line 2");
  expect_bad_file("bad/absurd_count.off", "header announces 4000000000 vertices but only 0 bytes follow the header",
                  "line 2");
  expect_bad_file("bad/absurd_count_binary.ply", "header announces 4000000000 vertices but only 12 bytes follow",
                  "line 3");
  expect_bad_file("bad/lying_count.off", "file ends after 5 of 8 vertices", "line 8");
  expect_bad_file("bad/out_of_range_index.obj", "face 1 refers to vertex 9 but there are 3 vertices", "line 4");
  expect_bad_file("bad/zero_index.obj", "face 1 has vertex index 0", "line 4");
  expect_bad_file("bad/truncated_binary.stl", "file ends after 1 of 2 triangles", "byte 134");
  expect_bad_file("bad/truncated.ply", "file ends after 0 of 1 face", "face 0");
  expect_bad_file("bad/nan_binary.ply", "coordinate is NaN", "vertex 1");
  expect_bad_file("bad/garbage_token.off", "expected a number, got 'foo'", "line 4");
  expect_bad_file("bad/zero_denominator.off", "coordinate '1/0' has a zero denominator", "line 4");
  expect_bad_file("bad/short_face.off", "face 0 has 2 vertices (at least 3 needed)", "line 6");
  expect_bad_file("bad/trailing_garbage.off", "unexpected token 'junk' after the last face", "line 7");
  expect_bad_file("bad/two_shapes.wrl", "more than one IndexedFaceSet", "line 3");
  expect_bad_file("bad/translated.wrl", "non-identity 'translation'", "line 7");
}

TEST(IoBad, MessageIsFilePlaceProblem) {
  try {
    read_mesh(data_path("bad/nan.off"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), data_path("bad/nan.off") + ": line 4: coordinate is NaN");
    EXPECT_EQ(e.file(), data_path("bad/nan.off"));
  }
}

TEST(IoBad, EmptyInputInEveryFormat) {
  for (Format f : {Format::off, Format::obj, Format::ply, Format::stl, Format::wrl}) {
    std::istringstream in("");
    expect_input_error([&] { read_mesh(in, f, "empty-stream"); }, "empty-stream", "file is empty", "");
  }
}

TEST(IoBad, AbsurdCountsFailFastInEveryCountedFormat) {
  auto t0 = std::chrono::steady_clock::now();
  // Binary STL announcing 4e9 triangles in a 100-byte file.
  std::string stl(84, '\0');
  const std::uint32_t n = 4000000000u;
  std::memcpy(&stl[80], &n, 4);
  stl += std::string(16, '\0');
  expect_input_error([&] { read_from_string(stl, Format::stl, "big.stl"); }, "big.stl",
                     "header announces 4000000000 triangles but the file has only 100 bytes", "byte 80");
  // Ascii PLY, faces.
  expect_input_error(
      [] {
        read_from_string("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\n"
                         "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                         Format::ply, "faces.ply");
      },
      "faces.ply", "header announces 4000000000 faces", "line 7");
  // OFF, faces only.
  expect_input_error([] { read_from_string("OFF 3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n", Format::off, "f.off"); },
                     "f.off", "header announces 3 vertices and 4000000000 faces", "line 1");
  // A face announcing 4e9 vertices.
  expect_input_error([] { read_from_string("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", Format::off); },
                     "mem", "face 0 announces 4000000000 vertices", "line 5");
  // Binary PLY list length 4e9.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\n"
      "property uchar z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n";
  ply += std::string(3, '\0');
  ply += std::string("\x00\x28\x6b\xee", 4);  // 4e9 little-endian
  ply += std::string(8, '\0');
  expect_input_error([&] { read_from_string(ply, Format::ply); }, "mem", "file ends after 0 of 1 face", "face 0");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 2.0);
}

TEST(IoBad, MoreReaderChecks) {
  auto off = [](const std::string& s) { return read_from_string(s, Format::off); };
  expect_input_error([&] { off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"); }, "mem",
                     "face 0 refers to vertex 3 but there are 3 vertices", "line 6");
  expect_input_error([&] { off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"); }, "mem",
                     "face 0 has negative vertex index -1", "line 6");
  expect_input_error([&] { off("OFF\n-3 1 0\n"); }, "mem", "negative vertex count", "line 2");
  expect_input_error([&] { off("OFF BINARY\n"); }, "mem", "binary OFF is not supported", "line 1");
  expect_input_error([&] { off("4OFF\n"); }, "mem", "only 3-dimensional OFF", "line 1");
  expect_input_error([&] { off("# only a comment\n"); }, "mem", "expected 'OFF' magic");
  expect_input_error([&] { off("OFF\n1 0 0\n1e999 0 0\n"); }, "mem", "out of double range", "line 3");
  expect_input_error([&] { off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 2 3 4 5\n"); }, "mem",
                     "unexpected token '5' after face 0", "line 6");
  // PLY header problems.
  auto ply = [](const std::string& s) { return read_from_string(s, Format::ply); };
  expect_input_error([&] { ply("plx\n"); }, "mem", "expected 'ply' magic", "line 1");
  expect_input_error([&] { ply("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"); }, "mem",
                     "no 'end_header'", "header");
  expect_input_error([&] { ply("ply\nformat ascii 1.0\nelement vertex 0\nproperty quad x\nend_header\n"); }, "mem",
                     "unknown property type 'quad'", "line 4");
  expect_input_error(
      [&] { ply("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nend_header\n"); },
      "mem", "vertex element has no 'z' property", "line 3");
  expect_input_error(
      [&] {
        ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
            "end_header\n0 0 0 7\n");
      },
      "mem", "unexpected token '7' after the last element", "line 8");
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\n"
      "property uchar z\nend_header\n";
  expect_input_error([&] { ply(header + "\x01\x02\x03\x04"); }, "mem",
                     "1 bytes of unexpected data after the last element", "byte " + std::to_string(header.size() + 3));
  // STL.
  auto stl = [](const std::string& s) { return read_from_string(s, Format::stl); };
  expect_input_error([&] { stl("not an stl"); }, "mem", "not an STL file");
  expect_input_error([&] { stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"); }, "mem",
                     "file ends where 'vertex' or 'endloop' was expected", "line 6");
  expect_input_error(
      [&] { stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 nan\nvertex 0 1 0\n"); }, "mem",
      "coordinate is NaN", "line 5");
  expect_input_error([&] { stl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\nendfacet\n"); },
                     "mem", "facet has 1 vertices (at least 3 needed)", "line 3");
  expect_input_error([&] { stl("solid x\nendsolid x\ngarbage\n"); }, "mem", "unexpected token 'garbage'", "line 3");
}

// --- atomic writes -----------------------------------------------------------------

TEST(IoAtomic, NonexistentDirectoryThrowsAndLeavesNothing) {
  TempDir dir;
  const std::string path = dir.path("no/such/dir/out.off");
  expect_input_error([&] { write_mesh(path, cube_mesh()); }, path, "cannot create a temporary file");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomic, FailedWriteKeepsOldContentAndNoTemporary) {
  TempDir dir;
  const std::string stl = dir.path("old.stl");
  write_mesh(stl, cube_mesh());
  const std::string before = slurp(stl);
  ASSERT_FALSE(before.empty());
  // Refused request: nothing touched.
  EXPECT_THROW(write_mesh(stl, cube_mesh(), {.exact = true}), UsageError);
  EXPECT_EQ(slurp(stl), before);
  // A failure in the middle of writing: the temporary is removed, the old file kept.
  Mesh huge = cube_mesh();
  huge.points.set(7, Point3(pow2(5000), Rational(1), Rational(1)));  // fails after some output
  EXPECT_THROW(write_mesh(stl, huge), UsageError);
  EXPECT_EQ(slurp(stl), before);
  EXPECT_THROW(write_file_atomically(stl,
                                     [](std::ostream& out) {
                                       out << std::string(100000, 'x');
                                       throw std::runtime_error("simulated failure");
                                     }),
               std::runtime_error);
  EXPECT_EQ(slurp(stl), before);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"old.stl"});
  // And a successful write replaces the content.
  write_mesh(stl, cube_mesh(), {.binary = true});
  EXPECT_NE(slurp(stl), before);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"old.stl"});
}

TEST(IoAtomic, UnknownExtensionIsAUsageError) {
  TempDir dir;
  EXPECT_THROW(write_mesh(dir.path("x.txt"), cube_mesh()), UsageError);
  EXPECT_THROW(read_mesh(dir.path("x.txt")), UsageError);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(IoAtomic, ReplacingADirectoryFails) {
  TempDir dir;
  fs::create_directories(dir.path("d.off"));
  expect_input_error([&] { write_mesh(dir.path("d.off"), cube_mesh()); }, "d.off", "cannot replace");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"d.off"});
}

// --- reading files and resolving operands ------------------------------------------

TEST(IoFiles, MissingDirectoryAndUnknownNames) {
  TempDir dir;
  expect_input_error([&] { read_mesh(dir.path("missing.off")); }, "missing.off", "no such file", "");
  fs::create_directories(dir.path("adir.off"));
  expect_input_error([&] { read_mesh(dir.path("adir.off")); }, "adir.off", "is a directory");
  expect_input_error([&] { load_polytope(dir.path("missing.ply")); }, "missing.ply", "no such file", "");
  expect_input_error([&] { load_polytope(dir.path("adir.off")); }, "adir.off", "is a directory");
  try {
    load_polytope("definitely-not-a-catalog-name");
    ADD_FAILURE() << "no UsageError";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "'definitely-not-a-catalog-name' is neither a file nor a catalog name; see 'minksum gen --help'");
  }
}

TEST(IoFiles, LoadPolytopeReadsAndValidates) {
  ConvexPolytope cube = load_polytope(data_path("bad/triangulated_cube.stl"));
  EXPECT_EQ(cube.num_vertices(), 8u);
  EXPECT_EQ(cube.num_edges(), 12u);
  EXPECT_EQ(cube.num_facets(), 6u);
  ConvexPolytope tetra = load_polytope(data_path("io/exact_tetra.wrl"));
  EXPECT_EQ(tetra.num_vertices(), 4u);
  EXPECT_EQ(tetra.num_facets(), 4u);
  // As a point cloud: the faces are ignored.
  ConvexPolytope hull = load_polytope(data_path("bad/two_cubes.off"), true);
  EXPECT_EQ(hull.num_vertices(), 8u);
  EXPECT_EQ(hull.num_facets(), 6u);
  EXPECT_EQ(hull.volume(), Rational(4));
  // Not a polytope: an InputError naming the file.
  expect_input_error([] { load_polytope(data_path("bad/open_mesh.off")); }, "open_mesh.off", "");
}

TEST(IoFiles, LoadPolytopeFromCatalog) {
  ConvexPolytope cube = load_polytope("cube");
  EXPECT_EQ(cube.num_facets(), 6u);
  ConvexPolytope hull = load_polytope("cube", true);
  EXPECT_EQ(hull.num_facets(), 6u);
  EXPECT_EQ(hull.volume(), cube.volume());
}

// --- output that reads back (writable_polytope, write_polytope) ---------------

namespace {

// Every way a polytope can be written: format, binary, exact.
struct WriteMode {
  Format format;
  WriteOptions options;
};
std::vector<WriteMode> every_write_mode() {
  std::vector<WriteMode> modes;
  for (const FormatInfo& f : formats()) {
    modes.push_back({f.format, {}});
    if (f.binary) modes.push_back({f.format, {.binary = true}});
    if (f.exact) modes.push_back({f.format, {.exact = true}});
  }
  return modes;
}
std::string mode_name(const WriteMode& m) {
  return std::string(format_name(m.format)) + (m.options.binary ? " binary" : "") + (m.options.exact ? " exact" : "");
}

// The sorted vertex set of a polytope, exactly.
std::vector<Point3> vertex_set(const ConvexPolytope& p) {
  std::vector<Point3> v = p.points();
  std::sort(v.begin(), v.end());
  return v;
}

// Is every coordinate of p exactly a number of the format (doubles; binary
// STL: floats)?
bool representable(const ConvexPolytope& p, const WriteMode& m) {
  const bool floats = m.format == Format::stl && m.options.binary;
  for (const Point3& v : p.points())
    for (int k = 0; k < 3; ++k) {
      if (!is_double(v[k])) return false;
      if (floats && Rational(double(static_cast<float>(to_double(v[k])))) != v[k]) return false;
    }
  return true;
}

// Write p in the mode, read it back with minksum's reader and validate it:
// a valid convex polytope, equal to writable_polytope's result; exactly p
// when exact or when nothing had to be rounded; else every vertex within the
// reported displacement of p's rounded points.
void expect_reads_back(const ConvexPolytope& p, const WriteMode& m, const std::string& what) {
  SCOPED_TRACE(what + " as " + mode_name(m));
  std::ostringstream out;
  RoundingReport report;
  try {
    write_polytope(out, p, m.format, m.options, &report);
  } catch (const UnrepresentableError& e) {
    ADD_FAILURE() << "refused: " << e.what();
    return;
  }
  ConvexPolytope back;
  try {
    back = ConvexPolytope::from_mesh(read_from_string(out.str(), m.format, "written"), "written");
  } catch (const InputError& e) {
    ADD_FAILURE() << "does not read back: " << e.what();
    return;
  }
  EXPECT_EQ(back.check_invariants(), "");
  const ConvexPolytope expected = writable_polytope(p, m.format, m.options);
  EXPECT_EQ(vertex_set(back), vertex_set(expected));
  EXPECT_EQ(back.num_facets(), expected.num_facets());
  EXPECT_TRUE(representable(back, m) || (m.options.exact && format_info(m.format).exact));
  if (!report.rounded()) {
    EXPECT_EQ(vertex_set(back), vertex_set(p));
    EXPECT_EQ(back.volume(), p.volume());
    EXPECT_EQ(back.num_facets(), p.num_facets());
  } else {
    EXPECT_FALSE(m.options.exact) << "exact output is never rounded";
    EXPECT_GT(report.max_displacement, 0);
    EXPECT_EQ(back.num_vertices() + report.merged + report.dropped, p.num_vertices());
    // Close to the exact solid: the volume within the displacement times
    // the surface (bounded by 4π R² for R the largest coordinate, here ~ 10).
    const double dv = std::abs(to_double(back.volume() - p.volume()));
    EXPECT_LE(dv, report.max_displacement * 4 * 3.15 * 400 * 1.01) << dv;
  }
}

// One polytope of every family of the catalog (src/catalog), plain (mostly
// doubles) and transformed (exact rationals), and a sum (exact double pairs).
std::vector<std::string> every_catalog_family() {
  std::vector<std::string> specs;
  for (const CatalogEntry& e : catalog_entries()) {
    const std::string name = e.syntax.substr(0, e.syntax.find(' '));
    if (name.find(':') != std::string::npos || name[0] == '@') continue;
    specs.push_back(name);
    specs.push_back(name + "@rot:7");
  }
  for (const char* s : {"sphere:1", "sphere:3", "sphere:3@rot:5", "dioctagonal:17", "dioctagonal:17@rot:3",
                        "random:200:1", "random:200:1@rot:2", "zonotope:8:3", "zonotope:8:3@rot:1",
                        "zonotope:1,0,0:0,1,0:0,0,1:1,1,1", "box:1:2:3", "box:1/3:1/7:2@rot:9",
                        "cube@scale:1/3", "cube@translate:1/3,1/5,1/7", "tetra@rot:4@neg"})
    specs.push_back(s);
  return specs;
}

}  // namespace

TEST(IoRounding, EveryWriterEveryCatalogFamilyReadsBack) {
  const std::vector<WriteMode> modes = every_write_mode();
  ASSERT_EQ(modes.size(), 10u);  // OFF, OBJ, VRML: rounded and exact; PLY, STL: ascii and binary
  for (const std::string& spec : every_catalog_family()) {
    const ConvexPolytope p = catalog_polytope(spec);
    for (const WriteMode& m : modes) expect_reads_back(p, m, spec);
  }
}

// The case that made minksum unable to read its own output: a sum with
// coordinates that are not doubles, whose facets rounded to doubles are no
// longer planar (OFF) or whose edges turn reflex (STL).
TEST(IoRounding, RoundedSphereSumReadsBack) {
  const ConvexPolytope s = minkowski_sum(catalog_polytope("sphere:4"), catalog_polytope("sphere:4@rot:5")).polytope;
  RoundingReport r;
  const ConvexPolytope w = writable_polytope(s, Format::off, {}, &r);
  EXPECT_TRUE(r.rounded());
  EXPECT_GT(r.split, 0u);  // quadrilaterals no longer planar, split along their convex diagonal
  EXPECT_FALSE(r.hull);
  EXPECT_GT(r.max_displacement, 0);
  EXPECT_LT(r.max_displacement, 1e-15);  // half an ulp of coordinates below 2
  for (const WriteMode& m : every_write_mode()) expect_reads_back(s, m, "sphere:4 + sphere:4@rot:5");
  // A sum of double polytopes: exact double pairs.
  expect_reads_back(minkowski_sum(catalog_polytope("random:300:4"), catalog_polytope("sphere:3")).polytope,
                    {Format::off, {}}, "random:300:4 + sphere:3");
}

// The report of a sum of double polytopes (exact double pairs, whose
// rounding skips the per-coordinate path of rationals): the coordinates
// that are not doubles and the largest displacement, as computed from the
// exact points in rationals.
TEST(IoRounding, DoublePairReportIsTheExactDifference) {
  for (const auto& [a, b] : {std::pair{"random:300:4", "sphere:3"}, std::pair{"cube", "sphere:4@rot:5"}}) {
    SCOPED_TRACE(std::string(a) + " + " + b);
    // The operands as a file of doubles gives them.
    auto doubles = [](const char* spec) { return writable_polytope(catalog_polytope(spec), Format::off, {}, nullptr); };
    const ConvexPolytope s = minkowski_sum(doubles(a), doubles(b)).polytope;
    ASSERT_EQ(s.coordinates().form(), PointList::Form::double_pairs);
    std::size_t coordinates = 0;
    double largest = 0;
    for (Index i = 0; i < s.num_vertices(); ++i) {
      const Point3 x = s.point(i);
      const Vec3d d = s.approx(i);
      const double e[3] = {to_double(x.x - Rational(d.x)), to_double(x.y - Rational(d.y)), to_double(x.z - Rational(d.z))};
      for (double c : e) coordinates += c != 0;
      largest = std::max(largest, std::hypot(e[0], e[1], e[2]));
    }
    ASSERT_GT(coordinates, 0u);
    RoundingReport r;
    const ConvexPolytope w = writable_polytope(s, Format::off, {}, &r);
    EXPECT_EQ(r.coordinates, coordinates);
    EXPECT_EQ(r.max_displacement, largest);
    for (Index i = 0; i < w.num_vertices(); ++i) EXPECT_TRUE(w.coordinates().is_double(i));
  }
}

// When splitting the facets is not enough, the hull of the rounded points:
// a prism over a pentagon whose vertex P3 lies 2^-80 outside the line of its
// neighbours, at a height (1 + 2^-54) that is not a double; rounded, P3
// falls inside the quadrilateral of the others, so both its copies are
// dropped: a prism over that quadrilateral, 8 vertices and 6 facets.
TEST(IoRounding, VertexRoundedInsideItsFacetIsDropped) {
  const Rational y3 = Rational(1) + pow2(-54) + pow2(-80);
  Mesh m;
  for (int z = 0; z < 2; ++z) {
    m.points.emplace_back(Rational(0), Rational(0), Rational(z));
    m.points.emplace_back(Rational(2), Rational(0), Rational(z));
    m.points.emplace_back(Rational(2), Rational(1) + pow2(-52), Rational(z));
    m.points.emplace_back(q("1/2"), y3, Rational(z));
    m.points.emplace_back(Rational(0), Rational(1), Rational(z));
  }
  m.faces = {{4, 3, 2, 1, 0}, {5, 6, 7, 8, 9}, {0, 1, 6, 5}, {1, 2, 7, 6}, {2, 3, 8, 7}, {3, 4, 9, 8}, {4, 0, 5, 9}};
  const ConvexPolytope prism = ConvexPolytope::from_mesh(m);
  ASSERT_EQ(prism.num_vertices(), 10u);
  RoundingReport r;
  const ConvexPolytope w = writable_polytope(prism, Format::off, {}, &r);
  EXPECT_EQ(r.coordinates, 2u);
  EXPECT_TRUE(r.hull);
  EXPECT_EQ(r.merged, 0u);
  EXPECT_EQ(r.dropped, 2u);
  EXPECT_EQ(w.num_vertices(), 8u);
  EXPECT_EQ(w.num_facets(), 6u);
  EXPECT_EQ(w.volume(), Rational(2) + pow2(-52));  // the quadrilateral's area times 1
  EXPECT_DOUBLE_EQ(r.max_displacement, to_double(y3 - 1));
  for (const WriteMode& mode : every_write_mode()) expect_reads_back(prism, mode, "prism");
}

// Nothing to round: the same polytope, no report.
TEST(IoRounding, RepresentablePolytopesAreWrittenAsTheyAre) {
  RoundingReport r;
  const ConvexPolytope cube = catalog_polytope("cube");
  EXPECT_EQ(vertex_set(writable_polytope(cube, Format::stl, {.binary = true}, &r)), vertex_set(cube));
  EXPECT_FALSE(r.rounded());
  const ConvexPolytope rot = catalog_polytope("cube@rot:1,2,3,4");
  EXPECT_EQ(vertex_set(writable_polytope(rot, Format::off, {.exact = true}, &r)), vertex_set(rot));
  EXPECT_FALSE(r.rounded());
  writable_polytope(rot, Format::off, {}, &r);
  std::size_t not_doubles = 0;
  for (const Point3& v : rot.points())
    for (int k = 0; k < 3; ++k) not_doubles += !is_double(v[k]);
  EXPECT_GT(not_doubles, 0u);
  EXPECT_EQ(r.coordinates, not_doubles);
}

// Underflow: a cube at ±1e-310 (subnormal doubles) becomes a point in the
// floats of binary STL; a cube at ±1/7^1000 becomes a point in any double
// format.  Refused, never written as a degenerate file.
TEST(IoRounding, SubnormalCubeToBinaryStlIsRefused) {
  const ConvexPolytope tiny = catalog_polytope("cube@scale:1e-310");
  ASSERT_TRUE(tiny.coordinates_are_doubles());
  try {
    writable_polytope(tiny, Format::stl, {.binary = true});
    ADD_FAILURE() << "no UnrepresentableError";
  } catch (const UnrepresentableError& e) {
    EXPECT_TRUE(e.floats_only());
    EXPECT_NE(e.problem().find("32-bit floats"), std::string::npos) << e.problem();
    EXPECT_NE(e.problem().find("no longer make a solid: all 8 points coincide"), std::string::npos) << e.problem();
  }
  for (const WriteMode& m : every_write_mode())
    if (!(m.format == Format::stl && m.options.binary)) expect_reads_back(tiny, m, "cube at 1e-310");
}

TEST(IoRounding, TinyRationalCubeIsRefusedWithoutExact) {
  Rational s(1);
  for (int i = 0; i < 1000; ++i) s /= 7;
  Mesh m = catalog_polytope("cube").to_mesh();
  m.points.transform([&](Point3 p) { return Point3(p.x * s, p.y * s, p.z * s); });
  const ConvexPolytope t = ConvexPolytope::from_mesh(m);
  for (const WriteMode& mode : every_write_mode()) {
    SCOPED_TRACE(mode_name(mode));
    if (mode.options.exact) {
      expect_reads_back(t, mode, "cube at 1/7^1000");
      continue;
    }
    try {
      writable_polytope(t, mode.format, mode.options);
      ADD_FAILURE() << "no UnrepresentableError";
    } catch (const UnrepresentableError& e) {
      EXPECT_FALSE(e.floats_only());
      EXPECT_NE(std::string(e.what()).find("exact rationals"), std::string::npos) << e.what();
    }
  }
}

// Overflow: refused with the fix; the file keeps its previous content.
TEST(IoRounding, CoordinateBeyondTheRangeIsRefusedBeforeWriting) {
  Mesh m = cube_mesh();
  m.points.transform([](Point3 p) { return Point3(p.x * pow2(1100), p.y, p.z); });
  const ConvexPolytope big = ConvexPolytope::from_mesh(m);
  TempDir dir;
  for (const char* name : {"b.off", "b.ply", "b.stl"}) {
    const std::string path = dir.path(name);
    EXPECT_THROW(write_polytope(path, big), UnrepresentableError) << name;
    EXPECT_FALSE(fs::exists(path)) << name;
  }
  write_polytope(dir.path("b.off"), big, {.exact = true});
  EXPECT_EQ(vertex_set(load_polytope(dir.path("b.off"))), vertex_set(big));
  // Beyond the floats only: ascii STL would do.
  Mesh f = cube_mesh();
  f.points.transform([](Point3 p) { return Point3(p.x * pow2(200), p.y, p.z); });
  try {
    writable_polytope(ConvexPolytope::from_mesh(f), Format::stl, {.binary = true});
    ADD_FAILURE() << "no UnrepresentableError";
  } catch (const UnrepresentableError& e) {
    EXPECT_TRUE(e.floats_only());
    EXPECT_NE(std::string(e.what()).find("ascii STL"), std::string::npos) << e.what();
  }
}

// Reading with a format the name does not tell, and from a stream.
TEST(IoFiles, FormatGivenForANameWithoutExtension) {
  TempDir dir;
  const std::string path = dir.path("mesh.dat");
  write_mesh(dir.path("m.off"), cube_mesh());
  fs::rename(dir.path("m.off"), path);
  EXPECT_THROW(load_polytope(path), UsageError);
  EXPECT_EQ(load_polytope(path, false, nullptr, Format::off).num_facets(), 6u);
  // A known extension keeps its own format.
  write_mesh(dir.path("c.stl"), cube_mesh());
  EXPECT_EQ(load_polytope(dir.path("c.stl"), false, nullptr, Format::off).num_facets(), 6u);
  std::istringstream in(write_to_string(cube_mesh(), Format::ply, {.binary = true}));
  EXPECT_EQ(load_polytope(in, Format::ply, "<stdin>").num_vertices(), 8u);
  std::istringstream bad("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_input_error([&] { load_polytope(bad, Format::off, "<stdin>"); }, "<stdin>", "");
}

// Validation decides the folds between two triangles of double coordinates
// with one orient3d sign (no exact facet normals).  Rounded sums of rotated
// solids have thousands of nearly flat folds, convex and reflex: each mesh
// must get exactly the verdict of the same mesh scaled by 1/3, whose rational
// coordinates take the exact-normal path (a positive scaling keeps every sign).
TEST(IoRounding, TriangleFoldsOfDoublesDecidedLikeRationals) {
  auto verdict = [](const Mesh& m) -> std::string {
    try {
      const ConvexPolytope p = ConvexPolytope::from_mesh(m, "m");
      return std::to_string(p.num_vertices()) + " " + std::to_string(p.num_edges()) + " " +
             std::to_string(p.num_facets());
    } catch (const InputError& e) {
      return minksum::testing::without_coordinates(e.what());  // the place's coordinates scale
    }
  };
  auto scaled_by_a_third = [](const Mesh& m) {
    Mesh t;
    for (std::size_t i = 0; i < m.points.size(); ++i) {
      const Point3 q = m.points.exact(i);
      t.points.push_back(Point3(q.x / 3, q.y / 3, q.z / 3));
    }
    t.faces = m.faces;
    return t;
  };
  int accepted = 0, refused = 0;
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"sphere:3", "sphere:3@rot:5"}, {"dodecahedron", "truncated-cube@rot:2"}, {"cube", "cube"}}) {
    const ConvexPolytope s = minkowski_sum(catalog_polytope(a), catalog_polytope(b)).polytope;
    const ConvexPolytope w = writable_polytope(s, Format::off, {}, nullptr);  // a valid rounded mesh
    for (int start = 0; start < 3; ++start) {  // every facet fanned from its vertex `start` (mod its size)
      Mesh m;
      for (Index v = 0; v < s.num_vertices(); ++v) {
        const Point3& q = s.point(v);
        m.points.push_back(Vec3d{to_double(q.x), to_double(q.y), to_double(q.z)});
      }
      for (Index f = 0; f < s.num_facets(); ++f) {
        const auto loop = s.facet_vertices(f);
        const std::size_t k = loop.size(), o = std::size_t(start) % k;
        for (std::size_t i = 1; i + 1 < k; ++i)
          m.faces.push_back({loop[o], loop[(o + i) % k], loop[(o + i + 1) % k]});
      }
      const std::string v = verdict(m);
      EXPECT_EQ(v, verdict(scaled_by_a_third(m))) << a << " + " << b << ", fans from vertex " << start;
      (v.find("reflex") != std::string::npos ? refused : accepted)++;
    }
    const Mesh m = w.to_mesh();  // its facets: triangles, and polygons that are exactly planar
    EXPECT_EQ(verdict(m), verdict(scaled_by_a_third(m))) << a << " + " << b << ", written";
    EXPECT_EQ(verdict(m), std::to_string(w.num_vertices()) + " " + std::to_string(w.num_edges()) + " " +
                              std::to_string(w.num_facets()));
  }
  EXPECT_GT(accepted, 0);  // cube + cube: exact doubles, coplanar triangles merged into 6 squares
  EXPECT_GT(refused, 0);   // a non-planar rounded quad fanned across its reflex diagonal
}

// ---------------------------------------------------------------------------
// VRML scenes: ExactPolyhedron and CubicalGaussianMap nodes (<minksum/scene.hpp>, docs/vrml.md).

namespace {

const char* kTwoShapeScene =
    "#VRML V2.0 utf8\n"
    "Shape { geometry DEF T ExactPolyhedron {\n"
    "  coord ExactCoordinate { ratPoint [ 0 0 0, 1/3 0 0, 0 1/3 0, 0 0 1/3 ] }\n"
    "  coordIndex [ 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1 ]\n"
    "} }\n"
    "Transform { children Shape { geometry DEF G CubicalGaussianMap {\n"
    "  polytope USE T\n"
    "  mapCounts [ 7 18 4  7 18 4  7 18 4  4 8 2  4 8 2  4 8 2 ]\n"
    "} } }\n";

// The scene of a polytope and of the sum with its CGM nodes, as 'cgm P Q -o' writes it.
Scene sum_scene(const ConvexPolytope& p, const ConvexPolytope& q, const ConvexPolytope& s) {
  Scene scene;
  for (const auto& [poly, name] : {std::pair{&p, "P"}, std::pair{&q, "Q"}, std::pair{&s, "S"}})
    scene.polytopes.push_back({name, poly->to_mesh(), 0, true});
  const CubicalGaussianMap g = CubicalGaussianMap::from_polytope(s);
  SceneCgm c;
  c.name = "CGM_S";
  c.polytope = 2;
  c.operands = {0, 1};
  std::array<Index, 18> counts{};
  std::vector<SceneMapPoint> points;
  for (int k = 0; k < 6; ++k) {
    counts[std::size_t(3 * k)] = g.counts(k).vertices;
    counts[std::size_t(3 * k + 1)] = g.counts(k).halfedges;
    counts[std::size_t(3 * k + 2)] = g.counts(k).faces;
    for (const auto& v : g.map(k).vertices)
      if (v.real) points.push_back({k, v.x, v.y});
  }
  c.map_counts = counts;
  c.map_points = points;
  scene.cgms.push_back(c);
  return scene;
}

std::string scene_text(const Scene& s, bool exact) {
  std::ostringstream out;
  write_scene(out, s, exact);
  return out.str();
}

}  // namespace

TEST(VrmlScene, ReadsExactPolyhedronAndCubicalGaussianMapNodes) {
  const Scene s = read_scene(std::string_view(kTwoShapeScene), "mem");
  ASSERT_EQ(s.shapes.size(), 2u);
  EXPECT_EQ(s.shapes[0].kind, SceneShape::Kind::polytope);
  EXPECT_EQ(s.shapes[1].kind, SceneShape::Kind::cgm);
  ASSERT_EQ(s.polytopes.size(), 1u);
  EXPECT_EQ(s.polytopes[0].name, "T");
  EXPECT_EQ(s.polytopes[0].line, 2u);
  EXPECT_TRUE(s.polytopes[0].exact_node);
  ASSERT_EQ(s.polytopes[0].mesh.points.size(), 4u);
  EXPECT_TRUE(s.polytopes[0].mesh.points[1] == Point3(Rational(1, 3), 0, 0));
  EXPECT_EQ(s.polytopes[0].mesh.faces.size(), 4u);
  ASSERT_EQ(s.cgms.size(), 1u);
  EXPECT_EQ(s.cgms[0].name, "G");
  EXPECT_EQ(s.cgms[0].polytope, 0u);
  EXPECT_TRUE(s.cgms[0].operands.empty());
  ASSERT_TRUE(s.cgms[0].map_counts.has_value());
  EXPECT_EQ((*s.cgms[0].map_counts)[4], 18u);
  EXPECT_EQ(s.cgms[0].map_counts_line, 8u);
  EXPECT_FALSE(s.cgms[0].map_points.has_value());
  // read_mesh: the scene's one polytope (the map refers to it).
  const Mesh m = read_from_string(kTwoShapeScene, Format::wrl);
  expect_same(m, s.polytopes[0].mesh);
  EXPECT_EQ(ConvexPolytope::from_mesh(m).volume(), Rational(1, 162));
}

TEST(VrmlScene, SumSceneRoundTripsExactly) {
  const ConvexPolytope p = catalog_polytope("truncated-cube@rot:2"), q = catalog_polytope("octahedron@rot:1,2,3,7");
  const ConvexPolytope s = minkowski_sum(p, q).polytope;
  const Scene scene = sum_scene(p, q, s);
  const std::string text = scene_text(scene, true);
  EXPECT_NE(text.find("geometry DEF S ExactPolyhedron"), std::string::npos);
  EXPECT_NE(text.find("polytope USE S"), std::string::npos);
  EXPECT_NE(text.find("operands [ USE P, USE Q ]"), std::string::npos);
  const Scene back = read_scene(std::string_view(text), "mem");
  ASSERT_EQ(back.polytopes.size(), 3u);
  ASSERT_EQ(back.shapes.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.polytopes[i].name, scene.polytopes[i].name);
    expect_same(back.polytopes[i].mesh, scene.polytopes[i].mesh);
  }
  EXPECT_TRUE(minksum::testing::same_polytope(ConvexPolytope::from_mesh(back.polytopes[2].mesh), s));
  ASSERT_EQ(back.cgms.size(), 1u);
  const SceneCgm& c = back.cgms[0];
  EXPECT_EQ(c.polytope, 2u);
  EXPECT_EQ(c.operands, (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(c.map_counts, scene.cgms[0].map_counts);
  ASSERT_TRUE(c.map_points.has_value());
  ASSERT_EQ(c.map_points->size(), scene.cgms[0].map_points->size());
  for (std::size_t i = 0; i < c.map_points->size(); ++i) {
    EXPECT_EQ((*c.map_points)[i].map, (*scene.cgms[0].map_points)[i].map);
    EXPECT_EQ((*c.map_points)[i].x, (*scene.cgms[0].map_points)[i].x);
    EXPECT_EQ((*c.map_points)[i].y, (*scene.cgms[0].map_points)[i].y);
  }
  // Without exact coordinates the points are the nearest doubles, as write_mesh writes them.
  const Scene doubles = read_scene(std::string_view(scene_text(scene, false)), "mem");
  EXPECT_EQ(doubles.polytopes[0].mesh.points.size(), p.num_vertices());
  EXPECT_NE(scene_text(scene, false).find("coord Coordinate {"), std::string::npos);
}

TEST(VrmlScene, ReadMeshRefusesASceneOfSeveralPolytopesNamingTheCount) {
  const ConvexPolytope p = catalog_polytope("cube"), q = catalog_polytope("tetrahedron");
  const std::string text = scene_text(sum_scene(p, q, minkowski_sum(p, q).polytope), true);
  const std::size_t second = std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find("DEF Q")), '\n')) + 1;
  expect_input_error([&] { read_from_string(text, Format::wrl); }, "mem",
                     "more than one IndexedFaceSet or ExactPolyhedron: the scene holds 3 polytopes",
                     "line " + std::to_string(second));
}

TEST(VrmlScene, MalformedNodesNameTheLine) {
  const std::string head = "#VRML V2.0 utf8\nDEF T ExactPolyhedron { coord ExactCoordinate { ratPoint [ 0 0 0 1 0 0 0 1 0 0 0 1 ] }"
                           " coordIndex [ 0 2 1 -1 0 1 3 -1 0 3 2 -1 1 2 3 -1 ] }\n";
  struct Case {
    std::string body, problem, place;
  };
  const std::vector<Case> cases = {
      {"CubicalGaussianMap { }", "has neither 'polytope' nor 'operands'", "line 3"},
      {"CubicalGaussianMap {\n operands [ USE T ] }", "'operands' lists 1 polytopes; two are needed", "line 4"},
      {"CubicalGaussianMap { polytope USE T\n mapCounts [ 1 2 3 ] }", "'mapCounts' has 3 integers; 18 are needed",
       "line 4"},
      {"CubicalGaussianMap { polytope USE T mapCounts [ 4 8 3 4 8 3 4 8 3 5 12 4 5 12 4 5 12 -4 ] }",
       "'mapCounts' needs non-negative integers, got '-4'", "line 3"},
      {"CubicalGaussianMap { polytope USE T mapPoint [ 7 0 0 ] }", "'mapPoint' names map 7", "line 3"},
      {"CubicalGaussianMap { polytope USE T mapPoint [ 0 0 ] }", "not a multiple of 3", "line 3"},
      {"CubicalGaussianMap { polytope USE T mapPoint [ 0 3/2 0 ] }", "lies outside the square", "line 3"},
      {"CubicalGaussianMap { polytope USE T mapPoint [ 0 x 0 ] }", "expected a number, got 'x'", "line 3"},
      {"CubicalGaussianMap { polytope USE T\n colour 1 }", "unknown field 'colour' in the CubicalGaussianMap", "line 4"},
      {"CubicalGaussianMap { polytope USE U }", "'polytope' USE 'U' names no earlier ExactPolyhedron", "line 3"},
      {"CubicalGaussianMap { polytope Coordinate { } }", "'polytope' needs an ExactPolyhedron", "line 3"},
      {"CubicalGaussianMap { polytope USE T\n polytope USE T }", "two 'polytope' fields", "line 4"},
      {"CubicalGaussianMap { polytope USE T", "file ends inside the CubicalGaussianMap", "line 4"},
      {"\nExactPolyhedron { coordIndex [ 0 1 2 ] }", "the ExactPolyhedron has no 'coord' field", "line 4"},
      {"ExactPolyhedron { coord ExactCoordinate { ratPoint [ 0 0 0 1 0 ] } }", "ratPoint list has 5 numbers", "line 3"},
      {"ExactPolyhedron { coord ExactCoordinate { ratPoint [ 0 0 1/0 ] } }", "zero denominator", "line 3"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.body);
    expect_input_error([&] { read_scene(std::string_view(head + c.body + "\n"), "scene.wrl"); }, "scene.wrl",
                       c.problem, c.place);
  }
  // A polytope inside a CubicalGaussianMap under a moved Transform is refused like an IndexedFaceSet.
  expect_input_error(
      [&] {
        read_scene(std::string_view(head + "Transform { translation 1 0 0\n children Shape { geometry "
                                           "CubicalGaussianMap { polytope USE T } } }\n"),
                   "scene.wrl");
      },
      "scene.wrl", "the CubicalGaussianMap is inside a Transform with a non-identity 'translation'", "line 3");
}

// The writer's local certificate (PolytopeBuilder::moved) against full
// validation.  The rounded vertices of exact sums, nudged by a few ulps (the
// folds of rotated spheres are nearly flat, so nudges make some reflex,
// flatten some, and keep most convex): whenever the certificate accepts, full
// validation of the same mesh builds the same polytope, facet by facet;
// whenever it declines, full validation refuses the mesh or changes it
// (merges coplanar facets, welds points).  Odd trials run the loops of both
// on threads (parallel_items() 1: every loop of two blocks or more).
TEST(IoRounding, LocalCertificateAgreesWithFullValidation) {
  const unsigned seed = 20261123;
  std::mt19937 rng(seed);
  int accepted = 0, declined = 0;
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{
           {"sphere:3", "sphere:3@rot:5"}, {"dodecahedron", "truncated-cube@rot:2"},
           {"random:200:1", "sphere:2@rot:3"}, {"cube@rot:1", "octahedron@rot:2"}}) {
    const ConvexPolytope s = minkowski_sum(catalog_polytope(a), catalog_polytope(b)).polytope;
    for (int trial = 0; trial < 16; ++trial) {
      SCOPED_TRACE(a + " + " + b + ", trial " + std::to_string(trial) + ", seed " + std::to_string(seed));
      PointList pts;
      for (Index v = 0; v < s.num_vertices(); ++v) {
        double c[3];
        for (int k = 0; k < 3; ++k) {
          c[k] = io_detail::coordinate_double(s.coordinates(), v, k);
          // trial 0: as written; then about one coordinate in 3, moved by
          // up to 2^(3 trial) ulps either way (2^45 ulps: a relative 2^-7).
          if (trial > 0 && rng() % 3 == 0) {
            const double ulp = std::nextafter(std::abs(c[k]), 1e300) - std::abs(c[k]);
            c[k] += std::ldexp(ulp, 3 * trial) * (double(rng() % 2001) / 1000 - 1);
          }
          c[k] += 0.0;
        }
        pts.push_back(Vec3d{c[0], c[1], c[2]});
      }
      // The mesh the full path validates: s's facets, quadrilaterals no
      // longer planar cut along the diagonal that folds outwards.
      Mesh m;
      m.points = pts;
      bool large_cut = false;
      for (Index f = 0; f < s.num_facets(); ++f) {
        const std::vector<Index> loop = s.facet_vertices(f);
        const auto& v = pts.approx();
        bool planar = true;
        for (std::size_t i = 3; i < loop.size(); ++i)
          planar = planar && orient3d(v[loop[0]], v[loop[1]], v[loop[2]], v[loop[i]]) == 0;
        if (planar) {
          m.faces.push_back(loop);
        } else if (loop.size() == 4) {
          const Index p0 = loop[0], p1 = loop[1], p2 = loop[2], p3 = loop[3];
          if (orient3d(v[p0], v[p1], v[p2], v[p3]) < 0) {
            m.faces.push_back({p0, p1, p2});
            m.faces.push_back({p0, p2, p3});
          } else {
            m.faces.push_back({p1, p2, p3});
            m.faces.push_back({p1, p3, p0});
          }
        } else {
          large_cut = true;
        }
      }
      std::optional<minksum::testing::ParallelItems> threads;
      if (trial % 2 == 1) threads.emplace(1);
      std::size_t split = 0;
      const std::optional<ConvexPolytope> fast = PolytopeBuilder::moved(s, pts, &split);
      if (large_cut) {
        EXPECT_FALSE(fast.has_value());
        continue;
      }
      std::optional<ConvexPolytope> full;
      try {
        full = ConvexPolytope::from_mesh(m);
      } catch (const InputError&) {
      }
      const bool same = full && full->num_vertices() == s.num_vertices() && full->num_facets() == m.faces.size();
      EXPECT_EQ(fast.has_value(), same);
      if (!fast || !same) {
        ++declined;
        continue;
      }
      ++accepted;
      EXPECT_EQ(split, m.faces.size() - s.num_facets());
      ASSERT_EQ(fast->num_facets(), full->num_facets());
      EXPECT_EQ(fast->num_edges(), full->num_edges());
      for (Index f = 0; f < fast->num_facets(); ++f) EXPECT_EQ(fast->facet_vertices(f), full->facet_vertices(f)) << f;
      for (Index v = 0; v < fast->num_vertices(); ++v) {
        const Vec3d &x = fast->approx(v), &y = full->approx(v);
        EXPECT_TRUE(x.x == y.x && x.y == y.y && x.z == y.z) << v;
      }
      if (trial == 0) {
        EXPECT_EQ(fast->check_invariants(), "");
      }
    }
  }
  EXPECT_GT(accepted, 10) << declined;
  EXPECT_GT(declined, 5) << accepted;
}

// Regression (writing sphere:4 ⊕ sphere:4@rot:5, both rounded to doubles,
// the end-to-end benchmark's second row): the rounding certificate's facet
// test counted the turns of a polygon by a reference ray along its first
// side, and a parallelogram's opposite side lies along that ray: a zero
// the intervals could not decide, so each of the 224 parallelograms still
// planar after rounding went to rational arithmetic (more than half of the
// write).  The ray now lies between the first two sides, and intervals
// decide every fan of this sum, in the certificate and when the written
// file is read back.
TEST(IoWrite, RoundedSumOfRotatedSpheresNeedsNoExactFanTests) {
  auto as_doubles = [](const ConvexPolytope& p) {
    Mesh m = writable_polytope(p, Format::off, {}, nullptr).to_mesh();
    EXPECT_TRUE(m.points.all_doubles());
    return ConvexPolytope::from_mesh(m);
  };
  const ConvexPolytope a = as_doubles(catalog_polytope("sphere:4")), b = as_doubles(catalog_polytope("sphere:4@rot:5"));
  const ConvexPolytope s = minkowski_sum(a, b).polytope;
  ASSERT_EQ(s.coordinates().form(), PointList::Form::double_pairs);
  const std::uint64_t before = exact_fan_tests();
  RoundingReport report;
  const ConvexPolytope w = writable_polytope(s, Format::off, {}, &report);
  EXPECT_EQ(exact_fan_tests(), before);
  EXPECT_EQ(s.num_vertices(), 2738u);
  EXPECT_EQ(s.num_facets(), 4016u);
  EXPECT_EQ(report.split, 1210u);
  EXPECT_FALSE(report.hull);
  EXPECT_EQ(w.num_facets(), 4016u + 1210u);
  // Read back: the same polytope, and no exact fan test either.
  const ConvexPolytope r = ConvexPolytope::from_mesh(w.to_mesh());
  EXPECT_EQ(exact_fan_tests(), before);
  EXPECT_EQ(r.num_vertices(), w.num_vertices());
  EXPECT_EQ(r.num_facets(), w.num_facets());
}

namespace {
// A box [0,1] x [0,2] x [-1, top] whose top is two triangles A B C and
// A C D folding along A-C, D given exactly (not a double).
ConvexPolytope roof(const Point3& d, const Point3& c) {
  PointList pts;
  pts.push_back(Point3(Rational(0), Rational(0), Rational(1)));
  pts.push_back(Point3(Rational(1), Rational(0), Rational(1)));
  pts.push_back(c);
  pts.push_back(d);
  for (const auto& [x, y] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {1, 2}, {0, 2}})
    pts.push_back(Point3(Rational(x), Rational(y), Rational(-1)));
  return ConvexPolytope::hull(pts);
}
// The nearest doubles of p's vertices, as the writer rounds them.
PointList nearest_doubles(const ConvexPolytope& p) {
  PointList rounded;
  for (Index v = 0; v < p.num_vertices(); ++v)
    rounded.push_back(Vec3d{to_double(p.point(v).x), to_double(p.point(v).y), to_double(p.point(v).z)});
  return rounded;
}
}  // namespace

// A fold made coplanar by rounding: D = (0, 2, 1 - 2^-60) lies below the
// plane z = 1 of A, B, C = (1, 2, 1); rounded, it lies on it.  Not certified
// locally; the full path merges the two triangles: the box, 6 facets.
TEST(IoRounding, FoldMadeCoplanarByRoundingIsMerged) {
  const ConvexPolytope p = roof(Point3(Rational(0), Rational(2), Rational(1) - pow2(-60)),
                               Point3(Rational(1), Rational(2), Rational(1)));
  ASSERT_EQ(p.num_vertices(), 8u);
  ASSERT_EQ(p.num_facets(), 7u);
  EXPECT_FALSE(PolytopeBuilder::moved(p, nearest_doubles(p), nullptr).has_value());
  RoundingReport r;
  const ConvexPolytope w = writable_polytope(p, Format::off, {}, &r);
  EXPECT_EQ(r.coordinates, 1u);
  EXPECT_FALSE(r.hull);
  EXPECT_EQ(w.num_vertices(), 8u);
  EXPECT_EQ(w.num_facets(), 6u);
  EXPECT_EQ(w.volume(), Rational(4));
  EXPECT_EQ(w.check_invariants(), "");
}

// A fold made reflex by rounding: C = (1, 2, 0), so A B C spans the plane
// z = 1 - y/2; D = (0, 2 - 2^-58, 7 * 2^-62) lies 2^-62 below it.  Rounded,
// D = (0, 2, 7 * 2^-62) lies above the plane's height 0 there: the fold turns
// reflex.  Not certified locally; the hull of the rounded points is written.
TEST(IoRounding, FoldMadeReflexByRoundingIsNotCertified) {
  const ConvexPolytope p = roof(Point3(Rational(0), Rational(2) - pow2(-58), 7 * pow2(-62)),
                               Point3(Rational(1), Rational(2), Rational(0)));
  ASSERT_EQ(p.num_vertices(), 8u);
  EXPECT_FALSE(PolytopeBuilder::moved(p, nearest_doubles(p), nullptr).has_value());
  RoundingReport r;
  const ConvexPolytope w = writable_polytope(p, Format::off, {}, &r);
  EXPECT_EQ(r.coordinates, 1u);
  EXPECT_TRUE(r.hull);
  EXPECT_EQ(w.check_invariants(), "");
  for (const WriteMode& m : every_write_mode()) expect_reads_back(p, m, "reflex roof");
}

// The same roof: its rounded fold is strictly reflex between two facets
// that are still planar (a triangle and the quadrilateral, which are kept
// as they are), so the validation would refuse the split mesh and the
// hull is written without it; the written polytope is the exact hull of
// the rounded points, vertex for vertex and facet for facet.
TEST(IoRounding, ReflexFoldBetweenPlanarFacetsIsTheHullOfTheRoundedPoints) {
  const ConvexPolytope p = roof(Point3(Rational(0), Rational(2) - pow2(-58), 7 * pow2(-62)),
                               Point3(Rational(1), Rational(2), Rational(0)));
  RoundingReport r;
  const ConvexPolytope w = writable_polytope(p, Format::off, {}, &r);
  const ConvexPolytope h = ConvexPolytope::hull(nearest_doubles(p));
  EXPECT_TRUE(r.hull);
  EXPECT_EQ(r.split, 0u);
  EXPECT_EQ(vertex_set(w), vertex_set(h));
  ASSERT_EQ(w.num_facets(), h.num_facets());
  for (Index f = 0; f < w.num_facets(); ++f) EXPECT_EQ(w.plane(f), h.plane(f)) << "facet " << f;
  EXPECT_EQ(w.volume(), h.volume());
}
