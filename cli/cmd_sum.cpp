// minksum sum A B: the Minkowski sum.
#include <minksum/io.hpp>

#include <iostream>
#include <optional>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "sum_command.hpp"

namespace minksum::cli {

namespace {

const char* kSumHelp = R"(Usage: minksum sum A B [C ...] [options]

Compute the Minkowski sum A ⊕ B = { a + b : a in A, b in B } exactly and print
a summary (or JSON).  The operands are files, catalog names, or '-' for a mesh
on standard input (with --format).  With more than two operands the sum is
A ⊕ B ⊕ C ⊕ ..., taken left to right with the same options.

Options:
  -o, --output OUT   write the sum to OUT ({formats}), or
                     to standard output for '-' (the summary or JSON then
                     goes to stderr); a file is written to a temporary name
                     and renamed when complete
  --format F         {format_names}: the format of '-' and of names
                     without a known extension
  --method M         {methods}.
{method_summaries}
                     All are exact and give the same polytope.
  --exact            write coordinates as exact rationals (p/q or integers);
                     default: shortest text that reads back to the nearest
                     double.  Only {exact_formats} can hold rationals.
  --binary           binary {binary_formats} output
  --scene            with -o OUT.wrl: write a VRML scene (docs/vrml.md) that
                     holds the operands and the sum, each an ExactPolyhedron
                     node (DEF A, B, C, ... and S; operands after R are
                     T to Z, then P26, P27, ...), instead of the sum alone;
                     exact coordinates with --exact, else the nearest doubles
                     as for a .wrl file ('minksum view OUT.wrl -o page.html'
                     shows it)
  --hull             take the convex hull of each operand's points instead
                     of requiring a valid convex mesh (point clouds, and
                     non-convex files or catalog solids); points spanning
                     fewer than 3 dimensions give a point, a segment or a
                     polygon
  --json             print one JSON object: dimension (3 for a polytope, 2,
                     1, 0 for a polygon, segment, point), kind (polytope,
                     polygon, segment, point; solid for a non-convex sum),
                     vertices, edges, facets, method,
                     seconds (the computation alone, not the I/O), phases
                     (seconds spent reading the operands, validating them,
                     computing the sum, making its explicit polytope, and
                     writing OUT), volume (exact rational as a string), the
                     operands' names and counts ("operands"; also "a" and "b"
                     for two), and "rounding" (below)

Sweeps: an operand may be a point, a segment or a flat convex polygon: a
catalog name (point:X,Y,Z, segment:X,Y,Z:X,Y,Z, polygon:N, square, with @
transforms), a file holding one face, or points spanning fewer than 3
dimensions with --hull.  A polytope ⊕ a segment is the solid the polytope
sweeps along it; two lower-dimensional operands give a point, a segment, a
polygon or a polytope ("dimension" in --json, "kind" its name, "route" how it
was made).  Only walk (the default) and chms take them.  A polygon result is
written as one face, a point or a segment as its points without faces
(exactly: never rounded; not to STL).  See docs/sweeps.md.

Rounding: the file written always reads back as a valid convex polytope.
Without --exact, coordinates that are not doubles (binary STL: 32-bit floats)
are rounded to the nearest ones; facets no longer planar are split along
convex folds, and when that is not enough the exact convex hull of the
rounded vertices is written.  A note on stderr (and "rounding" in --json:
coordinates rounded, largest vertex displacement, facets split, hull taken,
vertices merged and dropped) says so.  A coordinate beyond the format's range,
or a solid that rounding collapses, is refused with exit status 1 and one line
naming the fix.

Non-convex operands: a file or catalog solid (tube, lshape, ring:N, star:N,
gear:N) that is not convex must be a closed solid: a closed, consistently
oriented 2-manifold surface of planar faces, without self-intersection, facing
outwards (else exit status 3 and one line naming the problem).  The sum of two
operands, one or both non-convex, is exact (docs/nonconvex.md): by default the
boundary sweep, which sums each triangle of the non-convex operand's surface
with the other operand (in parallel; a non-convex other operand is cut into
convex pieces first), keeps only the facets that can be on the boundary and
writes the exact union (polygons of exact coordinates, cavities as inner
shells).  Without --exact, coordinates that are not doubles (binary STL:
floats) are rounded and the result written as a valid solid: points that round
together merged, degenerate triangles removed, where the sum touches itself
its parts moved apart, and where rounding made faces cross the points there
snapped to a coarser grid; a note gives the largest displacement.  Only a sum
that cannot be represented (beyond the format's range, or thinner than its
spacing everywhere) is refused (exit 1) naming --exact.  --json then has a
convex sum's counts, "dimension", "kind" ("solid"), "volume", "a", "b",
"operands", "output" and "rounding" (null or {"coordinates": N,
"max_displacement": D, "grid": G}), "method":
"nonconvex", and "nonconvex_method", "swept", "pieces", "pairs",
"pair_vertices", "pair_facets", "candidate_facets", "culled_facets" and
"union" (clips, shells, non-manifold edges, dropped components) and the
phases decompose, pairs, union and boundary.
  --nonconvex-method sweep|decomposition
                     sweep (default), or Hachenberger's decomposition: both
                     operands cut into convex pieces (CGAL), every pair of
                     pieces summed, then the same union; slower on solids
                     with many reflex edges, the same exact result
--method sums the convex pieces of the decomposition (walk by default); the
sweep's pieces, a triangle and a polytope, are built from their Gaussian maps,
or with --method chms as the exact hull of their vertex sums ("pair_method" in
--json names the construction: "gaussian_map", "chms" or a method); a sum with
a non-convex operand takes exactly two operands.

Progress: when stderr is a terminal and the sum takes more than a second, one
line is rewritten in place on stderr every 0.2 s and erased when the sum is
done: the phase, the fraction done when the method measures it, and the time
so far, for example
    minksum sum: walk 42% (2.3 s)
Nothing is printed when stderr is redirected to a file or a pipe.
)";

}  // namespace

