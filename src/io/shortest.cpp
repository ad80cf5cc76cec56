// put_shortest (io/readers.hpp): the text std::to_chars(first, last, d)
// gives for a double d, i.e. the shortest decimal that reads back as d
// (ties between shortest ones to the nearest of d, then to an even last
// digit), in fixed or scientific notation, whichever is shorter, fixed on a
// tie.  Exact integer arithmetic on 128 bits for 2^-9 <= |d| < 2^53, the
// range of most coordinates; std::to_chars for every other double.
//
// d = m 2^q with 2^52 <= m < 2^53.  The doubles that round to d are those
// of the interval [d - lo, d + hi] (closed when m is even: from_chars rounds
// ties to even; open when m is odd), hi = 2^(q-1), lo = hi except
// lo = 2^(q-2) when m = 2^52 (the gap below is half as large).  In units
// of 2^(q-2): d = 4m, d + hi = 4m + 2, d - lo = 4m - 2 (4m - 1).  With
// d in [10^E, 10^(E+1)) and s = 16 - E, every value x of these in units
// is scaled to x 10^s / 2^(2-q) < 10^17 · (1 + 2^-51): here
// 2 - q <= 63 and x 10^s < 2^55 · 10^19 < 2^119, so floor and remainder
// are exact in unsigned 128-bit arithmetic.  The interval holds a
// 17-digit decimal (its width is at least 0.75 ulp > 10^(E-16)); the
// fewest digits n for which it holds an n-digit decimal is found by
// dividing its integer bounds by powers of ten (ceil(ceil(x)/t) =
// ceil(x/t), and the same for floor), and the nearest such decimal to d
// is the nearest integer to d 10^(s-17+n) clamped to the bounds.
#include "io/readers.hpp"

#include <cstring>

