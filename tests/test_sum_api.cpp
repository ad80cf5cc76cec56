// <minksum/sum.hpp>: one operand of any kind, one sum over a sequence of
// them, one report.  Every kind of operand loads as what it is; the sum picks
// the engine the operands need and gives what that engine gives (compared
// with the engines called directly: the same exact results), and the report
// counts what the result holds.
#include <gtest/gtest.h>

#include <minksum/catalog.hpp>
#include <minksum/error.hpp>
#include <minksum/sum.hpp>

#include "test_support.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace minksum;

namespace {

std::vector<Operand> operands(std::initializer_list<const char*> names) {
  std::vector<Operand> out;
  for (const char* n : names) out.push_back(Operand::load(n));
  return out;
}

long long total(const std::vector<std::pair<std::string, long long>>& counts) {
  long long t = 0;
  for (const auto& c : counts) t += c.second;
  return t;
}

}  // namespace

TEST(SumApi, OperandsLoadAsWhatTheyAre) {
  const Operand cube = Operand::load("cube");
  EXPECT_EQ(cube.kind(), Operand::Kind::polytope);
  EXPECT_STREQ(cube.kind_name(), "polytope");
  EXPECT_EQ(cube.dimension(), 3);
  EXPECT_EQ(cube.num_vertices(), 8u);
  EXPECT_EQ(cube.num_edges(), 12u);
  EXPECT_EQ(cube.num_facets(), 6u);

  const Operand seg = Operand::load("segment:0,0,0:3,1,2");
  EXPECT_EQ(seg.kind(), Operand::Kind::set);
  EXPECT_STREQ(seg.kind_name(), "segment");
  EXPECT_EQ(seg.dimension(), 1);
  EXPECT_EQ(seg.num_vertices(), 2u);

  const Operand square = Operand::load("square");
  EXPECT_STREQ(square.kind_name(), "polygon");
  EXPECT_EQ(square.dimension(), 2);

  // The tube: 16 vertices, 16 quadrilateral faces, genus 1 (E = V + F).
  const Operand tube = Operand::load("tube");
  EXPECT_EQ(tube.kind(), Operand::Kind::solid);
  EXPECT_STREQ(tube.kind_name(), "solid");
  EXPECT_EQ(tube.num_vertices(), 16u);
  EXPECT_EQ(tube.num_facets(), 16u);
  EXPECT_EQ(tube.num_edges(), 32u);
  EXPECT_THROW(tube.to_set(), std::invalid_argument);
  EXPECT_THROW(seg.to_solid(), std::invalid_argument);

  // --hull: the hull of the tube's points is a box.
  const Operand hull = Operand::load("tube", {true, std::nullopt, {}});
  ASSERT_TRUE(hull.polytope());
  EXPECT_EQ(hull.num_vertices(), 8u);
}

TEST(SumApi, APointCloudIsRefusedWithTheHullHint) {
  const fs::path dir = fs::temp_directory_path() / ("minksum_sum_api_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path cloud = dir / "cloud.off";
  std::ofstream(cloud) << "OFF\n4 0 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  try {
    Operand::load(cloud.string());
    ADD_FAILURE() << "a point cloud was taken as an operand";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), cloud.string());
    EXPECT_NE(std::string(e.what()).find("--hull takes the convex hull of its points instead"), std::string::npos)
        << e.what();
  }
  const Operand hull = Operand::load(cloud.string(), {true, std::nullopt, {}});
  ASSERT_TRUE(hull.polytope());  // the tetrahedron
  EXPECT_EQ(hull.num_facets(), 4u);
  fs::remove_all(dir);
}

