// VRML scenes on the command line (scene.hpp).
#include "scene.hpp"

#include <minksum/minkowski.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <sys/stat.h>
#include <tuple>

#include "common.hpp"

namespace minksum::cli {

namespace {

std::string at_line(std::size_t line) { return "line " + std::to_string(line); }

std::string node_name(const std::string& def, const char* type, std::size_t line) {
  return def.empty() ? std::string(type) + " at line " + std::to_string(line) : def;
}

std::vector<Point3> sorted_vertices(const ConvexPolytope& p) {
  std::vector<Point3> v = p.points();
  std::sort(v.begin(), v.end());
  return v;
}

// The real vertices of the six maps, as (map, x, y), sorted.
std::vector<std::tuple<int, Rational, Rational>> real_points(const CubicalGaussianMap& g) {
  std::vector<std::tuple<int, Rational, Rational>> v;
  for (int k = 0; k < 6; ++k)
    for (const auto& x : g.map(k).vertices)
      if (x.real) v.emplace_back(k, x.x, x.y);
  std::sort(v.begin(), v.end());
  return v;
}

// What the node says about its maps, against the map built.
void check_claims(const std::string& path, const SceneCgm& node, const CubicalGaussianMap& g) {
  static const char* what[3] = {"vertices", "halfedges", "faces"};
  if (node.map_counts)
    for (int k = 0; k < 6; ++k) {
      const auto c = g.counts(k);
      const Index built[3] = {c.vertices, c.halfedges, c.faces};
      for (int i = 0; i < 3; ++i)
        if ((*node.map_counts)[std::size_t(3 * k + i)] != built[i])
          throw InputError(path, at_line(node.map_counts_line),
                           "'mapCounts' gives map " + std::to_string(k) + " " +
                               std::to_string((*node.map_counts)[std::size_t(3 * k + i)]) + " " + what[i] +
                               ", the map of its polytope has " + std::to_string(built[i]));
    }
  if (node.map_points) {
    std::vector<std::tuple<int, Rational, Rational>> claimed;
    for (const SceneMapPoint& m : *node.map_points) claimed.emplace_back(m.map, m.x, m.y);
    std::sort(claimed.begin(), claimed.end());
    const auto built = real_points(g);
    if (claimed.size() != built.size())
      throw InputError(path, at_line(node.map_points_line),
                       "'mapPoint' lists " + std::to_string(claimed.size()) +
                           " points, the maps of its polytope have " + std::to_string(built.size()) +
                           " real vertices");
    for (std::size_t i = 0; i < built.size(); ++i)
      if (claimed[i] != built[i]) {
        // The first point listed that is not a real vertex of its map.
        for (const SceneMapPoint& m : *node.map_points)
          if (!std::binary_search(built.begin(), built.end(), std::make_tuple(m.map, m.x, m.y)))
            throw InputError(path, at_line(node.map_points_line),
                             "'mapPoint' " + std::to_string(m.map) + " " + format_exact(m.x) + " " +
                                 format_exact(m.y) + " is not a facet normal on map " + std::to_string(m.map) +
                                 " of its polytope");
        throw InputError(path, at_line(node.map_points_line),
                         "'mapPoint' lists a point twice and misses a real vertex of the maps of its polytope");
      }
  }
}

}  // namespace

bool is_scene_file(const std::string& path) {
  struct stat st{};
  return format_from_path(path) == Format::wrl && ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

LoadedScene load_scene(const std::string& path) {
  Scene scene = read_scene(path);
  if (scene.shapes.empty()) throw InputError(path, "", "no ExactPolyhedron, CubicalGaussianMap or IndexedFaceSet found");
  LoadedScene out;
  out.shapes = scene.shapes;
  for (const ScenePolytope& p : scene.polytopes) {
    const char* type = p.exact_node ? "ExactPolyhedron" : "IndexedFaceSet";
    const std::string name = node_name(p.name, type, p.line);
    try {
      out.polytopes.push_back(ConvexPolytope::from_mesh(p.mesh, path));
    } catch (const InputError& e) {
      // The node's line first: the polytope's own place (a face, a vertex) follows.
      throw InputError(path, at_line(p.line),
                       std::string(type) + (p.name.empty() ? "" : " '" + p.name + "'") + ": " +
                           (e.place().empty() ? "" : e.place() + ": ") + e.problem());
    }
    out.names.push_back(name);
  }
  for (const SceneCgm& node : scene.cgms) {
    LoadedCgm c;
    c.name = node_name(node.name, "CubicalGaussianMap", node.line);
    if (!node.operands.empty()) {
      const ConvexPolytope& a = out.polytopes[node.operands[0]];
      const ConvexPolytope& b = out.polytopes[node.operands[1]];
      SumResult r = minkowski_sum(a, b, Method::cgm);
      if (node.polytope != kNoNode && sorted_vertices(out.polytopes[node.polytope]) != sorted_vertices(r.polytope))
        throw InputError(path, at_line(node.line),
                         "the CubicalGaussianMap's polytope " + out.names[node.polytope] +
                             " is not the Minkowski sum of its operands " + out.names[node.operands[0]] + " and " +
                             out.names[node.operands[1]] + " (" + std::to_string(r.polytope.num_vertices()) +
                             " vertices, " + std::to_string(r.polytope.num_facets()) + " facets)");
      c.map = CubicalGaussianMap::from_polytope(r.polytope);
      c.map.set_operands(r.vertex_origin, r.polytope);
      c.provenance = r.facet_provenance.empty() ? facet_provenance(a, b, r.polytope) : r.facet_provenance;
      c.operands = {out.names[node.operands[0]], out.names[node.operands[1]]};
      c.operand_nodes = node.operands;
      c.polytope = std::move(r.polytope);
    } else {
      c.polytope = out.polytopes[node.polytope];
      c.map = CubicalGaussianMap::from_polytope(c.polytope);
    }
    c.polytope_node = node.polytope;
    check_claims(path, node, c.map);
    out.cgms.push_back(std::move(c));
  }
  // The comment lines "# NAME = TEXT" naming DEF NAME (minksum sum --scene
  // writes "# A = cube" and "# S = A ⊕ B"); VRML's reader skips comments.
  out.comments.assign(out.polytopes.size(), std::string());
  std::ifstream in(path, std::ios::binary);
  std::map<std::string, std::string> said;
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 2 || line[0] != '#') continue;
    const std::size_t eq = line.find(" = ");
    if (eq == std::string::npos) continue;
    std::string name = line.substr(1, eq - 1);
    name.erase(0, name.find_first_not_of(' '));
    if (name.empty() || name.find(' ') != std::string::npos) continue;
    std::string text = line.substr(eq + 3);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    said.emplace(name, text);  // the first comment of a name
  }
  for (std::size_t i = 0; i < scene.polytopes.size(); ++i)
    if (auto it = said.find(scene.polytopes[i].name); !scene.polytopes[i].name.empty() && it != said.end())
      out.comments[i] = it->second;
  return out;
}

SceneCgm cgm_node(const CubicalGaussianMap& g, const std::string& name, std::size_t polytope,
                  const std::vector<std::size_t>& operands) {
  SceneCgm n;
  n.name = name;
  n.polytope = polytope;
  n.operands = operands;
  std::array<Index, 18> counts{};
  std::vector<SceneMapPoint> points;
  for (int k = 0; k < 6; ++k) {
    const auto c = g.counts(k);
    counts[std::size_t(3 * k)] = c.vertices;
    counts[std::size_t(3 * k + 1)] = c.halfedges;
    counts[std::size_t(3 * k + 2)] = c.faces;
    for (const auto& v : g.map(k).vertices)
      if (v.real) points.push_back({k, v.x, v.y});
  }
  n.map_counts = counts;
  n.map_points = std::move(points);
  return n;
}

ScenePolytope polytope_node(const ConvexPolytope& p, const std::string& name) {
  ScenePolytope n;
  n.name = name;
  n.mesh = p.to_mesh();
  return n;
}

void write_scene_output(const std::string& path, const Scene& scene, bool exact,
                        const std::vector<std::string>& comments) {
  try {
    write_scene(path, scene, exact, comments);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
}

}  // namespace minksum::cli
