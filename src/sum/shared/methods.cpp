// The table of methods: names, availability and the summaries --help prints.
#include <minksum/sum_result.hpp>

namespace minksum {

namespace {
constexpr MethodInfo kMethods[] = {
    {Method::automatic, "auto", "the default: walk, which is exact on every input and output-sensitive."},
    {Method::walk, "walk",
     "output-sensitive: walks along the Gaussian arcs of each operand's edges over the other's Gaussian map, "
     "building the result directly; cost grows with input + output.  --json adds its counters (crossings, steps, "
     "predicates, microseconds of the walk and of the conversion to exact coordinates)."},
    {Method::chms, "chms", "exact convex hull of all pairwise vertex sums, the reference oracle."},
    {Method::cvms, "cvms",
     "contributing vertices (Barki et al.); --json reports the facet types (translated, corner, edge, "
     "facet_edge, facet_facet)."},
    {Method::essdms, "essdms",
     "slope diagrams merged without embedding, contributing vertices instead of point-in-polygon queries "
     "(Barki et al.); --json reports the intersection case per facet and operation counts."},
    {Method::mssd, "mssd",
     "Wu et al.'s improved 3D-MSSD: the same merge with point-in-polygon queries and all edge-arc pairs; "
     "--json reports the intersection case per facet and operation counts."},
    {Method::cgm, "cgm",
     "overlay of the six pairs of planar maps of the Cubical Gaussian Maps (Fogel & Halperin); --json reports "
     "the overlay cases met."},
};
}  // namespace

std::span<const MethodInfo> methods() { return kMethods; }

const char* method_name(Method m) {
  for (const auto& i : kMethods)
    if (i.method == m) return i.name;
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  for (const auto& i : kMethods)
    if (name == i.name) return i.method;
  return std::nullopt;
}

bool method_available(Method m) {
  for (const auto& i : kMethods)
    if (i.method == m) return true;
  return false;
}

std::string method_list() {
  std::string out;
  for (const auto& i : kMethods) {
    if (!out.empty()) out += ", ";
    out += i.name;
  }
  return out;
}

const char* facet_origin_name(FacetOrigin o) {
  switch (o) {
    case FacetOrigin::translated: return "translated";
    case FacetOrigin::corner: return "corner";
    case FacetOrigin::edge: return "edge";
    case FacetOrigin::facet_edge: return "facet_edge";
    case FacetOrigin::facet_facet: return "facet_facet";
  }
  return "?";
}

}  // namespace minksum
