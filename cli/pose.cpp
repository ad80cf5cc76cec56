// The text of query vectors, rotations and trajectory lines.
#include "pose.hpp"

#include <minksum/error.hpp>

#include "text.hpp"

#include <vector>

namespace minksum::cli {

std::optional<Point3> parse_vector(std::string_view text, std::string* why) {
  Point3 p;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string_view::npos)) {
      *why = "expected three comma-separated numbers X,Y,Z, got '" + printable(text) + "'";
      return std::nullopt;
    }
    const std::string_view tok = text.substr(start, i < 2 ? comma - start : std::string_view::npos);
    std::string reason;
    auto v = parse_number(tok, &reason);
    if (!v) {
      *why = "bad coordinate '" + printable(tok) + "' in '" + printable(text) + "' (" + reason + ")";
      return std::nullopt;
    }
    p[i] = *v;
    start = comma + 1;
  }
  return p;
}

std::optional<Quaternion> parse_quaternion(std::string_view text, std::string* why) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  Quaternion q;
  bool ok = parts.size() == 4;
  for (std::size_t i = 0; ok && i < 4; ++i) {
    auto v = parse_number(parts[i]);
    ok = v && v->get_den() == 1 && parts[i].find_first_of(".eEpx") == std::string_view::npos;
    if (ok) q[i] = v->get_num();
  }
  if (!ok) {
    *why = "a rotation is four integers A,B,C,D, got '" + printable(text) + "'";
    return std::nullopt;
  }
  if (sgn(q[0]) == 0 && sgn(q[1]) == 0 && sgn(q[2]) == 0 && sgn(q[3]) == 0) {
    *why = "a rotation needs a non-zero quaternion, got '" + printable(text) + "'";
    return std::nullopt;
  }
  return q;
}

std::optional<Pose> parse_pose_line(std::string_view line, const std::string& source, long line_no) {
  // Tokens are separated by blanks (space, tab, carriage return, ...).
  std::vector<std::string_view> tok;
  constexpr std::string_view blanks = " \t\r\n\v\f";
  for (std::size_t i = line.find_first_not_of(blanks); i != std::string_view::npos;) {
    const std::size_t end = line.find_first_of(blanks, i);
    tok.push_back(line.substr(i, end == std::string_view::npos ? std::string_view::npos : end - i));
    i = end == std::string_view::npos ? end : line.find_first_not_of(blanks, end);
  }
  if (tok.empty() || tok[0][0] == '#') return std::nullopt;
  const std::string place = "line " + std::to_string(line_no);
  Pose pose;
  int vectors = 0;
  for (const std::string_view t : tok) {
    std::string why;
    if (t.starts_with("rp=") || t.starts_with("rq=")) {
      auto q = parse_quaternion(t.substr(3), &why);
      if (!q) throw InputError(source, place, why);
      (t[1] == 'p' ? pose.rp : pose.rq) = *q;
      continue;
    }
    auto v = parse_vector(t, &why);
    if (!v) throw InputError(source, place, why);
    if (vectors == 0) pose.p = *v;
    else if (vectors == 1) pose.q = *v;
    else throw InputError(source, place, "more than two translations on one line");
    ++vectors;
  }
  if (vectors == 0) throw InputError(source, place, "no translation of P on the line");
  return pose;
}

}  // namespace minksum::cli
