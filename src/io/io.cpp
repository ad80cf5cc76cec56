// Format dispatch, whole-file reading, atomic writing (operands named on the
// command line are resolved in src/operand/operand.cpp),
// and the helpers the per-format readers and writers share.
#include "io/readers.hpp"

#include <minksum/io.hpp>
#include <minksum/scene.hpp>

#include <cfenv>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <istream>
#include <iterator>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <streambuf>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace minksum {

namespace io_detail {

std::string line_place(std::size_t line) { return "line " + std::to_string(line); }

std::string quote(std::string_view token) {
  static const char* hex = "0123456789abcdef";
  std::string s = "'";
  std::size_t shown = 0;
  for (char ch : token) {
    if (shown == 40) {
      s += "...";
      break;
    }
    auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      s += ch;
    } else {
      s += "\\x";
      s += hex[c >> 4];
      s += hex[c & 15];
    }
    ++shown;
  }
  s += "'";
  return s;
}

static Rational parse_coordinate_exact(std::string_view token, const std::string& name, const std::string& place);

Coordinate read_coordinate(std::string_view token, const std::string& name, const std::string& place) {
  // Fast paths, no allocation: a plain decimal token ("-0.125", "1e-3") is
  // the nearest double by from_chars (correctly rounded, as strtod), which is
  // what parse_number means by a decimal token; an integer of at most 15
  // digits is exactly a double.  p/q, longer integers, hexadecimal and
  // anything unusual go through parse_number.
  if (!token.empty() && token.size() < 64) {
    bool decimal = false, plain = true;
    for (std::size_t i = 0; i < token.size() && plain; ++i) {
      char c = token[i];
      if (c == '.' || c == 'e' || c == 'E') decimal = true;
      else if (!((c >= '0' && c <= '9') || ((c == '-' || c == '+') && (i == 0 || token[i - 1] == 'e' || token[i - 1] == 'E'))))
        plain = false;
    }
    std::string_view t = token;
    if (plain && t[0] == '+') t.remove_prefix(1);
    if (decimal && plain && !t.empty()) {
      double d = 0;
      auto r = std::from_chars(t.data(), t.data() + t.size(), d);
      if (r.ec == std::errc() && r.ptr == t.data() + t.size() && std::isfinite(d) &&
          (d != 0 || t.find_first_of("123456789") == std::string_view::npos || t.find_first_of("eE") == std::string_view::npos))
        return {d, std::nullopt};
    } else if (plain && !t.empty() && t.size() <= 16) {
      long long n = 0;
      auto r = std::from_chars(t.data(), t.data() + t.size(), n);
      if (r.ec == std::errc() && r.ptr == t.data() + t.size() && n < 1000000000000000LL && n > -1000000000000000LL)
        return {double(n), std::nullopt};
    }
  }
  Rational q = parse_coordinate_exact(token, name, place);
  if (is_double(q)) return {to_double(q), std::nullopt};
  return {0.0, std::move(q)};
}

Coordinate read_coordinate(std::string_view token, const std::string& name, std::size_t line) {
  // The common case without making the place text: a token that from_chars
  // reads whole as a finite double, starting like a number (so not "inf" or
  // "nan"; "0x..." stops at the x).  A token with no '.', 'e' or 'E' is an
  // integer, exact only up to 15 digits here: longer ones take the exact path.
  if (!token.empty()) {
    const char c0 = token[0];
    if ((c0 >= '0' && c0 <= '9') || c0 == '-' || c0 == '.') {
      double d = 0;
      const char* end = token.data() + token.size();
      auto r = std::from_chars(token.data(), end, d);
      if (r.ec == std::errc() && r.ptr == end && std::isfinite(d) &&
          (token.size() - (c0 == '-') <= 15 || token.find_first_of(".eE") != std::string_view::npos))
        return {d, std::nullopt};
    }
  }
  return read_coordinate(token, name, line_place(line));
}

Rational parse_coordinate(std::string_view token, const std::string& name, const std::string& place) {
  Coordinate c = read_coordinate(token, name, place);
  return c.exact ? std::move(*c.exact) : Rational(c.d);
}

void push_point(PointList& points, Coordinate (&c)[3]) {
  if (!c[0].exact && !c[1].exact && !c[2].exact) {
    points.push_back(Vec3d{c[0].d, c[1].d, c[2].d});
    return;
  }
  auto value = [](Coordinate& x) { return x.exact ? std::move(*x.exact) : Rational(x.d); };
  points.push_back(Point3(value(c[0]), value(c[1]), value(c[2])));
}

