// minksum erode / open / close A B: erosion, opening and closing of a solid
// by a convex polytope (docs/nonconvex.md, "Erosion, opening, closing").
#include <minksum/minkowski.hpp>

#include <iostream>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "mesh_io.hpp"
#include "sum_command.hpp"

namespace minksum::cli {

namespace {

const char* kMorphologyHelp = R"(Usage: minksum erode A B [options]
       minksum open A B [options]
       minksum close A B [options]

Offsets of a solid A by a convex polytope B (the structuring element), exact:
  erode   A ⊖ B = { x : x + B ⊆ A }: the points where B, moved there, lies
          inside A (A shrunk by B; it may split into several parts or vanish)
  open    (A ⊖ B) ⊕ B: the union of the copies of B inside A (A's convex
          edges and corners rounded by B)
  close   (A ⊕ B) ⊖ B: A with its concave edges and corners filled by B
          (fillets)
A is a file, a catalog name or '-' (with --format): a closed solid of any
shape and genus (convex or not, several shells allowed), validated as 'minksum
sum' validates its operands; B must be a convex polytope (exit status 3 and
one line naming the problem otherwise).  The result is the exact boundary:
polygons of exact coordinates, one shell per part and per cavity; without
--exact it is written rounded as a valid solid, as 'minksum sum' writes a
non-convex sum.  Erosion is computed as the complement of Aᶜ ⊕ (−B) by the
boundary sweep of A's surface (docs/nonconvex.md); for a convex A, as the
intersection of A's facet half-spaces moved inwards by B's support, a convex
polytope written as a convex sum is.  Opening and closing are an erosion and
a sum in turn.

An empty result (B fits nowhere inside A, for erode and open) is not an
error: the summary says "= empty", --json has "empty": true and "volume":
"0", the exit status is 0, and -o OUT writes a file of OUT's format with no
faces (OFF "0 0 0", an STL with no triangles, ...), which 'minksum stats'
refuses as not a solid.

Options:
  -o, --output OUT   write the result to OUT ({formats}), or to
                     standard output for '-' (the summary or JSON then goes
                     to stderr); written to a temporary name and renamed
  --format F         {format_names}: the format of '-' and of names
                     without a known extension
  --exact            write exact rationals (p/q or integers; {exact_formats})
  --binary           binary {binary_formats} output
  --method walk|chms the construction of the sweep's pieces: from their
                     Gaussian maps (walk, the default) or as exact hulls of
                     their vertex sums (chms); the same exact result
  --json             print one JSON object: "operation" ("erosion",
                     "opening", "closing"), "empty", the counts (vertices,
                     edges, facets), "volume" (exact, a string) and
                     "volume_double", "union" (shells, clips, non-manifold
                     edges, dropped components), the work done ("pieces",
                     "pairs", "candidate_facets", "culled_facets"), the
                     phases (read, validate, decompose, pairs, union,
                     boundary, write), "seconds", "a", "b", "operands",
                     "output" and "rounding", as 'minksum sum --json' gives
                     them for a non-convex sum; for open and close the work
                     and times of both steps together

Progress: on a terminal, a sum taking more than a second shows its phase on
one line of stderr, erased when done; Ctrl-C stops between steps.

Examples:
  minksum erode lshape cube@scale:1/4 --exact -o eroded.off
  minksum open tube cube@scale:1/4 --json
  minksum close lshape sphere:2@scale:1/4 -o filleted.stl --binary
)";

int run_morphology(const std::vector<std::string>& argv, const char* command, SumOperation operation) {
  const Args a = parse_args(argv, command,
                            {{"--output", "-o", true}, {"--method", "", true}, {"--exact"}, {"--binary"},
                             {"--json"}, kFormatOption});
  if (a.help) {
    std::cout << expand_help(kMorphologyHelp);
    return 0;
  }
  if (a.positional.size() != 2)
    throw UsageError(std::string("'") + command + "' needs two operands A B (see 'minksum " + command + " --help')");
  const std::string method_text = a.value_or("--method", "walk");
  const auto method = parse_method(method_text);
  if (!method || (*method != Method::walk && *method != Method::chms && *method != Method::automatic))
    throw UsageError("unknown --method '" + method_text + "' for '" + command + "' (walk, chms)");
  const auto format = format_option(a);
  const std::optional<MeshOutput> output = output_option(a);
  SumCommand c;
  c.names = a.positional;
  c.format = format;
  c.output = output;
  c.json = a.flag("--json");
  c.request.operation = operation;
  c.request.method = *method;
  return run_sum_command(c);
}

}  // namespace

int run_erode(const std::vector<std::string>& args) { return run_morphology(args, "erode", SumOperation::erode); }
int run_open(const std::vector<std::string>& args) { return run_morphology(args, "open", SumOperation::open); }
int run_close(const std::vector<std::string>& args) { return run_morphology(args, "close", SumOperation::close); }

}  // namespace minksum::cli
