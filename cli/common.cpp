// The minksum command line: argument parsing, JSON and output helpers.
#include "common.hpp"

#include "mesh_io.hpp"

#include <minksum/io.hpp>
#include <minksum/minkowski.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace minksum::cli {

Args parse_args(const std::vector<std::string>& argv, const std::string& command,
                const std::vector<OptionSpec>& options) {
  Args a;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    std::string s = argv[i];
    if (s == "-h" || s == "--help") {
      a.help = true;
      continue;
    }
    bool negative_number = s.size() > 1 && s[0] == '-' && (std::isdigit((unsigned char)s[1]) || s[1] == '.');
    if (s.size() < 2 || s[0] != '-' || negative_number) {
      a.positional.push_back(s);
      continue;
    }
    std::string value;
    bool has_value = false;
    if (s.rfind("--", 0) == 0) {
      if (auto eq = s.find('='); eq != std::string::npos) {
        value = s.substr(eq + 1);
        s = s.substr(0, eq);
        has_value = true;
      }
    }
    const OptionSpec* spec = nullptr;
    for (const auto& o : options)
      if (s == o.name || (!o.alias.empty() && s == o.alias)) spec = &o;
    if (!spec)
      throw UsageError("unknown option '" + argv[i] + "' for '" + command + "' (see 'minksum " + command +
                       " --help')");
    if (spec->takes_value) {
      if (!has_value) {
        if (i + 1 >= argv.size()) throw UsageError(spec->name + " needs a value");
        value = argv[++i];
      }
      a.values[spec->name] = value;
    } else {
      if (has_value) throw UsageError(spec->name + " takes no value");
      a.flags.insert(spec->name);
    }
  }
  return a;
}


// The content of a JSON string literal of s, valid JSON whatever the bytes of
// s (a byte that is not UTF-8 becomes U+FFFD) and without a raw control
// character.
std::string json_escape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    char32_t cp = 0;
    const std::size_t n = utf8_length(s, i, &cp);
    if (n == 0) {  // JSON text is UTF-8: a byte that is not becomes U+FFFD
      out += "\\ufffd";
      ++i;
      continue;
    }
    if (cp == '"') out += "\\\"";
    else if (cp == '\\') out += "\\\\";
    else if (cp == '\n') out += "\\n";
    else if (cp == '\t') out += "\\t";
    else if (cp < 0x20 || (cp >= 0x7f && cp <= 0x9f) || cp == 0x2028 || cp == 0x2029) {
      // control characters (C0, DEL, C1: none reaches a terminal showing the
      // line) and U+2028, U+2029 (line terminators in JavaScript source)
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(cp));
      out += buf;
    } else {
      out.append(s, i, n);
    }
    i += n;
  }
  return out;
}

std::string json_number(double x) { return std::isfinite(x) ? format_double(x) : std::string("null"); }

void check_stdout() {
  // errno is that of the failed write: it is reset before flushing, and an
  // earlier failure is seen by the caller right after the write (or, at the
  // end of main, with no system call in between).
  if (std::cout) {
    errno = 0;
    std::cout.flush();
  }
  if (!std::cout) {
    const int err = errno;
    throw OutputError(std::string("cannot write to standard output") +
                      (err ? std::string(": ") + std::strerror(err) : std::string()));
  }
}

std::string counts_json(const ConvexPolytope& p) {
  std::ostringstream o;
  o << "\"vertices\": " << p.num_vertices() << ", \"edges\": " << p.num_edges()
    << ", \"facets\": " << p.num_facets();
  return o.str();
}

std::string kind_json(int dimension, const char* kind) {
  return "\"dimension\": " + std::to_string(dimension) + ", \"kind\": \"" + kind + "\"";
}

std::string polytope_json(const ConvexPolytope& p) { return counts_json(p) + ", " + kind_json(3, "polytope"); }

ConvexPolytope load_operand(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> format) {
  try {
    return load_operand_from(spec, hull, phases, format);
  } catch (const NotConvexError& e) {
    throw InputError(e.file(), e.place(), e.problem() + "; --hull takes the convex hull of its points instead");
  }
}

namespace {
// `text` wrapped to `width` columns, every line indented by `indent` spaces.
std::string wrap(const std::string& text, std::size_t indent, std::size_t width) {
  std::string out, line;
  std::istringstream words(text);
  for (std::string w; words >> w;) {
    if (!line.empty() && indent + line.size() + 1 + w.size() > width) {
      out += std::string(indent, ' ') + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + w;
  }
  if (!line.empty()) out += std::string(indent, ' ') + line + "\n";
  return out;
}
}  // namespace

std::string expand_help(std::string_view text) {
  std::string methods_text;
  for (const MethodInfo& m : methods()) {
    if (!methods_text.empty()) methods_text += ", ";
    methods_text += m.name;
    if (m.method == Method::automatic) methods_text += " (default)";
  }
  std::string summaries;
  for (const MethodInfo& m : methods())
    if (m.method != Method::automatic) summaries += wrap(std::string(m.name) + ": " + m.summary, 21, 79);
  if (!summaries.empty()) summaries.pop_back();  // the template's line break follows
  const std::pair<std::string_view, std::string> fills[] = {
      {"{formats}", extension_list(" ", " ")},
      {"{exact_formats}", extension_list(", ", " and ", true)},
      {"{binary_formats}", extension_list(" / ", " / ", false, true)},
      {"{format_names}", format_choices()},
      {"{methods}", methods_text},
      {"{method_summaries}", summaries},
  };
  std::string out(text);
  for (const auto& [key, value] : fills)
    for (std::size_t at = out.find(key); at != std::string::npos; at = out.find(key, at + value.size()))
      out.replace(at, key.size(), value);
  return out;
}

}  // namespace minksum::cli
