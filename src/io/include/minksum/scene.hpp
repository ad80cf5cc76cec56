// minksum — VRML 2.0 scenes with the geometry nodes of Fogel and Halperin's
// extended VRML: ExactPolyhedron (a polytope with exact coordinates) and
// CubicalGaussianMap (the Cubical Gaussian Map of a polytope, or of the
// Minkowski sum of two).  docs/vrml.md defines the fields.
//
// This layer reads and writes the text; it does not build Cubical Gaussian
// Maps.  read_scene checks the syntax, the types and counts of every field
// and the references between nodes (InputError, "line N"); what a
// CubicalGaussianMap node claims about its planar maps is checked exactly
// against the map of its polytope by the command line (cli/scene.cpp), which
// builds the maps.
#pragma once

#include <minksum/io.hpp>
#include <minksum/polytope.hpp>

#include <array>
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace minksum {

inline constexpr std::size_t kNoNode = std::size_t(-1);

// A polytope node of the scene: ExactPolyhedron, or the IndexedFaceSet of
// plain VRML.  `mesh` is raw (ConvexPolytope::from_mesh validates it).
struct ScenePolytope {
  std::string name;     // its DEF name, "" when it has none
  Mesh mesh;
  std::size_t line = 0;  // the line of the node's type name
  bool exact_node = true;  // ExactPolyhedron (false: IndexedFaceSet)
};

// A real vertex of planar map `map` (0-5) of a Cubical Gaussian Map: its
// exact 2D coordinates in the map's axes (<minksum/cubical_gaussian_map.hpp>).
struct SceneMapPoint {
  int map = 0;
  Rational x, y;
};

// A CubicalGaussianMap node.  Either field may be absent, not both: with
// `operands` the map is that of their Minkowski sum, and `polytope`, when
// also given, must be that sum exactly.
struct SceneCgm {
  std::string name;
  std::size_t line = 0;
  std::size_t polytope = kNoNode;   // index into Scene::polytopes
  std::vector<std::size_t> operands;  // none or two indices into Scene::polytopes
  // Per map 0-5: vertices, halfedges, faces (as 'minksum cgm --stats').
  std::optional<std::array<Index, 18>> map_counts;
  std::size_t map_counts_line = 0;
  std::optional<std::vector<SceneMapPoint>> map_points;
  std::size_t map_points_line = 0;
};

// The shapes of a scene, in file order: a top-level polytope node (a Shape's
// geometry, wherever the Shape is) or a CubicalGaussianMap node.  A polytope
// given inside a CubicalGaussianMap is in `polytopes` but not a shape of its
// own; a geometry reused through USE is not a second shape.
struct SceneShape {
  enum class Kind { polytope, cgm } kind = Kind::polytope;
  std::size_t index = 0;  // into Scene::polytopes or Scene::cgms
};

struct Scene {
  std::vector<ScenePolytope> polytopes;
  std::vector<SceneCgm> cgms;
  std::vector<SceneShape> shapes;
};

// Reads a VRML 2.0 file as a scene (the reader of read_mesh(.wrl), which
// takes the scene's one polytope).  InputError(name, "line N", problem) on
// any defect.
Scene read_scene(const std::string& path);
Scene read_scene(std::string_view data, const std::string& name);

// Writes `scene` as VRML 2.0: every polytope of `scene.polytopes` as a Shape
// whose geometry is DEF name ExactPolyhedron (exact: ExactCoordinate ratPoint;
// else Coordinate point with the nearest doubles, as write_mesh), each
// preceded by its `comments` line when given; then every CubicalGaussianMap
// as a Shape whose geometry refers to them with USE.  Every polytope needs a
// distinct name (a VRML identifier); shapes are written in this order, not
// from scene.shapes.  Atomic, as write_mesh.
void write_scene(std::ostream& out, const Scene& scene, bool exact, const std::vector<std::string>& comments = {});
void write_scene(const std::string& path, const Scene& scene, bool exact,
                 const std::vector<std::string>& comments = {});

}  // namespace minksum
