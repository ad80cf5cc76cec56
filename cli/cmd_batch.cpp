// minksum batch: many independent Minkowski sums on a pool of threads.
#include <minksum/parallel.hpp>

#include <cstddef>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"

namespace minksum::cli {

namespace {

const char* kBatchHelp = R"(Usage: minksum batch [FILE] [options]

Compute many Minkowski sums A ⊕ B, independently, on several threads, and
print one JSON line per pair, in input order.  FILE (default, or "-":
standard input) holds one pair per line, either as a JSON object
    {"a": "cube", "b": "sphere:3", "method": "walk", "hull": false}
("method" and "hull" optional: --method and --hull give the defaults) or as
two names separated by white space
    parts/gear.off tools/ball.stl
A and B are files ({formats}) or catalog names, as for 'minksum sum'.  Empty
lines and lines starting with '#' are skipped.

Options:
  --threads N        compute on N threads (default: one per hardware thread)
  --method M         {methods}.
                     All are exact and give the same polytope.
  --hull             take the convex hull of each input file's points

Output, one line per pair:
  {"line": 1, "a": "cube", "b": "sphere:3", "method": "walk", "vertices": V,
   "edges": E, "facets": F, "volume": "p/q", "volume_double": x, "seconds": s}
volume is exact (an integer or p/q); seconds is the sum's computation alone.
A pair that fails (a missing or bad file, an unknown catalog name) gets
  {"line": 3, "a": "...", "b": "...", "error": "FILE: PLACE: PROBLEM", "status": 3}
(status 3: bad input data, 2: bad usage) and the other pairs go on.

Exit status: 0 when every pair succeeded; otherwise 3 if a pair had bad input
data, else 2, with one line on stderr counting the failed pairs and naming
the first.  A malformed line of FILE itself (bad JSON, a missing "a") is bad
input: exit status 3 before anything is computed, nothing printed.
)";

struct Pair {
  std::size_t line = 0;
  std::string a, b;
  Method method = Method::automatic;
  bool hull = false;
};

struct Outcome {
  std::string json;  // the line's fields after "line", "a", "b"
  int status = 0;    // 0, 2 or 3
  std::string error;
};

// One member of a JSON line: a string, or a boolean (value "true" / "false").
struct Member {
  std::string key, value;
  bool is_string = true;
};

// A JSON line {"key": value, ...} with string and boolean values.  Throws InputError.
class LineParser {
 public:
  LineParser(const std::string& text, const std::string& file, std::size_t line)
      : s_(text), file_(file), place_("line " + std::to_string(line)) {}

  std::vector<Member> object() {
    std::vector<Member> out;
    expect('{');
    if (peek() == '}') {
      ++i_;
    } else {
      for (;;) {
        std::string key = string();
        expect(':');
        Member m{key, "", peek() == '"'};
        if (m.is_string) m.value = string();
        else if (word("true")) m.value = "true";
        else if (word("false")) m.value = "false";
        else fail("the value of \"" + key + "\" is not a string or a boolean");
        for (const auto& other : out)
          if (other.key == key) fail("\"" + key + "\" given twice");
        out.push_back(std::move(m));
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect('}');
        break;
      }
    }
    if (peek() != '\0') fail("text after the JSON object");
    return out;
  }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, place_, problem); }

 private:
  char peek() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
    return i_ < s_.size() ? s_[i_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "' at column " + std::to_string(i_ + 1));
    ++i_;
  }
  bool word(const char* w) {
    const std::string t(w);
    if (s_.compare(i_, t.size(), t) != 0) return false;
    i_ += t.size();
    return true;
  }
  static void append_utf8(std::string& out, unsigned cp) {
    if (cp < 0x80) {
      out += char(cp);
    } else if (cp < 0x800) {
      out += char(0xc0 | (cp >> 6));
      out += char(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
      out += char(0xe0 | (cp >> 12));
      out += char(0x80 | ((cp >> 6) & 0x3f));
      out += char(0x80 | (cp & 0x3f));
    } else {
      out += char(0xf0 | (cp >> 18));
      out += char(0x80 | ((cp >> 12) & 0x3f));
      out += char(0x80 | ((cp >> 6) & 0x3f));
      out += char(0x80 | (cp & 0x3f));
    }
  }
  unsigned hex4() {
    if (i_ + 4 > s_.size()) fail("truncated \\u escape");
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[i_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= unsigned(c - '0');
      else if (c >= 'a' && c <= 'f') v |= unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= unsigned(c - 'A' + 10);
      else fail("bad \\u escape");
    }
    return v;
  }
  std::string string() {
    expect('"');
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated string");
      switch (const char e = s_[i_++]) {
        case '"': case '\\': case '/': out += e; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xd800 && cp < 0xdc00) {  // a surrogate pair
            if (!word("\\u")) fail("lone surrogate in a \\u escape");
            const unsigned lo = hex4();
            if (lo < 0xdc00 || lo >= 0xe000) fail("lone surrogate in a \\u escape");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (lo - 0xdc00);
          } else if (cp >= 0xdc00 && cp < 0xe000) {
            fail("lone surrogate in a \\u escape");
          }
          if (cp == 0) fail("NUL in a string");
          append_utf8(out, cp);
          break;
        }
        default: fail(std::string("bad escape '\\") + e + "'");
      }
    }
  }

  const std::string& s_;
  std::string file_, place_;
  std::size_t i_ = 0;
};

