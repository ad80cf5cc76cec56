// Dispatch to the methods (their table: sum/shared/methods.cpp).
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

namespace minksum {

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
                       "' is not implemented in this version of minksum (available: " + method_list() + ")");
  }
}
}  // namespace

// Each method reports its own phases (and checks options.cancel) from its start.
SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b, Method method, const SumOptions& options) {
  return dispatch(a, b, method, options);
}

}  // namespace minksum
