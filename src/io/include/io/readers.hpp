// Internal to src/io/: the per-format readers and writers behind
// read_mesh()/write_mesh(), and the small text and binary cursors they share.
//
// Every reader takes the whole file in memory (`data`) and the name used in
// error messages, and throws InputError(name, place, problem) on any defect.
// Knowing the size up front is what lets a reader reject an absurd element
// count before allocating anything proportional to it.
#pragma once

#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/kernel.hpp>
#include <minksum/parallel.hpp>
#include <minksum/polytope.hpp>
#include <minksum/scene.hpp>

#include <algorithm>
#include <charconv>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace minksum::io_detail {

// ---------------------------------------------------------------------------
// Readers (data = the whole file).

Mesh read_off(std::string_view data, const std::string& name);
Mesh read_obj(std::string_view data, const std::string& name);
Mesh read_ply(std::string_view data, const std::string& name);
Mesh read_stl(std::string_view data, const std::string& name);
Mesh read_wrl(std::string_view data, const std::string& name);
// The VRML file as a scene of polytope and CubicalGaussianMap nodes
// (<minksum/scene.hpp>); read_wrl takes its one polytope.
Scene read_wrl_scene(std::string_view data, const std::string& name);

// Writers.  Precondition: every face index is < mesh.points.size() (checked
// by write_mesh, which calls these).
void write_off(std::ostream& out, const Mesh& mesh, const WriteOptions& options);
void write_obj(std::ostream& out, const Mesh& mesh, const WriteOptions& options);
void write_ply(std::ostream& out, const Mesh& mesh, const WriteOptions& options);
void write_stl(std::ostream& out, const Mesh& mesh, const WriteOptions& options);
void write_wrl(std::ostream& out, const Mesh& mesh, const WriteOptions& options);
// OFF straight from a polytope (the same text as write_off of its to_mesh()).
void write_off(std::ostream& out, const ConvexPolytope& p, const WriteOptions& options);
// True when the format holds every coordinate of p as it is (exact rationals
// with options.exact, or doubles in a format of doubles): writable_polytope
// would return p unchanged, so it is written without that copy.
bool holds_exactly(const ConvexPolytope& p, Format format, const WriteOptions& options);

// ---------------------------------------------------------------------------
// Shared helpers.

// The text after a UTF-8 byte-order mark (EF BB BF), if `data` begins with
// one, else `data`: the text formats accept a BOM, as editors on some systems
// write one (line numbers are unchanged; byte offsets count from after it).
inline std::string_view without_utf8_bom(std::string_view data) {
  return data.starts_with("\xEF\xBB\xBF") ? data.substr(3) : data;
}

// "line N" (1-based).
std::string line_place(std::size_t line);

// A token quoted for an error message: at most 40 characters, non-printable
// bytes shown as \xNN, in single quotes.
std::string quote(std::string_view token);

// Parse a coordinate token with parse_number; on failure throw
// InputError(name, place, problem) with a problem such as "coordinate is NaN",
// "coordinate is infinite", "coordinate '1/0' has a zero denominator",
// "expected a number, got 'foo'".
Rational parse_coordinate(std::string_view token, const std::string& name, const std::string& place);

// The same, in the cheapest exact form: the double when the token's exact
// value is one (no allocation), else the exact rational in `exact`.
struct Coordinate {
  double d = 0;
  std::optional<Rational> exact;
};
Coordinate read_coordinate(std::string_view token, const std::string& name, const std::string& place);
// The same at "line N" (the place text is only made on the slow path).
Coordinate read_coordinate(std::string_view token, const std::string& name, std::size_t line);
// Append the point with these coordinates (as doubles when all three are).
void push_point(PointList& points, Coordinate (&c)[3]);

// Writing one coordinate (k = 0, 1, 2) of point i:
//  * its nearest double; UnrepresentableError when it rounds beyond the double range
//    (only rational coordinates can);
//  * its nearest float (binary STL); UnrepresentableError beyond the float range;
//  * appended to `out` as text: the shortest round-trip text of the nearest
//    double, or with `exact` the exact value (an integer or p/q), printed
//    from the doubles' mantissas when the coordinate is a double or a pair.
double coordinate_double(const PointList& points, std::size_t i, int k);
float coordinate_float(const PointList& points, std::size_t i, int k);
void append_coordinate(std::string& out, const PointList& points, std::size_t i, int k, bool exact);
// One line "x y z" per point, and one line "k i0 ... i(k-1)" per face (the
// bodies of OFF and ascii PLY).
void write_point_lines(std::ostream& out, const PointList& points, bool exact);
void write_counted_face_lines(std::ostream& out, const std::vector<std::vector<Index>>& faces);
// A buffer of text in front of an ostream: reserve(n) returns room for at
// least n characters, commit(end) keeps what was written up to `end`; full
// buffers and the rest at destruction go to the stream with one write.
class TextBuffer {
 public:
  explicit TextBuffer(std::ostream& out) : out_(out) {}
  ~TextBuffer() { flush(); }
  TextBuffer(const TextBuffer&) = delete;
  TextBuffer& operator=(const TextBuffer&) = delete;
  char* reserve(std::size_t n) {
    if (used_ + n > kSize) flush();
    return buf_.get() + used_;
  }
  void commit(char* end) { used_ = std::size_t(end - buf_.get()); }
  void flush() {
    if (used_) out_.write(buf_.get(), std::streamsize(used_));
    used_ = 0;
  }

