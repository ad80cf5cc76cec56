// The text of query vectors, rotations and trajectory lines (`minksum query`):
// parsers that see only a string, so they can be tested and fuzzed alone.
#pragma once

#include <minksum/kernel.hpp>
#include <minksum/transform.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace minksum::cli {

// "X,Y,Z" -> an exact point (each coordinate as parse_number reads it);
// nullopt with a reason in *why.
std::optional<Point3> parse_vector(std::string_view text, std::string* why);
// "A,B,C,D" -> a non-zero integer quaternion; nullopt with a reason in *why.
std::optional<Quaternion> parse_quaternion(std::string_view text, std::string* why);

// One trajectory line: "PX,PY,PZ [QX,QY,QZ] [rp=A,B,C,D] [rq=A,B,C,D]".
struct Pose {
  Point3 p;                      // translation of P
  std::optional<Point3> q;       // translation of Q, if given
  std::optional<Quaternion> rp;  // rotation of P, if given
  std::optional<Quaternion> rq;  // rotation of Q, if given
};
// nullopt for a blank line or a comment ('#' first); InputError(source,
// "line N", reason) for anything else that is not a pose.
std::optional<Pose> parse_pose_line(std::string_view line, const std::string& source, long line_no);

}  // namespace minksum::cli