static Rational parse_coordinate_exact(std::string_view token, const std::string& name, const std::string& place) {
  std::string why;
  if (auto q = parse_number(token, &why)) return std::move(*q);
  if (why == "NaN") throw InputError(name, place, "coordinate is NaN");
  if (why == "infinite") throw InputError(name, place, "coordinate is infinite");
  if (why == "zero denominator")
    throw InputError(name, place, "coordinate " + quote(token) + " has a zero denominator");
  if (why == "out of double range")
    throw InputError(name, place, "coordinate " + quote(token) + " is out of double range");
  throw InputError(name, place, "expected a number, got " + quote(token));
}

std::optional<std::uint64_t> parse_unsigned(std::string_view t) {
  if (t.empty() || t[0] < '0' || t[0] > '9') return std::nullopt;
  std::uint64_t v = 0;
  auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) return std::nullopt;
  return v;
}

std::optional<std::int64_t> parse_signed(std::string_view t) {
  if (!t.empty() && t[0] == '+') t.remove_prefix(1);
  if (t.empty()) return std::nullopt;
  std::int64_t v = 0;
  auto r = std::from_chars(t.data(), t.data() + t.size(), v);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) return std::nullopt;
  return v;
}

bool looks_numeric(std::string_view t) {
  if (t.empty() || t.size() > 400) return false;
  std::string s(t);
  char* end = nullptr;
  (void)std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

namespace {
long binary_magnitude(const Rational& q) {
  return long(mpz_sizeinbase(q.get_num_mpz_t(), 2)) - long(mpz_sizeinbase(q.get_den_mpz_t(), 2));
}
}  // namespace

double checked_double(const Rational& q) {
  double d = to_double(q);
  if (!std::isfinite(d))
    throw UnrepresentableError(
        "a coordinate of magnitude about 2^" + std::to_string(binary_magnitude(q)) + " does not fit in a double",
        false);
  return d;
}

float checked_float(const Rational& q) {
  const float f = to_float(q);
  if (std::isinf(f)) {
    // Beyond the doubles too: the double's error, whose remedy is exact output.
    if (!std::isfinite(to_double(q))) checked_double(q);
    throw UnrepresentableError("a coordinate of magnitude about 2^" + std::to_string(binary_magnitude(q)) +
                                   " does not fit in the 32-bit floats of binary STL",
                               true);
  }
  return f;
}

double coordinate_double(const PointList& points, std::size_t i, int k) {
  if (points.form() != PointList::Form::rationals) return points.approx(i)[k];  // finite by construction
  const double d = points.approx(i)[k];
  if (std::isfinite(d)) return d;
  return checked_double(points.exact_ref(i)[k]);  // throws the range error
}

namespace {
// Nearest float of a finite double: one conversion when the rounding mode is
// to nearest (it rounds in the current mode), else the exact rounding of
// checked_float, which also gives the range error beyond the floats.
float double_to_float(double d) {
  if (std::fegetround() == FE_TONEAREST) {
    const float f = static_cast<float>(d);
    if (std::isfinite(f)) return f;
  }
  return checked_float(Rational(d));
}
}  // namespace

float coordinate_float(const PointList& points, std::size_t i, int k) {
  switch (points.form()) {
    case PointList::Form::rationals: return checked_float(points.exact_ref(i)[k]);
    case PointList::Form::doubles: return double_to_float(points.approx(i)[k]);
    case PointList::Form::double_pairs: break;
  }
  const double hi = points.approx(i)[k], lo = points.low(i)[k];
  if (lo == 0) return double_to_float(hi);
  // Nearest float of hi + lo: |lo| is at most half an ulp of hi, far below
  // half an ulp of a float, so it only matters when hi lies exactly halfway
  // between two floats (such midpoints are doubles): then lo's sign breaks
  // the tie.  Otherwise the nearest float of hi is the answer.
  const float f = double_to_float(hi);  // range errors as usual
  const double df = f;
  if (df == hi) return f;
  const float g = std::nextafter(f, hi > df ? std::numeric_limits<float>::infinity()
                                             : -std::numeric_limits<float>::infinity());
  if (std::isfinite(g) && (df + double(g)) / 2 == hi) return (lo > 0) == (double(g) > df) ? g : f;
  return f;
}

void append_coordinate(std::string& out, const PointList& points, std::size_t i, int k, bool exact) {
  if (!exact) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, coordinate_double(points, i, k));
    out.append(buf, r.ptr);
    return;
  }
  switch (points.form()) {
    case PointList::Form::doubles: append_exact_dyadic(out, points.approx(i)[k]); return;
    case PointList::Form::double_pairs: append_exact_dyadic(out, points.approx(i)[k], points.low(i)[k]); return;
    case PointList::Form::rationals: out += format_exact(points.exact_ref(i)[k]); return;
  }
}

