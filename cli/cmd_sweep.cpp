// minksum sum with points, segments and flat polygons (see sweep.hpp).
#include "sweep.hpp"

#include <minksum/plane.hpp>
#include <minksum/sweep.hpp>
#include <minksum/sweep_proximity.hpp>

#include <cmath>


#include <chrono>
#include <iostream>

#include "common.hpp"
#include "page.hpp"
#include "progress.hpp"
#include "text.hpp"

namespace minksum::cli {

namespace {

std::string set_counts_json(const ConvexSet& s) {
  return "\"vertices\": " + std::to_string(s.num_vertices()) + ", \"edges\": " + std::to_string(s.num_edges()) +
         ", \"facets\": " + std::to_string(s.num_facets()) + ", " + kind_json(s.dimension(), dimension_name(s.dimension()));
}

// A point, a segment or a polygon, written exactly as it is: one face for a
// polygon, the points alone for the others.  STL holds closed triangle
// meshes only, and coordinates are never rounded here (a rounded polygon
// may no longer be planar): both refused (exit status 1), naming the fix.
void write_lower(const MeshOutput& out, const ConvexSet& s) {
  const std::string name = out.to_stdout() ? "<stdout>" : out.path;
  const std::string what = std::string("a ") + dimension_name(s.dimension());
  if (out.format == Format::stl)
    throw OutputError("cannot write " + name + ": the sum is " + what +
                      ", and STL holds only closed triangle meshes; write off, obj, ply or wrl");
  const Mesh m = s.to_mesh();
  if (!out.options.exact && !m.points.all_doubles())
    throw OutputError("cannot write " + name + ": the sum is " + what +
                      " whose coordinates are not all doubles, and it is never rounded; use --exact with " +
                      extension_list(", ", " or ", true) + " to write exact rationals");
  try {
    write_mesh_as_is(out, m);
  } catch (const InputError& e) {
    throw OutputError(std::string("cannot write ") + e.what());
  }
}

}  // namespace

RoundingReport write_set_output(const MeshOutput& out, const ConvexSet& s) {
  if (s.full()) return write_mesh_output(out, s.polytope());
  write_lower(out, s);
  return {};
}

ConvexSet load_set_operand(const std::string& spec, bool hull, LoadPhases* phases, std::optional<Format> format) {
  try {
    if (spec != "-") return load_convex_set(spec, hull, phases, format);
    if (!format)
      throw UsageError("reading a mesh from standard input ('-') needs --format " + format_choices());
    claim_stdin("an operand");
    return load_convex_set(std::cin, *format, "<stdin>", hull, phases);
  } catch (const NotConvexError& e) {
    throw InputError(e.file(), e.place(), e.problem() + "; --hull takes the convex hull of its points instead");
  }
}

void append_set_json(std::string& out, const ConvexSet& s, const std::string& name, const std::string& role) {
  if (s.full()) return append_solid_json(out, s.polytope(), name, role);
  const std::vector<Point3>& v = s.vertices();
  out += "{\"name\": " + json_string(name) + ", \"role\": " + json_string(role) + ", \"counts\": {" +
         set_counts_json(s) + "}, \"volume\": \"0\", \"xyz\": [";
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec3d a = to_double(v[i]);
    out.append(i ? "," : "").append(json_number(a.x)).append(",").append(json_number(a.y)).append(",");
    out.append(json_number(a.z));
  }
  out += "], \"exact\": [";
  for (std::size_t i = 0; i < v.size(); ++i)
    out.append(i ? ",\"" : "\"").append(format_exact(v[i].x)).append(" ").append(format_exact(v[i].y)).append(" ")
        .append(format_exact(v[i].z)).append("\"");
  out += "], \"facets\": [";
  if (s.dimension() == 2) {
    std::string front, back;
    for (std::size_t i = 0; i < v.size(); ++i) {
      front.append(i ? "," : "").append(std::to_string(i));
      back.append(i ? "," : "").append(std::to_string(v.size() - 1 - i));
    }
    const Plane up = canonical_plane(s.normal(), v[0]), down = canonical_plane(-s.normal(), v[0]);
    auto text = [](const Plane& p) {
      return std::string(1, '"').append(p.a.get_str()).append(" ").append(p.b.get_str()).append(" ")
          .append(p.c.get_str()).append(" ").append(p.d.get_str()).append("\"");
    };
    out += "[" + front + "],[" + back + "]], \"planes\": [" + text(up) + "," + text(down) + "]}";
  } else {
    out += s.dimension() == 1 ? "[0,1,0]" : "[0,0,0]";
    out += "], \"planes\": [\"0 0 0 0\"]}";
  }
}

