// libFuzzer target for the trajectory lines of `minksum query --trajectory`
// (cli/pose.cpp), fed line by line as the command reads them: each line gives
// a pose, nothing (blank, comment) or an InputError whose message, once
// escaped for printing, is one line without control characters.
#include <minksum/error.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "pose.hpp"
#include "text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace minksum;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  long line_no = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    ++line_no;
    try {
      (void)cli::parse_pose_line(text.substr(start, end - start), "fuzz", line_no);
    } catch (const InputError& e) {
      const std::string shown = cli::printable(e.what());
      for (unsigned char c : shown)
        if (c < 0x20 || c == 0x7f) {
          std::fprintf(stderr, "property violated: a control character in a printed message\n");
          std::abort();
        }
    }
    start = end + 1;
  }
  return 0;
}
