// Text for messages: UTF-8 and escaping (see text.hpp).
#include "text.hpp"

#include <algorithm>
#include <cstdio>

namespace minksum::cli {

std::size_t utf8_length(std::string_view s, std::size_t i, char32_t* code) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned c = b(i);
  std::size_t n;
  char32_t cp, min;
  if (c < 0x80) n = 1, cp = c, min = 0;
  else if ((c & 0xe0) == 0xc0) n = 2, cp = c & 0x1f, min = 0x80;
  else if ((c & 0xf0) == 0xe0) n = 3, cp = c & 0x0f, min = 0x800;
  else if ((c & 0xf8) == 0xf0) n = 4, cp = c & 0x07, min = 0x10000;
  else return 0;
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (b(i + k) & 0x3f);
  }
  if (cp < min || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return 0;
  if (code) *code = cp;
  return n;
}

std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length(s, i, &cp);
    const bool control = n != 0 && (cp < 0x20 || (cp >= 0x7f && cp <= 0x9f));
    if (n != 0 && !control) {
      out.append(s, i, n);
      i += n;
    } else if (cp == '\n' && n == 1) {
      out += "\\n", ++i;
    } else if (cp == '\t' && n == 1) {
      out += "\\t", ++i;
    } else if (cp == '\r' && n == 1) {
      out += "\\r", ++i;
    } else {  // a control character (each of its bytes) or a byte that is not UTF-8
      for (std::size_t k = 0; k < std::max<std::size_t>(n, 1); ++k) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(s[i + k]));
        out += buf;
      }
      i += std::max<std::size_t>(n, 1);
    }
  }
  return out;
}

}  // namespace minksum::cli
