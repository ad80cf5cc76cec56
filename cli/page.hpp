// The pages 'minksum view', 'minksum cgm --html' and 'minksum simulate --html'
// write: one self-contained HTML file each (the viewer's script, three.js
// inlined with its licence, the data as JSON), opening offline in a browser.
// The viewer itself is web/src/viewer.js; docs/viewer.md describes the page.
#pragma once

#include <minksum/cubical_gaussian_map.hpp>
#include <minksum/polytope.hpp>
#include <minksum/sum_result.hpp>
#include <minksum/transform.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace minksum::cli {

// UsageError unless `path` ends in ".html" (`option` names the option in the message).
void check_html_path(const std::string& path, const std::string& option);

// Appends the JSON object of one solid as the page draws it: "name", "role",
// "counts" (vertices, edges, facets), "volume" (exact), "xyz" (the vertices' nearest doubles, flat, for
// drawing), "exact" (each vertex "x y z" in exact rationals), "facets" (vertex
// loops, counter-clockwise seen from outside), "planes" (each facet's
// canonical integer plane "a b c d": a x + b y + c z = d), and with
// `provenance` "origin" (per facet, the index of its FacetOrigin in
// "origins" of the page) and "from" (per facet: dim and index of face_A(n),
// then of face_B(n); dims 0 vertex, 1 edge, 2 facet).
void append_solid_json(std::string& out, const ConvexPolytope& p, const std::string& name, const std::string& role,
                       const std::vector<FacetProvenance>* provenance = nullptr);

// The same fields for a solid that need not be convex, given by its faces
// (simple planar polygons, counter-clockwise seen from outside, as a
// Solid's faces or a NonconvexSum's mesh): "counts" (vertices, edges and
// facets of `faces`), "volume" (`volume`, exact), "xyz", "exact", "facets"
// (the faces' loops), "planes" (each face's canonical integer plane), and
// "triangles" (each face cut into triangles by exact ear clipping: three
// vertex indices a triangle, flat) with "triangle_facet" (the face of each
// triangle), which the page draws instead of fanning the loops.
void append_mesh_solid_json(std::string& out, const Mesh& faces, const Rational& volume, const std::string& name,
                            const std::string& role);

// "[\"translated\", \"corner\", ...]": FacetOrigin names in enum order.
std::string origin_names_json();

// A JSON string literal of s (quotes included; json_escape).
std::string json_string(const std::string& s);

// JSON text made safe inside a <script> element: every '<', '>' and '&'
// becomes \u003c, \u003e, \u0026 and U+2028, U+2029 become \u2028, \u2029,
// so no "</script>", "<!--" or "<script" of a name ends the element or
// changes how the HTML parser reads it; JSON.parse reads the same value.
// `json` must be valid JSON (those characters then stand only in strings).
std::string script_safe_json(std::string_view json);

// Text for the content of an HTML element: '<', '>', '&', '"' and '\'' as
// character references, control characters and bytes that are not UTF-8 as
// U+FFFD.
std::string html_text(std::string_view s);

// The whole page as text: the viewer's script and three.js inlined, `data`
// (one JSON object) embedded through script_safe_json, `title` through
// html_text.  With `connect_self` its Content-Security-Policy also lets it
// send requests to the server it came from (the page of 'minksum play').
std::string page_html(const std::string& title, const std::string& data, bool connect_self = false);

// Writes the page atomically: `data` is one JSON object (it holds "kind":
// "sum", "polytope", "solid", "cgm" or "motion"); OutputError when the file cannot be written.
void write_page(const std::string& path, const std::string& title, const std::string& data);

// The page of 'minksum cgm --html': the map g of `shown` (P, or P ⊕ Q when
// `operands` names P and Q; then `provenance` gives each facet's origin, or
// is empty) on the unit cube, beside the polytope.  Per map: "xyz" (each
// vertex lifted to the cube, doubles), "exact" (its exact 2D coordinates in
// the map's axes), "facet" (the facet mapped to it, -1 for an artificial
// vertex), "origin" (that facet's provenance, with operands), "edges" (u, v,
// kind per edge: 0 artificial, 1 real, 2 of P, 3 of Q, 4 of both), "counts".
void write_cgm_page(const std::string& path, const std::string& title, const CubicalGaussianMap& g,
                    const ConvexPolytope& shown, const std::vector<std::string>& operands,
                    const std::vector<FacetProvenance>& provenance);

// The "maps" array of a page of a Cubical Gaussian Map (write_cgm_page
// above), appended; `provenance` (of the facets of g's polytope), when given,
// adds "origin".
void append_cgm_maps_json(std::string& out, const CubicalGaussianMap& g,
                          const std::vector<FacetProvenance>* provenance = nullptr);

// One frame of 'minksum simulate': the robot's translation and orientation
// (index into the quaternions), its state (0 separate, 1 touching, 2
// penetrating) and the exact squared distance or depth.
struct MotionFrame {
  Point3 translation;
  std::size_t orientation = 0;
  int status = 0;
  Rational value;
  int pass = 1;
};

// The page of 'minksum simulate --html': the obstacle, the robot in every
// frame (orientation k is `robot` rotated by turns[k]; the drawing rotates
// the exact vertices, then rounds), "events" (the frames where the state
// changes), played back at `fps` frames per second.
// With `c_obstacles` (one per orientation: Q ⊕ (−P_k) = −M_k, the set of
// translations u where P_k + u meets Q), the page shows the one of the
// current frame and the robot's reference point u.
void write_motion_page(const std::string& path, const std::string& title, const ConvexPolytope& obstacle,
                       const ConvexPolytope& robot, const std::vector<Quaternion>& turns,
                       const std::vector<MotionFrame>& frames, int fps,
                       const std::vector<ConvexPolytope>& c_obstacles = {});

}  // namespace minksum::cli
