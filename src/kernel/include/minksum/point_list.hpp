// minksum — a list of exact points, each stored in its cheapest exact form.
//
// Exactness costs nothing until it is needed.  A PointList holds the exact
// coordinates of a sequence of points in one of three forms, chosen by the
// data (the cheapest one that holds every point exactly):
//
//   * doubles:      every coordinate is a finite double; approx(i) IS the
//                   exact point.  What every double-coordinate file, STL or
//                   PLY float body and most catalog solids give.
//   * double_pairs: every coordinate is the exact sum hi + lo of two doubles
//                   with hi = the nearest double of the sum (round to
//                   nearest, ties to even) and |lo| ≤ half an ulp of hi; the
//                   form of a Minkowski sum of two double polytopes (each
//                   vertex is a_i + b_j, split by the error-free TwoSum).
//   * rationals:    exact rationals (p/q tokens, exact rotations, sums with
//                   a rational operand); approx(i) is the nearest double, and
//                   beside it a second double low(i) and a bound
//                   low_error(i) with |exact − approx − low| ≤ low_error
//                   coordinate-wise (low_error 0: the pair is exact).  The GMP
//                   rationals are either stored, or — for a Minkowski sum
//                   made by sums() — computed on demand from the two operand
//                   lists (shared, never copied): exact(i) adds two operand
//                   points, exact_ref(i) builds every point once (thread-safe)
//                   and keeps them.
//
// Costs: approx(i), low(i), low_error(i), form(), is_double(i) and
// all_doubles() are O(1) and never allocate.  exact(i) (and operator[],
// iteration) builds a Point3: three GMP rationals, i.e. heap allocations —
// use it for exact fallbacks and output, not in loops over every point.
// exact_ref(i) is free for stored rationals; on a sum's lazy list the first
// call builds all of them (one GMP addition per coordinate).  Appending a
// point that is not representable in the current form converts the whole
// list once to the next form (doubles → double_pairs → rationals).  Copies
// share the rationals (a list that is changed gets its own first).
//
// Zeros are stored as +0.0 (an exact coordinate has no sign of zero), so two
// equal points have equal bits in every form.
#pragma once

#include <minksum/kernel.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <utility>
#include <vector>

namespace minksum {

class PointList {
 public:
  enum class Form : std::uint8_t { doubles, double_pairs, rationals };

  PointList() = default;
  PointList(std::initializer_list<Point3> points);
  explicit PointList(const std::vector<Point3>& points);

  std::size_t size() const { return hi_.size(); }
  bool empty() const { return hi_.empty(); }
  Form form() const { return form_; }
  void reserve(std::size_t n);
  void clear();

  // The nearest doubles of point i's coordinates (exact in the doubles form).
  const Vec3d& approx(std::size_t i) const { return hi_[i]; }
  const std::vector<Vec3d>& approx() const { return hi_; }
  // double_pairs: exact point = approx(i) + low(i), coordinate-wise.
  // rationals: |exact − approx(i) − low(i)| ≤ low_error(i), coordinate-wise
  // (a finite or infinite double ≥ 0; 0 when approx + low is exact).  A
  // coordinate is exactly a double iff its low and low_error are both 0.
  const Vec3d& low(std::size_t i) const { return lo_[i]; }
  const Vec3d& low_error(std::size_t i) const { return err_[i]; }
  // True when point i's three coordinates are exactly doubles (then
  // approx(i) is exact, whatever the form).
  bool is_double(std::size_t i) const;
  // True when every point is exactly a double point.
  bool all_doubles() const { return non_double_ == 0; }

  // The exact point (allocates three GMP rationals).
  Point3 exact(std::size_t i) const;
  Point3 operator[](std::size_t i) const { return exact(i); }
  // Rationals form only: the exact point, kept by the list (a sum's lazy
  // list builds all of its points on the first call, once, thread-safe).
  const Point3& exact_ref(std::size_t i) const;
  // Every exact point (allocates).
  std::vector<Point3> to_points() const;

  // Append an exact point.
  void push_back(const Vec3d& p);   // doubles that ARE the coordinates (finite)
  void push_back(const Point3& p);  // any exact point; kept as doubles when it is one
  void push_back(Point3&& p);
  // The exact point hi + lo; precondition: hi is the nearest double of
  // hi + lo in each coordinate (as TwoSum gives), all finite.
  void push_pair(const Vec3d& hi, const Vec3d& lo);
  // Append point i of `other` (in its own form, no rounding).
  void push_from(const PointList& other, std::size_t i);

  // The exact points a_i + b_j for the given index pairs, in the cheapest
  // exact form, without a GMP operation per point:
  //   * both lists doubles (and the FPU rounding to nearest): double pairs,
  //     each coordinate split by TwoSum (a sum beyond the double range is
  //     kept as a rational);
  //   * otherwise rationals computed on demand from a and b (which the
  //     result shares), with approx(i) the nearest double decided from the
  //     operands' (approx, low, low_error) triples by a filter with a
  //     derived bound (point_list.cpp), and from exact GMP sums where it
  //     cannot decide (near a tie, near the ends of the double range, in a
  //     rounding mode other than to-nearest).
  static PointList sums(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, const PointList& a,
                        const PointList& b);
  template <class... A>
  void emplace_back(A&&... a) {
    push_back(Point3(std::forward<A>(a)...));
  }
  // Replace point i.
  void set(std::size_t i, const Point3& p);
  // Replace every point p by f(p), exactly (f takes and returns a Point3).
  template <class F>
  void transform(F f) {
    PointList out;
    out.reserve(size());
    for (std::size_t i = 0; i < size(); ++i) out.push_back(f(exact(i)));
    *this = std::move(out);
  }
  // Every point negated (-p), exactly, keeping the form.
  void negate();

  // Iteration yields exact points by value (allocates; see above).
  class const_iterator {
   public:
    using value_type = Point3;
    using difference_type = std::ptrdiff_t;
    const_iterator(const PointList* l, std::size_t i) : l_(l), i_(i) {}
    Point3 operator*() const { return l_->exact(i_); }
    const_iterator& operator++() {
      ++i_;
      return *this;
    }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }
    bool operator!=(const const_iterator& o) const { return i_ != o.i_; }

   private:
    const PointList* l_;
    std::size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }

  // Exact equality of the point sequences (whatever the forms).
  friend bool operator==(const PointList& a, const PointList& b);

 private:
  struct Exact;  // rationals: the GMP points, stored or made on demand (point_list.cpp)

  void promote(Form to);
  std::vector<Point3>& own_points();  // rationals: the stored points, unshared, to change
  void push_rational(const Vec3d& hi, const Vec3d& lo, const Vec3d& err, Point3&& p);

  Form form_ = Form::doubles;
  std::vector<Vec3d> hi_;     // nearest doubles (all forms)
  std::vector<Vec3d> lo_;     // double_pairs: the low parts; rationals: the next doubles
  std::vector<Vec3d> err_;    // rationals: bounds on |exact − hi − lo|
  std::shared_ptr<Exact> exact_;  // rationals: the exact points
  std::size_t non_double_ = 0;
};

}  // namespace minksum