TEST(SumApi, ConvexSumIsTheMethodsWithItsReport) {
  const std::vector<Operand> ops = operands({"dodecahedron", "sphere:3@rot:5"});
  const OperandSum s = minkowski_sum(ops);
  ASSERT_TRUE(s.polytope());
  EXPECT_FALSE(s.set());
  EXPECT_FALSE(s.solid());
  const SumResult direct = minkowski_sum(*ops[0].polytope(), *ops[1].polytope(), Method::walk);
  EXPECT_TRUE(minksum::testing::same_polytope(*s.polytope(), direct.polytope));
  const SumReport& r = s.report;
  EXPECT_STREQ(r.kind, "polytope");
  EXPECT_EQ(r.dimension, 3);
  EXPECT_EQ(r.method, "walk");
  EXPECT_EQ(r.vertices, std::size_t(direct.polytope.num_vertices()));
  EXPECT_EQ(r.edges, std::size_t(direct.polytope.num_edges()));
  EXPECT_EQ(r.facets, std::size_t(direct.polytope.num_facets()));
  ASSERT_TRUE(r.volume);
  EXPECT_EQ(*r.volume, direct.polytope.volume());
  EXPECT_EQ(total(r.facet_types), (long long)r.facets);  // every facet has one origin
  ASSERT_EQ(r.operands.size(), 2u);
  EXPECT_EQ(r.operands[0].name, "dodecahedron");
  EXPECT_EQ(r.operands[0].facets, 12u);
  ASSERT_EQ(r.phases.size(), 2u);
  EXPECT_STREQ(r.phases[0].first, "sum");
  EXPECT_FALSE(r.nonconvex);
  EXPECT_EQ(r.route, nullptr);
  EXPECT_FALSE(std::get<SumResult>(s.result).facet_provenance.empty());

  // Without the provenance in the result, the report still counts it.
  SumRequest lean;
  lean.provenance = false;
  lean.options.volume = false;
  const OperandSum l = minkowski_sum(ops, lean);
  EXPECT_TRUE(std::get<SumResult>(l.result).facet_provenance.empty());
  EXPECT_EQ(l.report.facet_types, r.facet_types);
  EXPECT_FALSE(l.report.volume);
  EXPECT_EQ(result_volume(l), *r.volume);
}

TEST(SumApi, ManyOperandsFoldLeftToRight) {
  // Three cubes of side 2: a cube of side 6.
  const OperandSum s = minkowski_sum(operands({"cube", "cube", "cube"}));
  ASSERT_TRUE(s.polytope());
  EXPECT_EQ(s.report.vertices, 8u);
  EXPECT_EQ(s.report.facets, 6u);
  EXPECT_EQ(*s.report.volume, Rational(216));
  EXPECT_EQ(s.report.operands.size(), 3u);
  EXPECT_TRUE(s.report.facet_types.empty());  // a method's details belong to one step
}

TEST(SumApi, LowerDimensionalOperandsSweep) {
  // A cube of side 2 swept along (3, 0, 0): a 5 x 2 x 2 box, a polytope.
  const OperandSum box = minkowski_sum(operands({"cube", "segment:0,0,0:3,0,0"}));
  ASSERT_TRUE(box.polytope());
  EXPECT_STREQ(box.report.kind, "polytope");
  ASSERT_NE(box.report.route, nullptr);
  EXPECT_STREQ(box.report.route, "sweep");
  EXPECT_EQ(*box.report.volume, Rational(20));
  EXPECT_EQ(box.report.facets, 6u);
  EXPECT_EQ(box.report.operands[1].dimension, 1);

  // Two segments that are not parallel: a parallelogram (a polygon).
  const OperandSum pg = minkowski_sum(operands({"segment:0,0,0:2,0,0", "segment:0,0,0:1,1,0"}));
  ASSERT_TRUE(pg.set());
  EXPECT_EQ(pg.report.dimension, 2);
  EXPECT_STREQ(pg.report.kind, "polygon");
  EXPECT_EQ(pg.report.vertices, 4u);
  EXPECT_EQ(pg.set()->area_squared(), Rational(4));  // base 2, height 1
  EXPECT_EQ(*pg.report.volume, Rational(0));

  // A point: a translation.
  const OperandSum moved = minkowski_sum(operands({"point:1,2,3", "point:1,1,1"}));
  ASSERT_TRUE(moved.set());
  EXPECT_STREQ(moved.report.kind, "point");
  EXPECT_EQ(moved.set()->vertices()[0], Point3(2.0, 3.0, 4.0));
}

TEST(SumApi, ASolidTakesTheBoundarySweep) {
  const std::vector<Operand> ops = operands({"tube", "cube@scale:1/8"});
  const OperandSum s = minkowski_sum(ops);
  ASSERT_TRUE(s.solid());
  const SumReport& r = s.report;
  EXPECT_STREQ(r.kind, "solid");
  EXPECT_EQ(r.method, "nonconvex");
  ASSERT_TRUE(r.nonconvex);
  EXPECT_STREQ(r.nonconvex->method, "sweep");
  EXPECT_TRUE(r.nonconvex->mesh.faces.empty());  // the report holds the work, not the mesh
  EXPECT_EQ(r.facets, s.solid()->faces.size());
  EXPECT_EQ(r.vertices, s.solid()->points.size());
  ASSERT_TRUE(r.volume);
  EXPECT_EQ(*r.volume, mesh_volume(*s.solid()));
  EXPECT_EQ(*r.volume, result_volume(s));
  // The engine called directly gives the same boundary.
  const NonconvexSum direct = minkowski_sum_nonconvex(ops[0].to_solid(), ops[1].to_solid());
  EXPECT_EQ(direct.volume, *r.volume);
  EXPECT_EQ(direct.mesh.faces.size(), r.facets);
  EXPECT_EQ(r.nonconvex->shells, direct.shells);
  ASSERT_EQ(r.phases.size(), 4u);
  EXPECT_STREQ(r.phases[2].first, "union");
  EXPECT_STREQ(r.operands[1].kind, "polytope");
}

