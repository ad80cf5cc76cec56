// The minksum command line: sums with points, segments and flat polygons
// (docs/sweeps.md).
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/operand.hpp>
#include <minksum/sum_result.hpp>

#include <optional>
#include <string>
#include <vector>

#include "mesh_io.hpp"

namespace minksum::cli {

// An operand of any dimension: as load_operand (common.hpp), '-' included,
// through load_convex_set (operand.hpp).
ConvexSet load_set_operand(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> format);

// Write a set: a polytope by write_mesh_output (mesh_io.hpp); a polygon as
// one face, a point or a segment as its points without faces, exactly (never
// rounded: OutputError naming --exact when a coordinate is not a double;
// OutputError for STL, which holds closed triangle meshes only).
RoundingReport write_set_output(const MeshOutput& out, const ConvexSet& s);

// The page data of a set for 'minksum view' (cli/page.hpp's
// append_solid_json, whose fields it has): a polytope as there; a polygon as
// two facets, its loop and the reversed loop with opposite planes (a face
// seen from both sides); a segment as one facet [0, 1, 0] of no area (its
// edge drawn) and a point as [0, 0, 0], with the plane "0 0 0 0".
void append_set_json(std::string& out, const ConvexSet& s, const std::string& name, const std::string& role);

// 'minksum view A B' when an operand is not full-dimensional: the page of A,
// B and A ⊕ B (no provenance), and the summary or --json on stdout.
int view_sets(const std::string& output, const std::string& title, const std::vector<std::string>& names,
              const std::vector<ConvexSet>& operands, Method method, bool json);

// 'minksum query KIND P Q' when P or Q is not full-dimensional: one answer
// by SetObstacle (<minksum/sweep_proximity.hpp>), as text or one JSON object
// with "status", the exact value ("squared_distance", "squared_depth", "t")
// and its double, and the obstacle's "dimension"; no witness.
int query_sets(const std::string& kind, const ConvexSet& p, const ConvexSet& q, const Point3& u, const Point3& w,
               const Point3& d, Method method, bool json);

}  // namespace minksum::cli