Method method_of(const std::string& text) {
  auto m = parse_method(text);
  if (!m) throw UsageError("unknown method '" + text + "' (" + method_list() + ")");
  if (!method_available(*m))
    throw UsageError(std::string("method '") + method_name(*m) + "' is not implemented in this version of minksum");
  return *m;
}

// The pairs of FILE, every line checked before anything is computed.
std::vector<Pair> read_pairs(std::istream& in, const std::string& file, Method method, bool hull) {
  std::vector<Pair> pairs;
  std::string text;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    const std::size_t first = text.find_first_not_of(" \t\r");
    if (first == std::string::npos || text[first] == '#') continue;
    Pair p;
    p.line = line;
    p.method = method;
    p.hull = hull;
    LineParser parser(text, file, line);
    if (text[first] == '{') {
      bool has_a = false, has_b = false;
      for (const auto& [key, value, is_string] : parser.object()) {
        if ((key == "a" || key == "b" || key == "method") && (!is_string || value.empty()))
          parser.fail("\"" + key + "\" must be a non-empty string");
        if (key == "a" || key == "b") {
          (key == "a" ? p.a : p.b) = value;
          (key == "a" ? has_a : has_b) = true;
        } else if (key == "method") {
          auto m = parse_method(value);
          if (!m || !method_available(*m)) parser.fail("unknown method '" + value + "' (" + method_list() + ")");
          p.method = *m;
        } else if (key == "hull") {
          if (is_string) parser.fail("\"hull\" must be true or false");
          p.hull = value == "true";
        } else {
          parser.fail("unknown key \"" + key + "\" (a, b, method, hull)");
        }
      }
      if (!has_a || !has_b) parser.fail(std::string("missing \"") + (has_a ? "b" : "a") + "\"");
    } else {
      std::istringstream words(text);
      std::string extra;
      if (!(words >> p.a >> p.b)) parser.fail("expected two names A B or a JSON object");
      if (words >> extra) parser.fail("more than two names (a name with spaces needs the JSON form)");
    }
    pairs.push_back(std::move(p));
  }
  if (in.bad()) throw InputError(file, "", "read error");
  return pairs;
}

Outcome compute(const Pair& p) {
  Outcome o;
  try {
    const ConvexPolytope a = load_operand(p.a, p.hull, nullptr);
    const ConvexPolytope b = load_operand(p.b, p.hull, nullptr);
    const SumResult r = minkowski_sum(a, b, p.method);
    const Rational volume = r.polytope.volume();
    o.json = ", \"method\": \"" + std::string(method_name(r.method)) + "\", " + counts_json(r.polytope) +
             ", \"volume\": \"" + format_exact(volume) + "\", \"volume_double\": " + json_number(to_double(volume)) +
             ", \"seconds\": " + json_number(r.seconds);
  } catch (const InputError& e) {
    o.status = 3;
    o.error = e.what();
  } catch (const UsageError& e) {
    o.status = 2;
    o.error = e.what();
  }
  if (o.status) o.json = ", \"error\": \"" + json_escape(o.error) + "\", \"status\": " + std::to_string(o.status);
  return o;
}

}  // namespace

int run_batch(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "batch", {{"--threads", "", true}, {"--method", "", true}, {"--hull"}});
  if (a.help) {
    std::cout << expand_help(kBatchHelp);
    return 0;
  }
  if (a.positional.size() > 1) throw UsageError("'batch' reads one FILE (see 'minksum batch --help')");
  const Method method = method_of(a.value_or("--method", "auto"));
  unsigned threads = 0;
  if (auto t = a.value("--threads")) {
    std::size_t used = 0;
    long n = 0;
    try {
      n = std::stol(*t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != t->size() || n < 1 || n > 1024) throw UsageError("--threads needs a whole number from 1 to 1024");
    threads = static_cast<unsigned>(n);
  }
  const std::string file = a.positional.empty() ? "-" : a.positional[0];
  std::vector<Pair> pairs;
  if (file == "-") {
    pairs = read_pairs(std::cin, "<stdin>", method, a.flag("--hull"));
  } else {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw InputError(file, "", "cannot open the file");
    pairs = read_pairs(in, file, method, a.flag("--hull"));
  }

  std::vector<Outcome> outcomes(pairs.size());
  parallel_for(pairs.size(), threads, [&](std::size_t i) { outcomes[i] = compute(pairs[i]); });

  std::size_t failed = 0;
  int status = 0;
  const Outcome* first = nullptr;
  const Pair* first_pair = nullptr;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const Outcome& o = outcomes[i];
    std::cout << "{\"line\": " << p.line << ", \"a\": \"" << json_escape(p.a) << "\", \"b\": \"" << json_escape(p.b)
              << "\"" << o.json << "}\n";
    if (o.status) {
      ++failed;
      status = std::max(status, o.status);
      if (!first) first = &o, first_pair = &p;
    }
  }
  std::cout.flush();
  if (!std::cout) throw OutputError("cannot write the results to standard output");
  if (first)
    std::cerr << "minksum: batch: " << failed << " of " << pairs.size() << " pairs failed; the first, "
              << (file == "-" ? "<stdin>" : file) << " line " << first_pair->line << ": " << first->error << "\n";
  return status;
}

}  // namespace minksum::cli