int view_sets(const std::string& output, const std::string& title, const std::vector<std::string>& names,
              const std::vector<ConvexSet>& operands, Method method, bool json) {
  if (operands.size() == 1) {
    std::string data = "{\"kind\": \"polytope\", \"title\": " + json_string(title) + ", \"solids\": [";
    append_set_json(data, operands[0], names[0], "polytope");
    data += "]}";
    write_page(output, title, data);
    if (json)
      std::cout << "{\"page\": \"polytope\", \"name\": \"" << json_escape(names[0]) << "\", "
                << set_counts_json(operands[0]) << ", \"output\": \""
                << json_escape(output) << "\"}\n";
    else
      std::cout << names[0] << ": a " << dimension_name(operands[0].dimension()) << ", "
                << operands[0].num_vertices() << " vertices\n  page written to " << output << "\n";
    return 0;
  }
  const SetSumResult r = [&] {
    ProgressTicker ticker("minksum view");
    return minkowski_sum_sets(operands[0], operands[1], method, ticker.sum_options());
  }();
  std::string data = "{\"kind\": \"sum\", \"title\": " + json_string(title) + ", \"method\": \"" +
                     method_name(r.method) + "\", \"provenance\": \"none\", \"origins\": " + origin_names_json() +
                     ", \"solids\": [";
  append_set_json(data, operands[0], names[0], "a");
  data += ", ";
  append_set_json(data, operands[1], names[1], "b");
  data += ", ";
  append_set_json(data, r.set, names[0] + " ⊕ " + names[1], "sum");
  data += "]}";
  write_page(output, title, data);
  if (json)
    std::cout << "{\"page\": \"sum\", " << set_counts_json(r.set) << ", \"method\": \"" << method_name(r.method)
              << "\", \"route\": \"" << r.route << "\", \"volume\": \"" << format_exact(r.set.volume())
              << "\", \"a\": {\"name\": \"" << json_escape(names[0]) << "\", " << set_counts_json(operands[0])
              << "}, \"b\": {\"name\": \"" << json_escape(names[1]) << "\", " << set_counts_json(operands[1])
              << "}, \"output\": \"" << json_escape(output) << "\"}\n";
  else
    std::cout << names[0] << " ⊕ " << names[1] << " = a " << dimension_name(r.set.dimension()) << ": "
              << r.set.num_vertices() << " vertices, " << r.set.num_edges() << " edges, " << r.set.num_facets()
              << " facets (method " << method_name(r.method) << ", " << r.route << ")\n  page written to " << output
              << "\n";
  return 0;
}

int query_sets(const std::string& kind, const ConvexSet& p, const ConvexSet& q, const Point3& u, const Point3& w,
               const Point3& d, Method method, bool json) {
  const SetObstacle ob(p, q, method);
  const Point3 s = w - u;
  const auto t0 = std::chrono::steady_clock::now();
  const ContactStatus status = ob.contact(s);
  std::string key, value;
  double approx = 0;
  if (kind == "distance") {
    const Rational d2 = ob.squared_distance(s);
    key = "squared_distance", value = format_exact(d2), approx = std::sqrt(to_double(d2));
  } else if (kind == "depth") {
    const Rational d2 = ob.squared_depth(s);
    key = "squared_depth", value = format_exact(d2), approx = std::sqrt(to_double(d2));
  } else if (kind == "ddepth") {
    const Rational t = ob.directional_depth(s, d);
    key = "t", value = format_exact(t), approx = to_double(t) * std::sqrt(to_double(dot(d, d)));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const char* name = kind == "distance" ? "distance" : "depth";
  if (json) {
    std::cout << "{\"query\": \"" << kind << "\", \"status\": \"" << contact_status_name(status) << "\"";
    if (!key.empty()) std::cout << ", \"" << key << "\": \"" << value << "\", \"" << name << "\": " << json_number(approx);
    std::cout << ", \"obstacle\": {" << set_counts_json(ob.obstacle()) << "}, \"seconds\": " << json_number(seconds)
              << "}\n";
  } else {
    std::cout << contact_status_name(status);
    if (kind == "distance") std::cout << "  distance² = " << value << "  distance ≈ " << format_double(approx);
    if (kind == "depth") std::cout << "  depth² = " << value << "  depth ≈ " << format_double(approx);
    if (kind == "ddepth") std::cout << "  t = " << value << "  depth ≈ " << format_double(approx);
    std::cout << "  [M = P ⊕ (−Q) is a " << dimension_name(ob.obstacle().dimension()) << "]\n";
  }
  return 0;
}

}  // namespace minksum::cli
