// Welding points by their exact coordinates (mesh/weld.hpp).
#include "mesh/weld.hpp"
#include "kernel/big_array.hpp"

#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace minksum {

namespace {

inline std::uint64_t mix64(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

inline std::uint64_t bits(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, 8);
  return b;
}

}  // namespace

std::vector<Index> weld_exact(const PointList& mp, const std::vector<char>* used) {
  const Index n_in = Index(mp.size());
  std::vector<Index> canon = big_array(n_in, kNoIndex);
  auto is_used = [&](Index v) { return !used || (*used)[v]; };
  if (mp.form() == PointList::Form::rationals) {
    std::unordered_map<Point3, Index, Point3Hash> first;
    first.reserve(n_in);
    for (Index v = 0; v < n_in; ++v)
      if (is_used(v)) canon[v] = first.try_emplace(mp.exact_ref(v), v).first->second;
    return canon;
  }
  // Open addressing on the coordinates' bits (hash, then exact compare).
  const bool pairs = mp.form() == PointList::Form::double_pairs;
  auto hash = [&](Index v) {
    const Vec3d& a = mp.approx(v);
    std::uint64_t h = mix64(bits(a.x)) ^ (mix64(bits(a.y) + 0x9e3779b97f4a7c15ULL) * 3) ^
                      (mix64(bits(a.z) + 0x3c6ef372fe94f82aULL) * 7);
    if (pairs) {
      const Vec3d& l = mp.low(v);
      h ^= mix64(bits(l.x) ^ (bits(l.y) << 1) ^ (bits(l.z) << 2));
    }
    return h;
  };
  auto same = [&](Index u, Index v) {
    const Vec3d &a = mp.approx(u), &b = mp.approx(v);
    if (a.x != b.x || a.y != b.y || a.z != b.z) return false;
    if (!pairs) return true;
    const Vec3d &c = mp.low(u), &d = mp.low(v);
    return c.x == d.x && c.y == d.y && c.z == d.z;
  };
  std::size_t n = 16;
  while (n < 2 * std::size_t(n_in) + 2) n *= 2;
  std::vector<Index> slot = big_array(n, kNoIndex);
  for (Index v = 0; v < n_in; ++v) {
    if (!is_used(v)) continue;
    for (std::size_t i = hash(v) & (n - 1);; i = (i + 1) & (n - 1)) {
      if (slot[i] == kNoIndex) {
        slot[i] = v;
        canon[v] = v;
        break;
      }
      if (same(slot[i], v)) {
        canon[v] = slot[i];
        break;
      }
    }
  }
  return canon;
}

Welded welded(const PointList& points, const std::vector<Index>& canon) {
  Welded w;
  w.id.assign(canon.size(), kNoIndex);
  for (Index v = 0; v < canon.size(); ++v)
    if (canon[v] == v) {
      w.id[v] = Index(w.points.size());
      w.points.push_from(points, v);
    } else if (canon[v] != kNoIndex) {
      w.id[v] = w.id[canon[v]];
    }
  return w;
}

}  // namespace minksum