namespace minksum::io_detail {

namespace {

using U128 = unsigned __int128;

constexpr std::uint64_t kPow10[20] = {1ULL,
                                      10ULL,
                                      100ULL,
                                      1000ULL,
                                      10000ULL,
                                      100000ULL,
                                      1000000ULL,
                                      10000000ULL,
                                      100000000ULL,
                                      1000000000ULL,
                                      10000000000ULL,
                                      100000000000ULL,
                                      1000000000000ULL,
                                      10000000000000ULL,
                                      100000000000000ULL,
                                      1000000000000000ULL,
                                      10000000000000000ULL,
                                      100000000000000000ULL,
                                      1000000000000000000ULL,
                                      10000000000000000000ULL};

// x 10^s / 2^p: its floor, and whether it is an integer.
struct Scaled {
  std::uint64_t floor;
  bool exact;
};
inline Scaled scale(std::uint64_t x, int s, int p) {
  const U128 n = U128(x) * kPow10[s];
  const U128 mask = (U128(1) << p) - 1;
  return {std::uint64_t(n >> p), (n & mask) == 0};
}

constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

}  // namespace

char* put_shortest(char* out, double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, 8);
  const int biased = int((bits >> 52) & 0x7ff);
  // 2^-9 <= |d| < 2^53: biased exponents 1014 to 1075.
  if (biased < 1023 - 9 || biased > 1023 + 52) return std::to_chars(out, out + 24, d).ptr;
  const bool negative = bits >> 63;
  const std::uint64_t m = (bits & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1) << 52);
  const int q = biased - 1075;  // d = m 2^q, -61 <= q <= 0
  const int p = 2 - q;          // units of 2^(q-2): divide by 2^p
  const bool closed = m % 2 == 0;
  const std::uint64_t hi_units = 4 * m + 2, lo_units = m == (std::uint64_t(1) << 52) ? 4 * m - 1 : 4 * m - 2;

  // E = floor(log10 d): from the binary exponent (d in [2^e2, 2^(e2+1))),
  // then corrected so that d 10^(16-E) is in [10^16, 10^17).
  const int e2 = q + 52;
  int E = (e2 * 78913) >> 18;  // floor(e2 log10 2) for |e2| < 1000: -3 <= E <= 15

  Scaled dv = scale(4 * m, 16 - E, p);
  if (dv.floor >= kPow10[17]) {
    ++E;
    dv = scale(4 * m, 16 - E, p);
  }
  const int s = 16 - E;  // 1 <= s <= 19 (E's first guess gives at most 19 too)
  // The integers of the interval at 17 digits: [a, b].
  const Scaled lv = scale(lo_units, s, p), hv = scale(hi_units, s, p);
  const std::uint64_t a = lv.exact && closed ? lv.floor : lv.floor + 1;
  const std::uint64_t b = hv.exact && !closed ? hv.floor - 1 : hv.floor;
  // The fewest digits n: drop r = 17 - n digits while an integer remains,
  // one digit at a time (divisions by the constant 10), keeping d's digits
  // F / 10^r, the last digit dropped and whether the others were all zero.
  std::uint64_t lo_c = a, hi_c = b, c = dv.floor;
  int r = 0, last = 0;
  bool rest_zero = dv.exact;  // d 10^s is an integer
  while (r < 16) {
    const std::uint64_t na = (lo_c + 9) / 10, nb = hi_c / 10;
    if (na > nb) break;
    lo_c = na;
    hi_c = nb;
    rest_zero = rest_zero && last == 0;
    last = int(c % 10);
    c /= 10;
    ++r;
  }
  // The nearest to d at that scale: up when the part dropped is above one
  // half, or exactly one half and c is odd.
  bool up;
  if (r == 0) {
    // The fraction of d 10^s itself: compare it with 1/2 exactly.
    const U128 n = U128(4 * m) * kPow10[s];
    const U128 frac = n & ((U128(1) << p) - 1), halfp = U128(1) << (p - 1);
    up = frac > halfp || (frac == halfp && c % 2 == 1);
  } else {
    up = last > 5 || (last == 5 && (!rest_zero || c % 2 == 1));
  }
  if (up) ++c;
  if (c < lo_c) c = lo_c;
  if (c > hi_c) c = hi_c;
  // c 10^(r-s) = the value, of 17 - r digits (18 - r when rounding up
  // carried into a new digit); strip trailing zeros.
  int scale10 = s - r;
  int nd = 17 - r + (c >= kPow10[17 - r]);
  while (c % 10 == 0) {
    c /= 10;
    --scale10;
    --nd;
  }
  char digits[20];
  for (int i = nd; i > 1; i -= 2) {  // two digits at a time
    const char* two = kDigitPairs + 2 * (c % 100);
    digits[i - 2] = two[0];
    digits[i - 1] = two[1];
    c /= 100;
  }
  if (nd % 2) digits[0] = char('0' + c);
  const int exp10 = nd - 1 - scale10;  // the value is d.ddd 10^exp10
  const int sci_len = nd + (nd > 1) + 2 + (exp10 >= 100 || exp10 <= -100 ? 3 : 2);
  const int fixed_len = exp10 >= 0 ? (nd <= exp10 + 1 ? exp10 + 1 : nd + 1) : 2 + (-exp10 - 1) + nd;
  char* o = out;
  if (negative) *o++ = '-';
  if (fixed_len <= sci_len) {
    if (exp10 >= 0) {
      for (int i = 0; i <= exp10; ++i) *o++ = i < nd ? digits[i] : '0';
      if (nd > exp10 + 1) {
        *o++ = '.';
        for (int i = exp10 + 1; i < nd; ++i) *o++ = digits[i];
      }
    } else {
      *o++ = '0';
      *o++ = '.';
      for (int i = 0; i < -exp10 - 1; ++i) *o++ = '0';
      for (int i = 0; i < nd; ++i) *o++ = digits[i];
    }
    return o;
  }
  *o++ = digits[0];
  if (nd > 1) {
    *o++ = '.';
    for (int i = 1; i < nd; ++i) *o++ = digits[i];
  }
  *o++ = 'e';
  int e = exp10;
  *o++ = e < 0 ? '-' : '+';
  if (e < 0) e = -e;
  if (e >= 100) *o++ = char('0' + e / 100);
  *o++ = char('0' + e / 10 % 10);
  *o++ = char('0' + e % 10);
  return o;
}

}  // namespace minksum::io_detail