void append_index(std::string& out, std::uint64_t v) {
  char buf[24];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void write_point_lines(std::ostream& out, const PointList& points, bool exact) {
  if (exact || points.form() == PointList::Form::rationals) {
    std::string line;
    for (std::size_t i = 0; i < points.size(); ++i) {
      line.clear();
      append_point(line, points, i, exact);
      out.write(line.data(), std::streamsize(line.size()));
    }
    return;
  }
  // Doubles and pairs printed as their nearest doubles (a line is at most
  // 3 * 24 + 3 characters).
  write_lines(
      out, points.size(), [](std::size_t) { return std::size_t(80); },
      [&](char* p, std::size_t i) {
        const Vec3d& a = points.approx(i);
        p = std::to_chars(p, p + 24, a.x).ptr;
        *p++ = ' ';
        p = std::to_chars(p, p + 24, a.y).ptr;
        *p++ = ' ';
        p = std::to_chars(p, p + 24, a.z).ptr;
        *p++ = '\n';
        return p;
      });
}

void write_counted_face_lines(std::ostream& out, const std::vector<std::vector<Index>>& faces) {
  write_lines(
      out, faces.size(), [&](std::size_t f) { return 21 * (faces[f].size() + 1); },
      [&](char* p, std::size_t f) {
        p = put_index(p, faces[f].size());
        for (Index v : faces[f]) {
          *p++ = ' ';
          p = put_index(p, v);
        }
        *p++ = '\n';
        return p;
      });
}

void append_point(std::string& out, const PointList& points, std::size_t i, bool exact, char sep, const char* end) {
  append_coordinate(out, points, i, 0, exact);
  out += sep;
  append_coordinate(out, points, i, 1, exact);
  out += sep;
  append_coordinate(out, points, i, 2, exact);
  out += end;
}

void put_le(std::ostream& out, std::uint64_t value, int bytes) {
  char b[8];
  for (int i = 0; i < bytes; ++i) b[i] = char((value >> (8 * i)) & 0xffu);
  out.write(b, bytes);
}

void put_le_double(std::ostream& out, double value) {
  std::uint64_t u;
  std::memcpy(&u, &value, 8);
  put_le(out, u, 8);
}

void put_le_float(std::ostream& out, float value) {
  std::uint32_t u;
  std::memcpy(&u, &value, 4);
  put_le(out, u, 4);
}

// --- TextCursor -------------------------------------------------------------

}  // namespace io_detail

using namespace io_detail;

// ---------------------------------------------------------------------------

UnrepresentableError::UnrepresentableError(const std::string& problem, bool floats_only)
    : UsageError(problem + (floats_only ? "; write ascii STL or another format"
                                        : "; write exact rationals to " + extension_list(", ", " or ", true))),
      problem_(problem), floats_only_(floats_only) {}

namespace {
constexpr FormatInfo kFormats[] = {
    {Format::off, "off", "OFF", true, false},  {Format::obj, "obj", "OBJ", true, false},
    {Format::ply, "ply", "PLY", false, true},  {Format::stl, "stl", "STL", false, true},
    {Format::wrl, "wrl", "VRML", true, false},
};
}  // namespace

std::span<const FormatInfo> formats() { return kFormats; }

const FormatInfo& format_info(Format f) {
  for (const FormatInfo& i : kFormats)
    if (i.format == f) return i;
  throw std::logic_error("format_info: not a Format");
}

std::optional<Format> format_from_path(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::size_t base = slash == std::string::npos ? 0 : slash + 1;
  std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || dot < base || dot + 1 >= path.size()) return std::nullopt;
  std::string_view ext = std::string_view(path).substr(dot + 1);
  for (const FormatInfo& i : kFormats)
    if (iequals(ext, i.extension)) return i.format;
  return std::nullopt;
}

const char* format_name(Format f) { return format_info(f).name; }

std::string extension_list(std::string_view separator, std::string_view last_separator, bool exact, bool binary) {
  std::vector<const char*> ext;
  for (const FormatInfo& i : kFormats)
    if ((!exact || i.exact) && (!binary || i.binary)) ext.push_back(i.extension);
  std::string out;
  for (std::size_t k = 0; k < ext.size(); ++k) {
    if (k > 0) out += k + 1 == ext.size() ? last_separator : separator;
    out += '.';
    out += ext[k];
  }
  return out;
}

