// PointList: exact points in their cheapest exact form (point_list.hpp).
#include <minksum/point_list.hpp>

#include <atomic>
#include <bit>
#include <cfenv>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace minksum {

namespace {
// +0.0 for either zero; the value otherwise.
inline double unsigned_zero(double x) { return x == 0 ? 0.0 : x; }
inline Vec3d clean(const Vec3d& p) { return {unsigned_zero(p.x), unsigned_zero(p.y), unsigned_zero(p.z)}; }
inline bool is_zero_vec(const Vec3d& p) { return p.x == 0 && p.y == 0 && p.z == 0; }
inline Rational pair_value(double hi, double lo) {
  if (lo == 0) return Rational(hi);
  Rational r(hi);
  r += Rational(lo);
  return r;
}
inline Vec3d neg(const Vec3d& p) { return clean({-p.x, -p.y, -p.z}); }

// Error-free sum (Knuth's TwoSum): s + e = x + y exactly, s = fl(x + y), in
// round-to-nearest and when s is finite (subnormal sums are exact, e = 0).
inline void two_sum(double x, double y, double& s, double& e) {
  s = x + y;
  const double yv = s - x;
  const double xv = s - yv;
  e = (x - xv) + (y - yv);
}

// One coordinate of a point in any form: x = hi + lo + r with |r| ≤ err.
struct Split {
  double hi, lo, err;
};

// The nearest double of x = p + q from the two splits, in round-to-nearest,
// and the split of x; false when the filter cannot decide (the caller then
// computes x exactly).
//
// With TwoSum (exact: every |hi| ≤ 2^1000, so nothing overflows):
//   p.hi + q.hi = s + e,  p.lo + q.lo = t + f,  e + t = v + d,  s + v = c + g,
// so x = c + g + d + f + r_p + r_q.  Let B = |d| + |f| + p.err + q.err
// (rounded to nearest three times: the true sum is below 2B; 2B is exact).
//   * g = 0 and B = 0: x = c, a double.
//   * |x − c| ≤ |g| + B < |g| + 2B.  Half the smaller gap around c, h/2
//     (h = |c| − pred(|c|), a power of two ≥ 2^−953 for |c| ≥ 2^−900), bounds
//     the distance within which c is the unique nearest double: T = fl(|g| +
//     2B) ≤ (h/2)(1 − 2^−50) (exact product) gives |g| + 2B ≤ T(1 + 2^−53) <
//     h/2, so c is the nearest double, not a tie.
//   * |g| > 2B: x ≠ c, so x is not a double (c is its nearest).
// Otherwise undecided.  The rest x − c is then lo = fl(g + w), w = fl(d + f)
// with |x − c − lo| ≤ 2^−53 (|w| + |lo|) + (2^−1075 if subnormal) + p.err +
// q.err, bounded with a factor 2 to spare by err = 2 (p.err + q.err) +
// (|w| + |lo|) 2^−52 + 2^−1000.  Undecided with probability about
// (B / h) — 2^−50 for operands whose errors are far below their ulps.
inline bool sum_filter(const Split& p, const Split& q, Split& x) {
  if (!(std::fabs(p.hi) <= 0x1p1000 && std::fabs(q.hi) <= 0x1p1000)) return false;
  double s, e, t, f, v, d, c, g;
  two_sum(p.hi, q.hi, s, e);
  two_sum(p.lo, q.lo, t, f);
  two_sum(e, t, v, d);
  two_sum(s, v, c, g);
  const double B = ((std::fabs(d) + std::fabs(f)) + p.err) + q.err;
  if (g == 0 && B == 0) {
    x = {unsigned_zero(c), 0.0, 0.0};
    return true;
  }
  const double ac = std::fabs(c);
  if (!(ac >= 0x1p-900)) return false;
  const double h = ac - std::bit_cast<double>(std::bit_cast<std::uint64_t>(ac) - 1);
  const double ag = std::fabs(g);
  if (!(ag > 2 * B) || !(ag + 2 * B <= h * (0.5 - 0x1p-51))) return false;
  const double w = d + f;
  const double lo = g + w;
  x = {c, lo, (2 * (p.err + q.err) + (std::fabs(w) + std::fabs(lo)) * 0x1p-52) + 0x1p-1000};
  return true;
}

Split split_of(const Rational& q) {
  Split s;
  to_double_rest(q, s.hi, s.lo, s.err);
  s.hi = unsigned_zero(s.hi);
  s.lo = unsigned_zero(s.lo);
  return s;
}
}  // namespace

