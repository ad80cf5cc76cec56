// PointList: exact points in their cheapest exact form (point_list.hpp).
#include <minksum/point_list.hpp>

#include <cmath>
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
}  // namespace

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
  if (form_ == Form::double_pairs) lo_.reserve(n);
  if (form_ == Form::rationals) exact_.reserve(n);
}

void PointList::clear() { *this = PointList(); }

bool PointList::is_double(std::size_t i) const {
  switch (form_) {
    case Form::doubles: return true;
    case Form::double_pairs: return is_zero_vec(lo_[i]);
    case Form::rationals: return minksum::is_double(exact_[i]);
  }
  return false;
}

Point3 PointList::exact(std::size_t i) const {
  switch (form_) {
    case Form::doubles: return Point3(hi_[i].x, hi_[i].y, hi_[i].z);
    case Form::double_pairs:
      return Point3(pair_value(hi_[i].x, lo_[i].x), pair_value(hi_[i].y, lo_[i].y), pair_value(hi_[i].z, lo_[i].z));
    case Form::rationals: return exact_[i];
  }
  throw std::logic_error("PointList: bad form");
}

std::vector<Point3> PointList::to_points() const {
  if (form_ == Form::rationals) return exact_;
  std::vector<Point3> out;
  out.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) out.push_back(exact(i));
  return out;
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
    exact_ = std::move(ex);
    lo_ = {};
  }
  form_ = to;
}

void PointList::push_back(const Vec3d& p) {
  const Vec3d c = clean(p);
  hi_.push_back(c);
  if (form_ == Form::double_pairs) lo_.push_back(Vec3d{});
  else if (form_ == Form::rationals) exact_.emplace_back(c.x, c.y, c.z);
}

void PointList::push_back(const Point3& p) {
  if (minksum::is_double(p)) {
    push_back(to_double(p));
    return;
  }
  promote(Form::rationals);
  hi_.push_back(to_double(p));
  exact_.push_back(p);
  ++non_double_;
}

void PointList::push_back(Point3&& p) {
  if (minksum::is_double(p)) {
    push_back(to_double(p));
    return;
  }
  promote(Form::rationals);
  hi_.push_back(to_double(p));
  exact_.push_back(std::move(p));
  ++non_double_;
}

void PointList::push_pair(const Vec3d& hi, const Vec3d& lo) {
  if (is_zero_vec(lo)) {
    push_back(hi);
    return;
  }
  if (form_ == Form::doubles) promote(Form::double_pairs);
  const Vec3d h = clean(hi);
  hi_.push_back(h);
  ++non_double_;
  if (form_ == Form::double_pairs) {
    lo_.push_back(clean(lo));
  } else {
    exact_.emplace_back(pair_value(h.x, lo.x), pair_value(h.y, lo.y), pair_value(h.z, lo.z));
  }
}

void PointList::push_from(const PointList& other, std::size_t i) {
  switch (other.form_) {
    case Form::doubles: push_back(other.hi_[i]); return;
    case Form::double_pairs: push_pair(other.hi_[i], other.lo_[i]); return;
    case Form::rationals: push_back(other.exact_[i]); return;
  }
}

void PointList::set(std::size_t i, const Point3& p) {
  if (!is_double(i)) --non_double_;
  if (minksum::is_double(p)) {
    const Vec3d d = clean(to_double(p));
    hi_[i] = d;
    if (form_ == Form::double_pairs) lo_[i] = Vec3d{};
    if (form_ == Form::rationals) exact_[i] = Point3(d.x, d.y, d.z);
    return;
  }
  promote(Form::rationals);
  hi_[i] = to_double(p);
  exact_[i] = p;
  ++non_double_;
}

void PointList::negate() {
  for (auto& p : hi_) p = clean({-p.x, -p.y, -p.z});
  for (auto& p : lo_) p = clean({-p.x, -p.y, -p.z});
  for (auto& p : exact_) p = -p;
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
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a.exact(i) == b.exact(i))) return false;
  return true;
}

}  // namespace minksum
