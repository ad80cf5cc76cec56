// A small strict JSON reader for one flat object of strings and booleans:
// the lines of 'minksum batch' and the requests of 'minksum play'.
#pragma once

#include <minksum/error.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace minksum::cli {

// One member of a JSON line: a string, or a boolean (value "true" / "false").
struct JsonMember {
  std::string key, value;
  bool is_string = true;
};

// One JSON object {"key": value, ...} with string and boolean values (a
// line of 'minksum batch', the body of a request to 'minksum play'): nothing
// but JSON white space may follow the closing brace, and a NUL byte is
// refused wherever it stands (JSON has no unescaped NUL; "\u0000" is refused
// too, no name holds one).  Linear in the length of the text, however many
// keys it has.  Throws InputError(file, place, problem).
class JsonObjectParser {
 public:
  JsonObjectParser(const std::string& text, const std::string& file, const std::string& place)
      : s_(text), file_(file), place_(place) {}

  std::vector<JsonMember> object() {
    std::vector<JsonMember> out;
    expect('{');
    if (peek() == '}') {
      ++i_;
    } else {
      for (;;) {
        JsonMember m;
        m.key = string();
        expect(':');
        m.is_string = peek() == '"';
        if (m.is_string) m.value = string();
        else if (word("true")) m.value = "true";
        else if (word("false")) m.value = "false";
        else fail("the value of \"" + m.key + "\" is not a string or a boolean");
        out.push_back(std::move(m));
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect('}');
        break;
      }
    }
    check_unique_keys(out);
    if (peek() != kEnd) fail("text after the JSON object at column " + std::to_string(i_ + 1));
    return out;
  }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, place_, problem); }

 private:
  static constexpr int kEnd = -1;  // peek() at the end of the text

  // Fails on the first member (in order) whose key an earlier one has: an
  // open-addressing hash table of member indices, expected constant time per key.
  void check_unique_keys(const std::vector<JsonMember>& members) const {
    if (members.size() < 2) return;
    constexpr std::size_t kFree = std::size_t(-1);
    std::size_t mask = 1;
    while (mask < 2 * members.size()) mask <<= 1;
    std::vector<std::size_t> slot(mask--, kFree);
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::string& key = members[i].key;
      for (std::size_t h = std::hash<std::string_view>{}(key) & mask;; h = (h + 1) & mask) {
        if (slot[h] == kFree) {
          slot[h] = i;
          break;
        }
        if (members[slot[h]].key == key) fail("\"" + key + "\" given twice");
      }
    }
  }

  // The next character after JSON white space, as an unsigned char, or kEnd.
  // A NUL byte there is refused: it is no JSON token.
  int peek() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r' || s_[i_] == '\n')) ++i_;
    if (i_ >= s_.size()) return kEnd;
    if (s_[i_] == '\0') fail("a NUL byte at column " + std::to_string(i_ + 1));
    return static_cast<unsigned char>(s_[i_]);
  }
  void expect(char c) {
    if (peek() != static_cast<unsigned char>(c))
      fail(std::string("expected '") + c + "' at column " + std::to_string(i_ + 1));
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
      if (c == '\0') fail("a NUL byte at column " + std::to_string(i_));
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {  // with the plain characters after it, at once
        std::size_t end = i_;
        while (end < s_.size() && s_[end] != '"' && s_[end] != '\\' && static_cast<unsigned char>(s_[end]) >= 0x20) ++end;
        out.append(s_, i_ - 1, end - i_ + 1);
        i_ = end;
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated string");
      if (s_[i_] == '\0') fail("a NUL byte at column " + std::to_string(i_ + 1));
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

}  // namespace minksum::cli
