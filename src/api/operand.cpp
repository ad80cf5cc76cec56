// One operand of any kind (<minksum/sum.hpp>): a convex polytope, a point,
// segment or polygon, or a closed solid that is not convex.
#include <minksum/error.hpp>
#include <minksum/sum.hpp>

#include <chrono>
#include <stdexcept>

namespace minksum {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// validate_solid for an operand named `name`, with the hint that --hull
// takes the convex hull of its points where that gives what was likely
// meant: a point cloud, or a closed surface whose fault the convex validator
// finds in its convexity or planarity (NotConvexError: a CAD tool's
// rounding, a surface crossing itself); not for a surface that is broken
// (open, non-manifold, oriented inwards).
Solid validate_operand_solid(const Mesh& mesh, const std::string& name) {
  try {
    return validate_solid(mesh, name);
  } catch (const InputError& e) {
    bool hint = mesh.faces.empty();
    if (!hint) {
      try {
        ConvexPolytope::from_mesh(mesh, name);
      } catch (const NotConvexError&) {
        hint = true;
      } catch (const InputError&) {
      }
    }
    if (!hint) throw;
    throw InputError(e.file(), e.place(), e.problem() + "; --hull takes the convex hull of its points instead");
  }
}

// What load_any_operand read, as an Operand (a mesh validated as a solid).
Operand from_any(AnyOperand any, const std::string& name, LoadPhases& phases, const OperandOptions& options) {
  if (any.polytope) return Operand(std::move(*any.polytope), name);
  if (any.flat) return Operand(std::move(*any.flat), name);
  if (options.before_solid) options.before_solid();
  const auto t0 = Clock::now();
  Solid s = validate_operand_solid(any.mesh, name);
  phases.validate += since(t0);
  return Operand(std::move(s), name);
}

// load_convex_set's NotConvexError with the hint that --hull accepts it.
template <class Load>
ConvexSet hinted(Load load) {
  try {
    return load();
  } catch (const NotConvexError& e) {
    throw InputError(e.file(), e.place(), e.problem() + "; --hull takes the convex hull of its points instead");
  }
}

}  // namespace

Operand::Operand(ConvexPolytope p, std::string name) : value_(std::move(p)), name_(std::move(name)) {}

Operand::Operand(ConvexSet s, std::string name) : name_(std::move(name)) {
  if (s.full()) value_ = std::move(s).release_polytope();
  else value_ = std::move(s);
}

Operand::Operand(Solid s, std::string name) : value_(std::move(s)), name_(std::move(name)) {}

Operand Operand::load(const std::string& spec, const OperandOptions& options, LoadPhases* phases) {
  LoadPhases load;
  std::optional<Operand> o;
  if (options.hull) o.emplace(hinted([&] { return load_convex_set(spec, true, &load, options.format); }), spec);
  else o.emplace(from_any(load_any_operand(spec, &load, options.format), spec, load, options));
  if (phases) *phases = load;
  return std::move(*o);
}

Operand Operand::load(std::istream& in, Format format, const std::string& name, const OperandOptions& options,
                      LoadPhases* phases) {
  LoadPhases load;
  std::optional<Operand> o;
  if (options.hull) o.emplace(hinted([&] { return load_convex_set(in, format, name, true, &load); }), name);
  else o.emplace(from_any(load_any_operand(in, format, name, &load), name, load, options));
  if (phases) *phases = load;
  return std::move(*o);
}

int Operand::dimension() const {
  if (const ConvexSet* s = set()) return s->dimension();
  return 3;
}

const char* Operand::kind_name() const {
  switch (kind()) {
    case Kind::polytope: return "polytope";
    case Kind::set: return dimension_name(set()->dimension());
    case Kind::solid: return solid()->convex ? "polytope" : "solid";
  }
  return "polytope";
}

std::size_t Operand::num_vertices() const {
  if (const ConvexPolytope* p = polytope()) return p->num_vertices();
  if (const ConvexSet* s = set()) return s->num_vertices();
  return solid()->vertices;
}

std::size_t Operand::num_edges() const {
  if (const ConvexPolytope* p = polytope()) return p->num_edges();
  if (const ConvexSet* s = set()) return s->num_edges();
  // A face of k corners is k - 2 triangles with k - 3 edges inside it: the
  // triangles' 3T/2 edges less the T - F inner ones.
  const Solid& s = *solid();
  return s.triangles.faces.size() / 2 + s.faces;
}

std::size_t Operand::num_facets() const {
  if (const ConvexPolytope* p = polytope()) return p->num_facets();
  if (const ConvexSet* s = set()) return s->num_facets();
  return solid()->faces;
}

Solid Operand::to_solid() const {
  if (const ConvexPolytope* p = polytope()) return solid_of(*p);
  if (const Solid* s = solid()) return *s;
  throw std::invalid_argument("Operand::to_solid: " + name_ + " is a " + kind_name() + ", not a solid");
}

ConvexSet Operand::to_set() const {
  if (const ConvexPolytope* p = polytope()) return ConvexSet(*p);
  if (const ConvexSet* s = set()) return *s;
  throw std::invalid_argument("Operand::to_set: " + name_ + " is a solid, not a convex set");
}

}  // namespace minksum