// The GMP points of a rationals list: stored (`points` complete), or, for a
// sum's lazy list, point i = a.point(pairs[i].first) + b.point(pairs[i].second),
// all of them made on the first exact_ref() under `once` (then `ready`).
struct PointList::Exact {
  // An operand of a sum, as much of it as its exact points need: the
  // doubles (copied), or the rationals (shared).
  struct Operand {
    Form form = Form::doubles;
    std::vector<Vec3d> hi, lo;
    std::shared_ptr<Exact> exact;

    Operand() = default;
    explicit Operand(const PointList& l) : form(l.form_) {
      if (form == Form::rationals) {
        exact = l.exact_;
        return;
      }
      hi = l.hi_;
      if (form == Form::double_pairs) lo = l.lo_;
    }
    Point3 point(std::size_t i) const {
      switch (form) {
        case Form::doubles: return Point3(hi[i].x, hi[i].y, hi[i].z);
        case Form::double_pairs:
          return Point3(pair_value(hi[i].x, lo[i].x), pair_value(hi[i].y, lo[i].y), pair_value(hi[i].z, lo[i].z));
        case Form::rationals: break;
      }
      return exact->point(i);
    }
    // Every exact point: the shared ones, or made into `own`.
    const Point3* all(std::vector<Point3>& own) const {
      if (form == Form::rationals) return exact->all().data();
      own.reserve(hi.size());
      for (std::size_t i = 0; i < hi.size(); ++i) own.push_back(point(i));
      return own.data();
    }
  };

  std::vector<Point3> points;
  bool lazy = false;  // set before the object is shared, never changed
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  Operand a, b;
  std::once_flag once;
  std::atomic<bool> ready{false};

  const std::vector<Point3>& all() {
    if (lazy) std::call_once(once, [this] { make(); });
    return points;
  }
  Point3 point(std::size_t i) {
    if (!lazy || ready.load(std::memory_order_acquire)) return points[i];
    return a.point(pairs[i].first) + b.point(pairs[i].second);
  }
  void make() {
    // Each operand's exact points once (its own storage when it holds
    // rationals), each sum made in place.
    std::vector<Point3> own_a, own_b;
    const Point3* pa = a.all(own_a);
    const Point3* pb = b.all(own_b);
    points.reserve(pairs.size());
    for (auto [i, j] : pairs) {
      Point3 s;
      for (int k = 0; k < 3; ++k) mpq_add(s[k].get_mpq_t(), pa[i][k].get_mpq_t(), pb[j][k].get_mpq_t());
      points.push_back(std::move(s));
    }
    ready.store(true, std::memory_order_release);
  }
};

PointList::PointList(std::initializer_list<Point3> points) {
  reserve(points.size());
  for (const Point3& p : points) push_back(p);
}

PointList::PointList(const std::vector<Point3>& points) {
  reserve(points.size());
  for (const Point3& p : points) push_back(p);
}

void PointList::reserve(std::size_t n) {
  hi_.reserve(n);
  if (form_ != Form::doubles) lo_.reserve(n);
  if (form_ == Form::rationals) {
    err_.reserve(n);
    if (!exact_->lazy && exact_.use_count() == 1) exact_->points.reserve(n);
  }
}

void PointList::clear() { *this = PointList(); }

bool PointList::is_double(std::size_t i) const {
  switch (form_) {
    case Form::doubles: return true;
    case Form::double_pairs: return is_zero_vec(lo_[i]);
    case Form::rationals: return is_zero_vec(lo_[i]) && is_zero_vec(err_[i]);
  }
  return false;
}

Point3 PointList::exact(std::size_t i) const {
  switch (form_) {
    case Form::doubles: return Point3(hi_[i].x, hi_[i].y, hi_[i].z);
    case Form::double_pairs:
      return Point3(pair_value(hi_[i].x, lo_[i].x), pair_value(hi_[i].y, lo_[i].y), pair_value(hi_[i].z, lo_[i].z));
    case Form::rationals: return exact_->point(i);
  }
  throw std::logic_error("PointList: bad form");
}

