// libFuzzer target for the option values of `minksum query` (cli/pose.cpp):
// --translate-p/-q and --direction (X,Y,Z) and --rotate-p/-q (A,B,C,D).  Any
// text gives a value or a reason; a vector read prints back exactly
// (format_exact) and reads back to the same point.
#include <minksum/kernel.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "pose.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace minksum;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string why;
  if (const auto v = cli::parse_vector(text, &why)) {
    const std::string printed = format_exact(v->x) + "," + format_exact(v->y) + "," + format_exact(v->z);
    const auto again = cli::parse_vector(printed, &why);
    if (!again || !(*again == *v)) {
      std::fprintf(stderr, "property violated: a vector does not read back from its exact text\n");
      std::abort();
    }
  } else if (why.empty()) {
    std::fprintf(stderr, "property violated: a refused vector has no reason\n");
    std::abort();
  }
  why.clear();
  if (!cli::parse_quaternion(text, &why) && why.empty()) {
    std::fprintf(stderr, "property violated: a refused rotation has no reason\n");
    std::abort();
  }
  return 0;
}