TEST(SumApi, AConvexSolidStaysASolid) {
  // A Solid given as one (Python's Solid): the non-convex engine, whose
  // boundary of two cubes of side 2 is a cube of side 4.
  std::vector<Operand> ops;
  ops.emplace_back(solid_of(catalog_polytope("cube")), "a");
  ops.emplace_back(catalog_polytope("cube"), "b");
  const OperandSum s = minkowski_sum(ops);
  ASSERT_TRUE(s.solid());
  EXPECT_EQ(*s.report.volume, Rational(64));
  EXPECT_STREQ(s.report.operands[0].kind, "polytope");
}

TEST(SumApi, ErosionOpeningClosing) {
  SumRequest request;
  request.operation = SumOperation::erode;
  const OperandSum e = minkowski_sum(operands({"lshape", "cube@scale:1/4"}), request);
  ASSERT_TRUE(e.solid());
  EXPECT_STREQ(e.report.operation, "erosion");
  EXPECT_EQ(*e.report.volume, Rational(5, 8));
  request.operation = SumOperation::open;
  const OperandSum o = minkowski_sum(operands({"lshape", "cube@scale:1/4"}), request);
  EXPECT_STREQ(o.report.operation, "opening");
  EXPECT_EQ(*o.report.volume, Rational(3));  // the axis-aligned L opened by a smaller cube is itself
  // Nothing left: an empty boundary, volume 0, no error.
  request.operation = SumOperation::erode;
  const OperandSum none = minkowski_sum(operands({"cube", "cube@scale:2"}), request);
  EXPECT_TRUE(none.report.empty);
  EXPECT_EQ(*none.report.volume, Rational(0));
  EXPECT_EQ(result_volume(none), Rational(0));
}

TEST(SumApi, WhatCannotBeSummedIsRefused) {
  EXPECT_THROW(minkowski_sum(operands({"cube"})), std::invalid_argument);
  // A segment with a non-convex solid.
  EXPECT_THROW(minkowski_sum(operands({"tube", "segment:0,0,0:1,0,0"})), UsageError);
  // A non-convex sum of three operands.
  EXPECT_THROW(minkowski_sum(operands({"tube", "cube", "cube"})), UsageError);
  // A method that takes polytopes only, with a segment.
  SumRequest cgm;
  cgm.method = Method::cgm;
  EXPECT_THROW(minkowski_sum(operands({"cube", "segment:0,0,0:1,0,0"}), cgm), UsageError);
  // Erosion by a B that is not convex: bad input naming B.
  SumRequest erode;
  erode.operation = SumOperation::erode;
  try {
    minkowski_sum(operands({"cube", "lshape"}), erode);
    ADD_FAILURE() << "a non-convex B was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "lshape");
    EXPECT_NE(e.problem().find("is not convex"), std::string::npos) << e.what();
  }
  EXPECT_THROW(minkowski_sum(operands({"cube", "square"}), erode), UsageError);
}

// The command line gives worker threads their own malloc arenas just before
// a solid's validation, the first work on worker threads (set later, as a
// first version of the api layer did, the sums of solids ran on one shared
// arena and 20-40 % slower): the hook runs exactly for the meshes that are
// validated as solids.
TEST(SumApi, BeforeSolidRunsJustForSolids) {
  int calls = 0;
  const OperandOptions options{false, std::nullopt, [&] { ++calls; }};
  EXPECT_TRUE(Operand::load("cube", options).polytope());
  EXPECT_TRUE(Operand::load("segment:0,0,0:1,0,0", options).set());
  EXPECT_EQ(calls, 0);
  EXPECT_TRUE(Operand::load("tube", options).solid());
  EXPECT_EQ(calls, 1);
  const OperandOptions hull{true, std::nullopt, [&] { ++calls; }};
  EXPECT_TRUE(Operand::load("tube", hull).polytope());
  EXPECT_EQ(calls, 1);
}
