// One sum over a sequence of operands of any kind (<minksum/sum.hpp>): the
// choice between the convex, the lower-dimensional and the non-convex
// engines, and the one report of what was computed.
#include <minksum/error.hpp>
#include <minksum/sum.hpp>

#include <map>
#include <optional>
#include <stdexcept>

namespace minksum {

namespace {

OperandReport operand_report(const Operand& o) {
  return {o.name(), o.dimension(), o.kind_name(), o.num_vertices(), o.num_edges(), o.num_facets()};
}

// The facets by origin, and the method's facet cases, counted.
void convex_details(const SumResult& r, SumReport& report) {
  if (!r.facet_provenance.empty()) {
    constexpr FacetOrigin kinds[] = {FacetOrigin::translated, FacetOrigin::corner, FacetOrigin::edge,
                                     FacetOrigin::facet_edge, FacetOrigin::facet_facet};
    std::map<FacetOrigin, long long> count;
    for (const auto& p : r.facet_provenance) ++count[p.origin()];
    for (FacetOrigin k : kinds) report.facet_types.emplace_back(facet_origin_name(k), count[k]);
  }
  if (!r.facet_case.empty()) {
    std::vector<long long> count(r.facet_case_names.size(), 0);
    for (auto c : r.facet_case) ++count.at(c);
    for (std::size_t i = 0; i < count.size(); ++i) report.facet_cases.emplace_back(r.facet_case_names[i], count[i]);
  }
  report.counters = r.counters;
}

OperandSum convex_sum(const std::vector<Operand>& operands, const SumRequest& request) {
  OperandSum out;
  SumResult r;
  double seconds = 0, explicit_seconds = 0;
  for (std::size_t i = 1; i < operands.size(); ++i) {
    r = minkowski_sum(i == 1 ? *operands[0].polytope() : r.polytope, *operands[i].polytope(), request.method,
                      request.options);
    seconds += r.seconds;
    explicit_seconds += r.explicit_seconds;
  }
  SumReport& report = out.report;
  const ConvexPolytope& s = r.polytope;
  report.vertices = s.num_vertices();
  report.edges = s.num_edges();
  report.facets = s.num_facets();
  report.method = method_name(r.method);
  report.seconds = seconds;
  report.phases = {{"sum", seconds - explicit_seconds}, {"explicit", explicit_seconds}};
  // The exact volume by mixed volumes from the two operands (sum_volume), a
  // fraction of what the sum's own triangles cost; of more, from the sum.
  if (request.options.volume)
    report.volume = operands.size() == 2 ? sum_volume(*operands[0].polytope(), *operands[1].polytope(), r)
                                         : s.volume();
  // The method's details are those of a sum of two operands only (of more,
  // they would be the last step's).
  if (operands.size() == 2) convex_details(r, report);
  if (!request.provenance) {
    decltype(r.facet_provenance)().swap(r.facet_provenance);
    decltype(r.vertex_origin)().swap(r.vertex_origin);
  }
  out.result = std::move(r);
  return out;
}

OperandSum set_sum(const std::vector<Operand>& operands, const SumRequest& request) {
  OperandSum out;
  SetSumResult r;
  double seconds = 0;
  for (std::size_t i = 1; i < operands.size(); ++i) {
    r = minkowski_sum_sets(i == 1 ? operands[0].to_set() : r.set, operands[i].to_set(), request.method,
                           request.options);
    seconds += r.seconds;
  }
  SumReport& report = out.report;
  const ConvexSet& s = r.set;
  report.dimension = s.dimension();
  report.kind = s.full() ? "polytope" : dimension_name(s.dimension());
  report.vertices = s.num_vertices();
  report.edges = s.num_edges();
  report.facets = s.num_facets();
  report.method = method_name(r.method);
  report.route = r.route;
  report.seconds = seconds;
  report.phases = {{"sum", seconds}, {"explicit", 0.0}};
  if (request.options.volume) report.volume = s.volume();
  if (s.full()) {  // a polytope, as a convex sum gives it (no provenance)
    SumResult p;
    p.method = r.method;
    p.seconds = seconds;
    p.polytope = std::move(r.set).release_polytope();
    out.result = std::move(p);
  } else {
    out.result = std::move(r);
  }
  return out;
}

OperandSum solid_sum(const std::vector<Operand>& operands, const SumRequest& request) {
  static const char* const kCommand[] = {"sum", "erode", "open", "close"};
  const char* command = kCommand[int(request.operation)];
  if (operands.size() != 2) {
    if (request.operation != SumOperation::sum)
      throw UsageError(std::string("'") + command + "' takes exactly two operands A B (" +
                       std::to_string(operands.size()) + " given)");
    throw UsageError("a sum with a non-convex operand takes exactly two operands A B (" +
                     std::to_string(operands.size()) + " given)");
  }
  for (const Operand& o : operands)
    if (o.set()) {
      if (request.operation != SumOperation::sum)
        throw UsageError(std::string("'") + command + "' takes solids: '" + o.name() +
                         "' is a point, a segment or a flat polygon");
      throw UsageError("a point, segment or polygon operand is summed with convex operands only, not with a "
                       "non-convex solid (docs/sweeps.md)");
    }
  if (request.operation != SumOperation::sum && !operands[1].polytope() && !operands[1].solid()->convex)
    throw InputError(operands[1].name(), "", std::string("is not convex: 'minksum ") + command +
                                                 "' takes a convex polytope B (a solid A of any shape)");
  // The operands as solids: a solid operand's own (not copied), a convex
  // polytope's made here without its volume (the sums do not read it).
  std::optional<Solid> made[2];
  auto solid = [&](int k) -> const Solid& {
    if (const Solid* s = operands[k].solid()) return *s;
    return made[k].emplace(solid_of(*operands[k].polytope(), false));
  };
  const Solid& a = solid(0);
  const Solid& b = solid(1);
  const Method m = request.method == Method::automatic ? Method::walk : request.method;
  OperandSum out;
  NonconvexSum r;
  switch (request.operation) {
    case SumOperation::sum:
      r = minkowski_sum_nonconvex(a, b, request.options, request.threads, m, request.nonconvex);
      break;
    case SumOperation::erode: r = erode(a, b, request.options, request.threads, m); break;
    case SumOperation::open: r = opening(a, b, request.options, request.threads, m); break;
    case SumOperation::close: r = closing(a, b, request.options, request.threads, m); break;
  }
  SumReport& report = out.report;
  report.operation = r.operation;
  report.kind = "solid";
  report.vertices = r.mesh.points.size();
  report.facets = r.mesh.faces.size();
  std::size_t corners = 0;
  for (const auto& f : r.mesh.faces) corners += f.size();
  report.edges = corners / 2;  // every edge has as many faces on each side
  report.empty = r.mesh.faces.empty();
  report.method = "nonconvex";
  report.seconds = r.seconds();
  report.phases = {{"decompose", r.seconds_decompose},
                   {"pairs", r.seconds_pairs},
                   {"union", r.seconds_union},
                   {"boundary", r.seconds_boundary}};
  if (request.options.volume) report.volume = r.volume;
  Mesh mesh = std::move(r.mesh);
  r.mesh = Mesh{};
  report.nonconvex = r;  // the work, without the mesh
  r.mesh = std::move(mesh);
  out.result = std::move(r);
  return out;
}

}  // namespace

const ConvexPolytope* OperandSum::polytope() const {
  if (const SumResult* r = std::get_if<SumResult>(&result)) return &r->polytope;
  return nullptr;
}

const ConvexSet* OperandSum::set() const {
  if (const SetSumResult* r = std::get_if<SetSumResult>(&result)) return &r->set;
  return nullptr;
}

const Mesh* OperandSum::solid() const {
  if (const NonconvexSum* r = std::get_if<NonconvexSum>(&result)) return &r->mesh;
  return nullptr;
}

OperandSum minkowski_sum(const std::vector<Operand>& operands, const SumRequest& request) {
  if (operands.size() < 2) throw std::invalid_argument("minkowski_sum: two or more operands are needed");
  bool solid = request.operation != SumOperation::sum, lower = false;
  for (const Operand& o : operands) {
    solid = solid || o.solid();
    lower = lower || o.set();
  }
  OperandSum out = solid   ? solid_sum(operands, request)
                   : lower ? set_sum(operands, request)
                           : convex_sum(operands, request);
  for (const Operand& o : operands) out.report.operands.push_back(operand_report(o));
  return out;
}

Rational result_volume(const OperandSum& sum) {
  if (const ConvexPolytope* p = sum.polytope()) return p->volume();
  if (const ConvexSet* s = sum.set()) return s->volume();
  const Mesh& m = *sum.solid();
  return m.faces.empty() ? Rational(0) : mesh_volume(m);
}

}  // namespace minksum