namespace {

std::string lower_strerror(int err) {
  std::string s = std::strerror(err);
  if (!s.empty() && s[0] >= 'A' && s[0] <= 'Z') s[0] = char(s[0] - 'A' + 'a');
  return s;
}

[[noreturn]] void unknown_extension(const std::string& path, const char* verb) {
  throw UsageError("cannot " + std::string(verb) + " '" + path + "': unknown file extension (use " +
                   extension_list(", ", " or ") + ")");
}

Mesh parse(std::string_view data, Format format, const std::string& name) {
  // STL decides between binary (whose 80-byte header may begin with any
  // bytes) and ascii itself.
  if (format != Format::stl) data = without_utf8_bom(data);
  if (data.empty()) throw InputError(name, "", "file is empty");
  switch (format) {
    case Format::off: return read_off(data, name);
    case Format::obj: return read_obj(data, name);
    case Format::ply: return read_ply(data, name);
    case Format::stl: return read_stl(data, name);
    case Format::wrl: return read_wrl(data, name);
  }
  throw UsageError("unknown format");
}

// Whole regular file into memory; InputError for anything else.
std::string slurp(const std::string& path) {
  struct stat st{};
  if (::stat(path.c_str(), &st) != 0) {
    int err = errno;
    if (err == ENOENT) throw InputError(path, "", "no such file");
    throw InputError(path, "", "cannot access: " + lower_strerror(err));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path, "", "is a directory, not a file");
  if (!S_ISREG(st.st_mode)) throw InputError(path, "", "is not a regular file");
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path, "", "cannot open: " + lower_strerror(errno));
  // Straight into the string, in as few reads as the kernel allows (one for
  // a file in the page cache); a file that grew since the stat goes on
  // growing the string.
  std::string data(static_cast<std::size_t>(st.st_size) + 1, '\0');
  std::size_t used = 0;
  for (;;) {
    if (used == data.size()) data.resize(2 * data.size());
    ssize_t got = ::read(fd, data.data() + used, data.size() - used);
    if (got < 0) {
      if (errno == EINTR) continue;
      int err = errno;
      ::close(fd);
      throw InputError(path, "", "read error: " + lower_strerror(err));
    }
    if (got == 0) break;
    used += static_cast<std::size_t>(got);
  }
  ::close(fd);
  data.resize(used);
  return data;
}

void check_exact_possible(Format format, const WriteOptions& options) {
  if (options.exact && !format_info(format).exact)
    throw UsageError(std::string(format_name(format)) + " cannot store exact rationals; use " +
                     extension_list(", ", " or ", true));
}

void check_writable(const Mesh& mesh, Format format, const WriteOptions& options) {
  check_exact_possible(format, options);
  const std::size_t n = mesh.points.size();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    for (Index v : mesh.faces[f])
      if (v >= n)
        throw UsageError("cannot write mesh: face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(v) + " but there are " + std::to_string(n) + " vertices");
}

// A streambuf writing to a file descriptor, remembering the first errno.
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd) { setp(buf_.get(), buf_.get() + kSize); }
  int error() const { return err_; }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (err_ != 0) return false;
    const char* p = pbase();
    std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    while (n > 0) {
      ssize_t w = ::write(fd_, p, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        err_ = errno;
        return false;
      }
      p += w;
      n -= static_cast<std::size_t>(w);
    }
    setp(buf_.get(), buf_.get() + kSize);
    return true;
  }

  static constexpr std::size_t kSize = std::size_t(1) << 16;
  int fd_;
  int err_ = 0;
  std::unique_ptr<char[]> buf_ = std::make_unique_for_overwrite<char[]>(kSize);  // (not on the stack: TextBuffer)
};

std::string random_suffix() {
  static const char alphabet[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  thread_local std::mt19937_64 rng([] {
    std::random_device rd;
    std::uint64_t seed = (std::uint64_t(rd()) << 32) ^ rd();
    seed ^= std::uint64_t(::getpid()) << 17;
    seed ^= std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count());
    return seed;
  }());
  std::string s;
  for (int i = 0; i < 6; ++i) s += alphabet[rng() % (sizeof alphabet - 1)];
  return s;
}

}  // namespace

Format output_format(const std::string& path, const WriteOptions& options, std::optional<Format> given) {
  auto format = format_from_path(path);
  if (!format) format = given;
  if (!format) unknown_extension(path, "write");
  check_exact_possible(*format, options);
  return *format;
}