const Point3& PointList::exact_ref(std::size_t i) const {
  if (form_ != Form::rationals) throw std::logic_error("PointList::exact_ref: not a rationals list");
  return exact_->all()[i];
}

std::vector<Point3> PointList::to_points() const {
  if (form_ == Form::rationals) return exact_->all();
  std::vector<Point3> out;
  out.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) out.push_back(exact(i));
  return out;
}

std::vector<Point3>& PointList::own_points() {
  if (!exact_) {
    exact_ = std::make_shared<Exact>();
  } else if (exact_->lazy || exact_.use_count() > 1) {
    auto mine = std::make_shared<Exact>();
    mine->points = exact_->all();
    exact_ = std::move(mine);
  }
  return exact_->points;
}

void PointList::promote(Form to) {
  if (to <= form_) return;
  if (to == Form::double_pairs) {
    lo_.assign(hi_.size(), Vec3d{});
    lo_.reserve(hi_.capacity());
  } else {
    std::vector<Point3> ex;
    ex.reserve(hi_.capacity());
    for (std::size_t i = 0; i < hi_.size(); ++i) ex.push_back(exact(i));
    exact_ = std::make_shared<Exact>();
    exact_->points = std::move(ex);
    if (form_ == Form::doubles) lo_.assign(hi_.size(), Vec3d{});
    lo_.reserve(hi_.capacity());
    err_.assign(hi_.size(), Vec3d{});
    err_.reserve(hi_.capacity());
  }
  form_ = to;
}

void PointList::push_back(const Vec3d& p) {
  const Vec3d c = clean(p);
  hi_.push_back(c);
  if (form_ != Form::doubles) lo_.push_back(Vec3d{});
  if (form_ == Form::rationals) {
    err_.push_back(Vec3d{});
    own_points().emplace_back(c.x, c.y, c.z);
  }
}

void PointList::push_rational(const Vec3d& hi, const Vec3d& lo, const Vec3d& err, Point3&& p) {
  promote(Form::rationals);
  own_points().push_back(std::move(p));
  hi_.push_back(hi);
  lo_.push_back(lo);
  err_.push_back(err);
  ++non_double_;
}

namespace {
struct PointSplit {
  Vec3d hi, lo, err;
  bool is_double() const { return is_zero_vec(lo) && is_zero_vec(err); }
};
PointSplit split_of(const Point3& p) {
  const Split x = split_of(p.x), y = split_of(p.y), z = split_of(p.z);
  return {{x.hi, y.hi, z.hi}, {x.lo, y.lo, z.lo}, {x.err, y.err, z.err}};
}
}  // namespace

void PointList::push_back(const Point3& p) {
  const PointSplit s = split_of(p);
  if (s.is_double()) push_back(s.hi);
  else push_rational(s.hi, s.lo, s.err, Point3(p));
}

void PointList::push_back(Point3&& p) {
  const PointSplit s = split_of(p);
  if (s.is_double()) push_back(s.hi);
  else push_rational(s.hi, s.lo, s.err, std::move(p));
}

void PointList::push_pair(const Vec3d& hi, const Vec3d& lo) {
  if (is_zero_vec(lo)) {
    push_back(hi);
    return;
  }
  if (form_ == Form::doubles) promote(Form::double_pairs);
  const Vec3d h = clean(hi), l = clean(lo);
  if (form_ == Form::double_pairs) {
    hi_.push_back(h);
    lo_.push_back(l);
    ++non_double_;
    return;
  }
  push_rational(h, l, Vec3d{}, Point3(pair_value(h.x, l.x), pair_value(h.y, l.y), pair_value(h.z, l.z)));
}

void PointList::push_from(const PointList& other, std::size_t i) {
  switch (other.form_) {
    case Form::doubles: push_back(other.hi_[i]); return;
    case Form::double_pairs: push_pair(other.hi_[i], other.lo_[i]); return;
    case Form::rationals:
      if (other.is_double(i)) push_back(other.hi_[i]);
      else push_rational(other.hi_[i], other.lo_[i], other.err_[i], other.exact(i));
      return;
  }
}

void PointList::set(std::size_t i, const Point3& p) {
  const PointSplit s = split_of(p);
  const bool dbl = s.is_double();
  if (!is_double(i)) --non_double_;
  if (!dbl) {
    promote(Form::rationals);
    ++non_double_;
  }
  hi_[i] = s.hi;
  if (form_ != Form::doubles) lo_[i] = s.lo;
  if (form_ == Form::rationals) {
    err_[i] = s.err;
    own_points()[i] = dbl ? Point3(s.hi.x, s.hi.y, s.hi.z) : p;
  }
}