 private:
  // On the heap, not the stack: a stack this deep is fresh memory that
  // faults a page at a time, the heap's blocks are mostly reused.
  static constexpr std::size_t kSize = std::size_t(1) << 15;
  std::ostream& out_;
  std::size_t used_ = 0;
  std::unique_ptr<char[]> buf_ = std::make_unique_for_overwrite<char[]>(kSize);
};

// Lines 0 .. n-1 written in order: size(i) bounds the length of line i,
// put(p, i) writes it at p and returns its end.  From parallel_items() lines
// on (<minksum/parallel.hpp>), chunks of kLinesChunk lines are formatted on
// threads and written in order while the next ones are being formatted: the
// thread that completes the chunk next in line writes it, and every chunk
// already formatted after it, with the lock released, while the other
// threads go on formatting (in a large text file, formatting numbers is most
// of the writing; the system calls of the writes are most of the rest).  No
// chunk is formatted more than kLinesWindow chunks per thread ahead of the
// last one written, so the memory stays bounded.  On one thread (or inside a
// job of another parallel_for) the chunks are formatted and written one
// after the other.
inline constexpr std::size_t kLinesChunk = 1024, kLinesWindow = 8;
template <class Size, class Put>
void write_lines(std::ostream& out, std::size_t n, Size&& size, Put&& put) {
  if (n < parallel_items()) {
    TextBuffer buf(out);
    std::string long_line;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t m = size(i);
      if (m <= 1 << 14) {
        buf.commit(put(buf.reserve(m), i));
        continue;
      }
      long_line.resize(m);
      long_line.resize(std::size_t(put(long_line.data(), i) - long_line.data()));
      buf.flush();
      out.write(long_line.data(), std::streamsize(long_line.size()));
    }
    return;
  }
  const std::size_t chunks = (n + kLinesChunk - 1) / kLinesChunk;
  const std::size_t window = kLinesWindow * std::size_t(parallel_threads(0, chunks));
  std::vector<std::string> text(chunks);
  std::vector<unsigned char> ready(chunks, 0);
  std::size_t written = 0;  // chunks [0, written) are written or being written
  bool writing = false;     // a thread is writing
  bool failed = false;      // a chunk threw (no memory): the waiting jobs stop
  std::mutex m;
  std::condition_variable room;
  parallel_for(chunks, 0, [&](std::size_t c) {
    {
      std::unique_lock<std::mutex> lock(m);
      room.wait(lock, [&] { return failed || c < written + window; });
      if (failed) return;
    }
    std::string t;
    try {
      const std::size_t begin = c * kLinesChunk, end = std::min(n, begin + kLinesChunk);
      std::size_t bound = 0;
      for (std::size_t i = begin; i < end; ++i) bound += size(i);
      t.resize(bound);
      char* p = t.data();
      for (std::size_t i = begin; i < end; ++i) p = put(p, i);
      t.resize(std::size_t(p - t.data()));
    } catch (...) {
      {
        std::lock_guard<std::mutex> lock(m);
        failed = true;
      }
      room.notify_all();
      throw;  // rethrown by parallel_for
    }
    std::unique_lock<std::mutex> lock(m);
    if (failed) return;
    text[c] = std::move(t);
    ready[c] = 1;
    if (writing) return;  // the writing thread takes this chunk when its turn comes
    writing = true;
    while (written < chunks && ready[written]) {
      const std::string chunk = std::move(text[written++]);
      lock.unlock();
      room.notify_all();
      out.write(chunk.data(), std::streamsize(chunk.size()));
      lock.lock();
    }
    writing = false;
  });
}

// A decimal index, written at p (at most 20 characters); returns the end.
inline char* put_index(char* p, std::uint64_t v) { return std::to_chars(p, p + 20, v).ptr; }

