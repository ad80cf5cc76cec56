// libFuzzer target for one reader (MINKSUM_FUZZ_FORMAT: off, obj, ply, stl or
// wrl), through the public API reading from memory.  Any input must give a
// mesh or an InputError, nothing else (no crash, no other exception, no
// sanitizer report, no hang); a mesh read must survive exact OFF text
// unchanged (write, read back, same points and faces), and validating it must
// give a polytope or an InputError.
#include <minksum/error.hpp>
#include <minksum/io.hpp>
#include <minksum/polytope.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "property violated: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace minksum;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  Mesh mesh;
  try {
    mesh = read_mesh(in, Format::MINKSUM_FUZZ_FORMAT, "fuzz");
  } catch (const InputError&) {
    return 0;
  }
  std::ostringstream text;
  WriteOptions exact;
  exact.exact = true;
  write_mesh(text, mesh, Format::off, exact);
  if (!mesh.points.empty()) {  // an OFF file with no vertices is refused as empty
    std::istringstream back(text.str());
    const Mesh again = read_mesh(back, Format::off, "round trip");
    check(again.points.size() == mesh.points.size(), "round trip keeps the number of points");
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      check(again.points.exact(i) == mesh.points.exact(i), "round trip keeps every point exactly");
    check(again.faces == mesh.faces, "round trip keeps the faces");
  }
  try {
    const ConvexPolytope p = ConvexPolytope::from_mesh(mesh, "fuzz");
    check(p.num_vertices() - p.num_edges() + p.num_facets() == 2, "a valid polytope has Euler characteristic 2");
  } catch (const InputError&) {
  }
  return 0;
}
