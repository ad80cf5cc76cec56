// VRML scenes on the command line (docs/vrml.md): reading one whole, with
// every node checked, and the nodes 'cgm -o' and 'sum --scene' write.
#pragma once

#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/polytope.hpp>
#include <minksum/scene.hpp>
#include <minksum/sum_result.hpp>

#include <string>
#include <vector>

namespace minksum::cli {

// A CubicalGaussianMap node, checked: the map of `polytope` (the node's
// polytope, or the Minkowski sum of its operands).
struct LoadedCgm {
  std::string name;                     // for the page: its DEF name or "CubicalGaussianMap at line N"
  CubicalGaussianMap map;
  ConvexPolytope polytope;
  std::vector<std::string> operands;    // the operands' names, for a sum
  std::vector<std::size_t> operand_nodes;  // their indices into LoadedScene::polytopes
  std::size_t polytope_node = kNoNode;     // the node's polytope in LoadedScene::polytopes, if it names one
  std::vector<FacetProvenance> provenance;  // of a sum's facets
};

struct LoadedScene {
  std::vector<ConvexPolytope> polytopes;  // Scene::polytopes, validated
  std::vector<std::string> names;         // their DEF names, or "ExactPolyhedron at line N"
  // For each polytope, the text of a comment line "# NAME = TEXT" naming its
  // DEF NAME ('minksum sum --scene' writes "# A = cube", "# S = A ⊕ B"); "".
  std::vector<std::string> comments;
  std::vector<LoadedCgm> cgms;
  std::vector<SceneShape> shapes;
};

// True when `path` names an existing VRML file (.wrl).
bool is_scene_file(const std::string& path);

// The scene of `path`: read_scene, then every polytope validated as a convex
// polytope and every CubicalGaussianMap built; a node whose polytope is not
// the sum of its operands, or whose mapCounts or mapPoint differ from the
// map of its polytope, is an InputError naming the node's line.
LoadedScene load_scene(const std::string& path);

// A CubicalGaussianMap node for writing: polytope `polytope`, `operands`
// (none or two), and the counts and real vertices of g's six maps.
SceneCgm cgm_node(const CubicalGaussianMap& g, const std::string& name, std::size_t polytope,
                  const std::vector<std::size_t>& operands = {});

// A polytope node for writing.
ScenePolytope polytope_node(const ConvexPolytope& p, const std::string& name);

// Writes the scene to `path` (atomically); OutputError when it cannot be written.
void write_scene_output(const std::string& path, const Scene& scene, bool exact,
                        const std::vector<std::string>& comments);

}  // namespace minksum::cli