void PointList::negate() {
  for (auto& p : hi_) p = neg(p);
  for (auto& p : lo_) p = neg(p);
  if (form_ == Form::rationals)
    for (auto& p : own_points()) p = -p;
}

PointList PointList::sums(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs, const PointList& a,
                          const PointList& b) {
  PointList out;
  const bool nearest = std::fegetround() == FE_TONEAREST;
  const std::size_t n = pairs.size();
  if (nearest && a.all_doubles() && b.all_doubles()) {
    // Every vertex a_i + b_j as the exact pair (fl(a + b), error); a sum
    // beyond the double range: its exact rational.
    out.reserve(n);
    for (auto [i, j] : pairs) {
      const Vec3d& p = a.approx(i);
      const Vec3d& q = b.approx(j);
      Vec3d hi, lo;
      two_sum(p.x, q.x, hi.x, lo.x);
      two_sum(p.y, q.y, hi.y, lo.y);
      two_sum(p.z, q.z, hi.z, lo.z);
      if (!std::isfinite(hi.x) || !std::isfinite(hi.y) || !std::isfinite(hi.z)) out.push_back(a.exact(i) + b.exact(j));
      else out.push_pair(hi, lo);
    }
    return out;
  }
  // Rationals made on demand from the operands; here only the nearest
  // doubles and the rests, decided by sum_filter or exactly.
  out.form_ = Form::rationals;
  out.hi_.resize(n);
  out.lo_.resize(n);
  out.err_.resize(n);
  auto split = [](const PointList& l, std::size_t i, int k) -> Split {
    switch (l.form_) {
      case Form::doubles: return {l.hi_[i][k], 0.0, 0.0};
      case Form::double_pairs: return {l.hi_[i][k], l.lo_[i][k], 0.0};
      case Form::rationals: break;
    }
    return {l.hi_[i][k], l.lo_[i][k], l.err_[i][k]};
  };
  for (std::size_t m = 0; m < n; ++m) {
    const auto [i, j] = pairs[m];
    Split x[3];
    bool decided = nearest;
    for (int k = 0; k < 3 && decided; ++k) decided = sum_filter(split(a, i, k), split(b, j, k), x[k]);
    if (!decided) {
      // The exact point (rare; every one in a directed rounding mode).
      const Point3 s = a.exact(i) + b.exact(j);
      for (int k = 0; k < 3; ++k) x[k] = split_of(s[k]);
    }
    out.hi_[m] = {x[0].hi, x[1].hi, x[2].hi};
    out.lo_[m] = {x[0].lo, x[1].lo, x[2].lo};
    out.err_[m] = {x[0].err, x[1].err, x[2].err};
    if (!out.is_double(m)) ++out.non_double_;
  }
  auto e = std::make_shared<Exact>();
  e->lazy = true;
  e->pairs = pairs;
  e->a = Exact::Operand(a);
  e->b = Exact::Operand(b);
  out.exact_ = std::move(e);
  return out;
}

bool operator==(const PointList& a, const PointList& b) {
  if (a.size() != b.size()) return false;
  if (a.form_ == b.form_ && a.form_ != PointList::Form::rationals) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a.hi_[i].x != b.hi_[i].x || a.hi_[i].y != b.hi_[i].y || a.hi_[i].z != b.hi_[i].z) return false;
      if (a.form_ == PointList::Form::double_pairs &&
          (a.lo_[i].x != b.lo_[i].x || a.lo_[i].y != b.lo_[i].y || a.lo_[i].z != b.lo_[i].z))
        return false;
    }
    return true;
  }
  // The nearest doubles differ: the points differ.
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a.hi_[i].x != b.hi_[i].x || a.hi_[i].y != b.hi_[i].y || a.hi_[i].z != b.hi_[i].z) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool ra = a.form_ == PointList::Form::rationals, rb = b.form_ == PointList::Form::rationals;
    if (ra && rb ? !(a.exact_ref(i) == b.exact_ref(i)) : !(a.exact(i) == b.exact(i))) return false;
  }
  return true;
}

}  // namespace minksum
