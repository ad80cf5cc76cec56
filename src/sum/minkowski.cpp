// Method names and dispatch.
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

namespace minksum {

namespace {
struct MethodInfo {
  Method method;
  const char* name;
};
constexpr MethodInfo kMethods[] = {
    {Method::automatic, "auto"}, {Method::walk, "walk"}, {Method::cvms, "cvms"},
    {Method::essdms, "essdms"},  {Method::mssd, "mssd"}, {Method::chms, "chms"},
    {Method::cgm, "cgm"},
};
}  // namespace

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
  return m == Method::walk || m == Method::chms || m == Method::cvms || m == Method::essdms || m == Method::mssd ||
         m == Method::cgm || m == Method::automatic;
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

Method automatic_choice(const ConvexPolytope&, const ConvexPolytope&) {
  // walk is output-sensitive and exact on every input (docs/walk.md).
  return Method::walk;
}

namespace {
SumResult dispatch(const ConvexPolytope& a, const ConvexPolytope& b, Method method, const SumOptions& options) {
  switch (method) {
    case Method::automatic:
      return dispatch(a, b, automatic_choice(a, b), options);
    case Method::walk:
      return minkowski_sum_walk(a, b, options);
    case Method::chms:
      return minkowski_sum_chms(a, b, options);
    case Method::cvms:
      return minkowski_sum_cvms(a, b, options);
    case Method::essdms:
      return minkowski_sum_essdms(a, b, options);
    case Method::mssd:
      return minkowski_sum_mssd(a, b, options);
    case Method::cgm:
      return minkowski_sum_cgm(a, b, options);
    default:
      throw UsageError(std::string("method '") + method_name(method) +
                       "' is not implemented in this version of minksum (available: auto, walk, chms, cvms, essdms, mssd, cgm)");
  }
}
}  // namespace

// Each method reports its own phases (and checks options.cancel) from its start.
SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b, Method method, const SumOptions& options) {
  return dispatch(a, b, method, options);
}

}  // namespace minksum