Mesh read_mesh(const std::string& path) {
  auto format = format_from_path(path);
  if (!format) unknown_extension(path, "read");
  std::string data = slurp(path);
  return parse(data, *format, path);
}

Scene read_scene(std::string_view data, const std::string& name) {
  data = without_utf8_bom(data);
  if (data.empty()) throw InputError(name, "", "file is empty");
  return read_wrl_scene(data, name);
}

Scene read_scene(const std::string& path) {
  const std::string data = slurp(path);
  return read_scene(std::string_view(data), path);
}

void write_scene(const std::string& path, const Scene& scene, bool exact, const std::vector<std::string>& comments) {
  write_file_atomically(path, [&](std::ostream& out) { write_scene(out, scene, exact, comments); });
}

Mesh read_mesh(const std::string& path, Format format) {
  std::string data = slurp(path);
  return parse(data, format, path);
}

Mesh read_mesh(std::istream& in, Format format, const std::string& name) {
  std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(name, "", "read error");
  return parse(data, format, name);
}

namespace {
// p's coordinates, which the format holds (writable_polytope's result).
void write_polytope_exactly(std::ostream& out, const ConvexPolytope& p, Format format, const WriteOptions& options) {
  if (format == Format::off) write_off(out, p, options);
  else write_mesh(out, p.to_mesh(), format, options);
}
}  // namespace

void write_mesh(std::ostream& out, const Mesh& mesh, Format format, const WriteOptions& options) {
  check_writable(mesh, format, options);
  switch (format) {
    case Format::off: write_off(out, mesh, options); break;
    case Format::obj: write_obj(out, mesh, options); break;
    case Format::ply: write_ply(out, mesh, options); break;
    case Format::stl: write_stl(out, mesh, options); break;
    case Format::wrl: write_wrl(out, mesh, options); break;
  }
}

void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  auto format = format_from_path(path);
  if (!format) unknown_extension(path, "write");
  // Refuse before touching the file system.
  check_writable(mesh, *format, options);
  write_file_atomically(path, [&](std::ostream& out) { write_mesh(out, mesh, *format, options); });
}

void write_polytope(const std::string& path, const ConvexPolytope& p, const WriteOptions& options,
                    RoundingReport* report, std::optional<Format> format) {
  if (!format) format = format_from_path(path);
  if (!format) unknown_extension(path, "write");
  check_exact_possible(*format, options);
  // Rounded (and refused) before the file system is touched; p itself when
  // the format holds it (no copy).
  std::optional<ConvexPolytope> rounded;
  if (holds_exactly(p, *format, options)) {
    if (report) *report = {};
  } else {
    rounded = writable_polytope(p, *format, options, report);
  }
  const ConvexPolytope& q = rounded ? *rounded : p;
  write_file_atomically(path, [&](std::ostream& out) { write_polytope_exactly(out, q, *format, options); });
}

void write_polytope(std::ostream& out, const ConvexPolytope& p, Format format, const WriteOptions& options,
                    RoundingReport* report) {
  check_exact_possible(format, options);
  if (holds_exactly(p, format, options)) {
    if (report) *report = {};
    write_polytope_exactly(out, p, format, options);
    return;
  }
  write_polytope_exactly(out, writable_polytope(p, format, options, report), format, options);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& fill) {
  if (path.empty()) throw InputError(path, "", "empty output path");
  // Create the temporary with O_EXCL and mode 0666 so the umask applies as
  // for any new file; keep an existing target's permissions.
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    tmp = path + ".tmp." + random_suffix();
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0)
    throw InputError(path, "", "cannot create a temporary file beside it: " + lower_strerror(errno));
  struct stat old{};
  if (::stat(path.c_str(), &old) == 0 && S_ISREG(old.st_mode))
    (void)::fchmod(fd, old.st_mode & 07777);

  auto fail = [&](const std::string& reason) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    throw InputError(path, "", reason);
  };

  FdBuf buf(fd);
  std::ostream out(&buf);
  try {
    fill(out);
    out.flush();
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  if (buf.error() != 0) fail("write error: " + lower_strerror(buf.error()));
  if (!out) fail("write error");
  // No fsync: the rename makes the write atomic for every reader (the old
  // content or the whole new file, never a part), which is the guarantee
  // minksum gives; durability across a power failure is the file system's
  // (an fsync per output costs more than a whole sum of mid-sized operands).
  int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("write error: " + lower_strerror(errno));
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot replace the file: " + lower_strerror(errno));
}

}  // namespace minksum