int run_sum(const std::vector<std::string>& argv) {
  const Args a = parse_args(argv, "sum",
                            {{"--output", "-o", true}, {"--method", "", true}, {"--exact"}, {"--binary"},
                             {"--json"}, {"--hull"}, {"--scene"}, {"--nonconvex-method", "", true}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kSumHelp);
    return 0;
  }
  if (a.positional.size() < 2)
    throw UsageError("'sum' needs two or more operands A B [C ...] (see 'minksum sum --help')");
  const std::string method_text = a.value_or("--method", "auto");
  const bool json = a.flag("--json"), hull = a.flag("--hull");
  auto method = parse_method(method_text);
  if (!method)
    throw UsageError("unknown method '" + method_text + "' (" + method_list() + ")");
  if (!method_available(*method))
    throw UsageError(std::string("method '") + method_name(*method) + "' is not implemented in this version of minksum");
  const std::string nonconvex_text = a.value_or("--nonconvex-method", "sweep");
  NonconvexMethod nonconvex_method = NonconvexMethod::sweep;
  if (nonconvex_text == "decomposition")
    nonconvex_method = NonconvexMethod::decomposition;
  else if (nonconvex_text != "sweep")
    throw UsageError("unknown --nonconvex-method '" + nonconvex_text + "' (sweep, decomposition)");
  const auto format = format_option(a);
  const std::optional<MeshOutput> output = output_option(a);
  const bool scene = a.flag("--scene");
  if (scene && (!output || output->format != Format::wrl))
    throw UsageError("--scene writes a VRML scene: it needs -o OUT.wrl (or -o - --format wrl)");
  SumCommand command;
  command.names = a.positional;
  command.hull = hull;
  command.format = format;
  command.output = output;
  command.json = json;
  command.scene = scene;
  command.request.method = *method;
  command.request.nonconvex = nonconvex_method;
  return run_sum_command(command);
}

}  // namespace minksum::cli
