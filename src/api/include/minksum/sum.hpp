// minksum — one operand of any kind and one Minkowski sum over a sequence of
// them: the layer the command line, `minksum batch` and the Python package
// share, so that the choice between the kinds of operands is made once.
//
// An operand is a convex polytope, a lower-dimensional convex set (a point,
// a segment or a flat convex polygon: docs/sweeps.md) or a closed solid that
// is not convex (docs/nonconvex.md).  minkowski_sum(operands, request) folds
// the sum left to right and returns the right kind of result:
//   * convex polytopes only: a convex polytope (<minksum/minkowski.hpp>);
//   * any lower-dimensional set among convex operands: a convex set of
//     dimension 0 to 3 (<minksum/sweep.hpp>);
//   * a solid that is not convex (then exactly two operands, neither of them
//     lower-dimensional): the exact boundary of the sum, a closed polygon
//     mesh (<minksum/nonconvex.hpp>).
// Erosion, opening and closing of a solid by a convex polytope are the same
// call with SumRequest::operation.  Every result comes with one SumReport:
// counts, kind, method, phases, exact volume and the method's own work, from
// which `minksum sum --json`, `minksum batch` and Python's results are all
// printed.
#pragma once

#include <minksum/convex_set.hpp>
#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>
#include <minksum/nonconvex.hpp>
#include <minksum/operand.hpp>
#include <minksum/polytope.hpp>
#include <minksum/sum_result.hpp>
#include <minksum/sweep.hpp>

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace minksum {

// How an operand is read (Operand::load).
struct OperandOptions {
  // Take the exact convex hull of the points (in whatever dimension they
  // span) instead of requiring a valid mesh: point clouds, and closed
  // surfaces that are not exactly convex.
  bool hull = false;
  // The format of a file whose name has no known extension.
  std::optional<Format> format;
  // Called once the mesh is known not to be convex, just before it is
  // validated as a solid (validation runs on worker threads): the command
  // line gives each worker thread its own malloc arena there, which must
  // happen before any worker thread allocates.
  std::function<void()> before_solid;
};

// One operand of a sum, with the name that identifies it in messages and
// reports.
class Operand {
 public:
  enum class Kind { polytope, set, solid };

  explicit Operand(ConvexPolytope p, std::string name = {});
  // A full-dimensional set is kept as its polytope.
  explicit Operand(ConvexSet s, std::string name = {});
  // A solid stays one, convex or not: a sum with it takes the non-convex
  // path and gives a solid's boundary (Operand::load reads a convex mesh as
  // a polytope instead).
  explicit Operand(Solid s, std::string name = {});

  // A file or a catalog name (<minksum/operand.hpp> decides which), read as
  // what it is: a convex polytope when the mesh is one; a point, a segment
  // or a polygon (a catalog name, a file holding one face); else the mesh
  // validated as a closed solid (validate_solid, whose InputError names the
  // problem; for a point cloud or a closed surface that is only nearly
  // convex the message adds that --hull takes the convex hull of its points
  // instead).  With options.hull, the exact hull of the points.  `phases`
  // receives the seconds spent reading and validating (a solid's validation
  // included).  Errors as load_polytope's.
  static Operand load(const std::string& spec, const OperandOptions& options = {}, LoadPhases* phases = nullptr);
  // The same for a mesh read whole from a stream in `format`; `name` names it
  // (options.format is not used).
  static Operand load(std::istream& in, Format format, const std::string& name, const OperandOptions& options = {},
                      LoadPhases* phases = nullptr);

  const std::string& name() const { return name_; }
  Kind kind() const { return static_cast<Kind>(value_.index()); }
  // 3 for a polytope or a solid, else the set's (0 to 2).
  int dimension() const;
  // "polytope", "polygon", "segment", "point" or "solid" (docs/json.md; a
  // Solid that is exactly convex is a "polytope").
  const char* kind_name() const;
  // Null unless the operand is of that kind.
  const ConvexPolytope* polytope() const { return std::get_if<ConvexPolytope>(&value_); }
  const ConvexSet* set() const { return std::get_if<ConvexSet>(&value_); }
  const Solid* solid() const { return std::get_if<Solid>(&value_); }
  // Vertices, edges and facets (a solid's faces as validated: a polygon of
  // k corners counts once, its k - 3 inner triangle edges not at all).
  std::size_t num_vertices() const;
  std::size_t num_edges() const;
  std::size_t num_facets() const;
  // The operand as a solid (a polytope's solid_of); std::invalid_argument
  // for a lower-dimensional set.
  Solid to_solid() const;
  // The operand as a convex set; std::invalid_argument for a solid.
  ConvexSet to_set() const;
  // The operand itself, moved out (the Operand is left empty).
  std::variant<ConvexPolytope, ConvexSet, Solid> release() && { return std::move(value_); }

 private:
  std::variant<ConvexPolytope, ConvexSet, Solid> value_;  // in the order of Kind
  std::string name_;
};

// What is computed from the operands A, B (SumRequest::operation).
enum class SumOperation {
  sum,    // A ⊕ B ⊕ ..., left to right
  erode,  // A ⊖ B = {x : x + B ⊆ A}: a solid A, a convex polytope B
  open,   // (A ⊖ B) ⊕ B
  close,  // (A ⊕ B) ⊖ B
};

struct SumRequest {
  SumOperation operation = SumOperation::sum;
  // The method of convex sums (and of the non-convex sums' convex pieces:
  // walk for automatic).
  Method method = Method::automatic;
  NonconvexMethod nonconvex = NonconvexMethod::sweep;
  // Progress and cancellation; options.volume: whether SumReport::volume is
  // computed (a caller that has other work meanwhile computes it with
  // result_volume, as the command line does while it writes the file).
  SumOptions options;
  unsigned threads = 0;  // non-convex sums: 0, every hardware thread
  // Keep a convex sum's per-facet and per-vertex records (SumResult's
  // facet_provenance and vertex_origin) in the result; when false they are
  // dropped once SumReport has counted them.
  bool provenance = true;
};

// An operand as the report gives it.
struct OperandReport {
  std::string name;
  int dimension = 3;
  const char* kind = "polytope";
  std::size_t vertices = 0, edges = 0, facets = 0;
};

struct SumReport {
  // "sum", or "erosion", "opening", "closing".
  const char* operation = "sum";
  // The result: dimension (0 to 3), kind ("point", "segment", "polygon",
  // "polytope" or "solid" for the boundary of a sum with a non-convex
  // operand), counts; empty when an erosion or opening left nothing.
  int dimension = 3;
  const char* kind = "polytope";
  std::size_t vertices = 0, edges = 0, facets = 0;
  bool empty = false;
  // The method's name ("walk", ...), or "nonconvex".
  std::string method;
  // Sums with a lower-dimensional set: how the last step was made
  // (SetSumResult::route); else null.
  const char* route = nullptr;
  // Seconds of the computation alone (not reading, validating or writing),
  // and its phases in order: convex and sets "sum" and "explicit"; solids
  // "decompose", "pairs", "union", "boundary".
  double seconds = 0;
  std::vector<std::pair<const char*, double>> phases;
  // The exact volume (0 below dimension 3); empty when
  // SumRequest::options.volume was false.
  std::optional<Rational> volume;
  std::vector<OperandReport> operands;
  // Convex sums of two polytopes: the facets by origin (FacetOrigin's names,
  // when the method records it), the method's own facet cases and counters.
  std::vector<std::pair<std::string, long long>> facet_types, facet_cases, counters;
  // Sums with a non-convex operand, erosion, opening, closing: the work
  // (NonconvexSum without its mesh).
  std::optional<NonconvexSum> nonconvex;
};

// A sum's result: exactly one of a convex polytope (SumResult), a convex set
// of dimension below 3 (SetSumResult), a solid's boundary (NonconvexSum,
// whose mesh may be empty after an erosion), and its report.
struct OperandSum {
  std::variant<SumResult, SetSumResult, NonconvexSum> result;
  SumReport report;

  const ConvexPolytope* polytope() const;  // null unless a convex polytope
  const ConvexSet* set() const;            // null unless dimension < 3
  const Mesh* solid() const;               // null unless a solid's boundary
};

// The sum (or erosion, opening, closing) of `operands`, exactly.  Throws
// std::invalid_argument for fewer than two operands; UsageError for a
// lower-dimensional set with a solid that is not convex, for a non-convex
// sum of more than two operands, for a method that takes polytopes only
// with a lower-dimensional set, and for erode/open/close with other than
// two operands; InputError naming B when erode/open/close is given a B that
// is not a convex polytope; Cancelled when options.cancel is set.
OperandSum minkowski_sum(const std::vector<Operand>& operands, const SumRequest& request = {});

// The exact volume of a result (a solid's boundary by mesh_volume; 0 below
// dimension 3).
Rational result_volume(const OperandSum& sum);

}  // namespace minksum