// A decimal index or count, appended.
void append_index(std::string& out, std::uint64_t v);
// The three coordinates of point i separated by `sep`, then `end`, appended.
void append_point(std::string& out, const PointList& points, std::size_t i, bool exact, char sep = ' ',
                  const char* end = "\n");

// Parse a non-negative decimal integer token (no sign, no fraction) that fits
// in 64 bits; nullopt otherwise.
std::optional<std::uint64_t> parse_unsigned(std::string_view token);
// Parse a decimal integer token with an optional sign that fits in 64 bits.
std::optional<std::int64_t> parse_signed(std::string_view token);
// True when strtod would read the whole token (numbers, nan, inf): used to
// validate values that are skipped anyway (colours, normals, other properties).
bool looks_numeric(std::string_view token);

// Writing doubles: the nearest double of q; UnrepresentableError when q rounds beyond
// the double range.
double checked_double(const Rational& q);

// Text cursor over a whole file: whitespace-separated tokens, optional
// comments (from `comment` to the end of the line; 0 for none), 1-based line
// numbers.
class TextCursor {
 public:
  explicit TextCursor(std::string_view data, char comment = '#', std::size_t pos = 0,
                      std::size_t line = 1)
      : data_(data), pos_(pos), line_(line), comment_(comment) {}

  // Skip whitespace and comments, then return the next token; false at the end.
  // token_line() is the line of the token returned.
  bool next(std::string_view& token);
  // Like next(), but only if the next token is on the current line (after the
  // previous token); false (and nothing consumed but blanks/comment) otherwise.
  bool next_on_line(std::string_view& token);
  // Skip whitespace and comments; true if the end of data was reached.
  bool at_end();

  std::size_t token_line() const { return token_line_; }
  std::size_t line() const { return line_; }
  std::size_t pos() const { return pos_; }

  // For a reader's fast path, which parses a whole line itself: the bytes
  // from the current position to the end, and moving past what it parsed
  // (`p`, after `lines` line ends).
  const char* here() const { return data_.data() + pos_; }
  const char* end() const { return data_.data() + data_.size(); }
  void advance_to(const char* p, std::size_t lines) {
    pos_ = std::size_t(p - data_.data());
    line_ += lines;
  }

 private:
  void skip_blanks_on_line();
  std::string_view take_token();

  std::string_view data_;
  std::size_t pos_;
  std::size_t line_;
  std::size_t token_line_ = 0;
  char comment_;
};

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

// TextCursor's members, inline: readers call them once per token.
inline bool TextCursor::at_end() {
  const std::size_t n = data_.size();
  for (;;) {
    while (pos_ < n && is_space(data_[pos_])) {
      if (data_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ < n && comment_ != 0 && data_[pos_] == comment_) {
      while (pos_ < n && data_[pos_] != '\n') ++pos_;
      continue;
    }
    return pos_ >= n;
  }
}

inline std::string_view TextCursor::take_token() {
  // Every blank is <= ' ', so one comparison usually settles a byte; the
  // comment character (printable, or none) is the other way a token ends.
  const char* p = data_.data() + pos_;
  const char* const end = data_.data() + data_.size();
  const char* const start = p;
  const char stop = comment_ != 0 ? comment_ : ' ';
  while (p != end) {
    const char c = *p;
    if (static_cast<unsigned char>(c) <= ' ' ? is_space(c) : c == stop) break;
    ++p;
  }
  pos_ = std::size_t(p - data_.data());
  return std::string_view(start, std::size_t(p - start));
}

inline bool TextCursor::next(std::string_view& token) {
  if (at_end()) return false;
  token_line_ = line_;
  token = take_token();
  return true;
}

inline void TextCursor::skip_blanks_on_line() {
  const std::size_t n = data_.size();
  while (pos_ < n && data_[pos_] != '\n' && is_space(data_[pos_])) ++pos_;
  if (pos_ < n && comment_ != 0 && data_[pos_] == comment_)
    while (pos_ < n && data_[pos_] != '\n') ++pos_;
}

inline bool TextCursor::next_on_line(std::string_view& token) {
  skip_blanks_on_line();
  if (pos_ >= data_.size() || data_[pos_] == '\n') return false;
  token_line_ = line_;
  token = take_token();
  return true;
}


// Case-insensitive ASCII equality.
bool iequals(std::string_view a, std::string_view b);

// Little-endian binary output of fixed-size values.
void put_le(std::ostream& out, std::uint64_t value, int bytes);
void put_le_double(std::ostream& out, double value);
void put_le_float(std::ostream& out, float value);

// Nearest float (round to nearest, ties to even, gradual underflow) of an
// exact rational; throws UnrepresentableError when |q| rounds beyond FLT_MAX.
float checked_float(const Rational& q);

}  // namespace minksum::io_detail
