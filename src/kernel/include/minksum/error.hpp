// minksum — the two kinds of failure a caller must tell apart.
//
// InputError: the data is bad (malformed file, NaN, open mesh, non-convex
// solid, degenerate point set...).  The CLI prints what() on one line and
// exits with status 3.  what() is "FILE: PLACE: PROBLEM" (PLACE may be empty).
//
// NotConvexError: an InputError for a closed surface that is not exactly
// convex (the CLI suggests --hull for it).
//
// UsageError: the request is bad (unknown catalog name, unknown method, bad
// option value).  The CLI exits with status 2.
//
// Cancelled: not a failure of the data or the request — the caller asked a
// running computation to stop (SumOptions::cancel in sum_result.hpp), and it
// did at its next report point.  Nothing it was computing is returned.
#pragma once

#include <stdexcept>
#include <string>

namespace minksum {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string place, std::string problem)
      : std::runtime_error(compose(file, place, problem)),
        file_(std::move(file)), place_(std::move(place)), problem_(std::move(problem)) {}

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }
  const std::string& problem() const { return problem_; }

 private:
  static std::string compose(const std::string& f, const std::string& p, const std::string& pr) {
    std::string s = f.empty() ? std::string("<input>") : f;
    if (!p.empty()) s += ": " + p;
    s += ": " + pr;
    return s;
  }
  std::string file_, place_, problem_;
};

// The data describes a closed surface that is not exactly convex (a reflex
// edge, a non-planar facet, a vertex the solid folds around): what a mesh
// rounded by another tool gives.  Taking the convex hull of the points
// (ConvexPolytope::hull, the command line's --hull) accepts such data.
class NotConvexError : public InputError {
 public:
  using InputError::InputError;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("minksum: the computation was cancelled") {}
};

}  // namespace minksum
