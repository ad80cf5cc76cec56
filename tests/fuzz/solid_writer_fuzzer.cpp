// libFuzzer target for the writer of non-convex solids: each input is one
// case of solid_writer_case.hpp; a violated property throws, and the
// uncaught exception is the finding.
#include "solid_writer_case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  minksum_fuzz::solid_writer_case(data, size);
  return 0;
}
