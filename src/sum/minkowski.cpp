// Dispatch to the methods (their table: sum/shared/methods.cpp).
#include <minksum/error.hpp>
#include <minksum/minkowski.hpp>

namespace minksum {

Method automatic_choice(const ConvexPolytope&, const ConvexPolytope&) {
  // walk is output-sensitive and exact on every input (docs/walk.md).
  return Method::walk;
}

namespace {
SumResult dispatch(const ConvexPolytope& a, const ConvexPolytope& b, Method method) {
  switch (method) {
    case Method::automatic:
      return dispatch(a, b, automatic_choice(a, b));
    case Method::walk:
      return minkowski_sum_walk(a, b);
    case Method::chms:
      return minkowski_sum_chms(a, b);
    case Method::cvms:
      return minkowski_sum_cvms(a, b);
    case Method::essdms:
      return minkowski_sum_essdms(a, b);
    case Method::mssd:
      return minkowski_sum_mssd(a, b);
    case Method::cgm:
      return minkowski_sum_cgm(a, b);
    default:
      throw UsageError(std::string("method '") + method_name(method) +
                       "' is not implemented in this version of minksum (available: " + method_list() + ")");
  }
}

// Clears the progress report however the method ends.
struct ProgressScope {
  explicit ProgressScope(Method m) { report_sum_progress(method_name(m), -1); }
  ~ProgressScope() { report_sum_progress(nullptr, -1); }
};
}  // namespace

SumResult minkowski_sum(const ConvexPolytope& a, const ConvexPolytope& b, Method method) {
  ProgressScope scope(method == Method::automatic ? automatic_choice(a, b) : method);
  return dispatch(a, b, method);
}

}  // namespace minksum
