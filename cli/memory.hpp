// The command's memory set-up (memory.cpp).
#pragma once

namespace minksum::cli {

// Keep freed memory for reuse and back the heap with transparent huge pages
// where the kernel offers them on request, so that a run touches far fewer
// fresh pages.  Best effort: any call that fails leaves the defaults.
void tune_memory();

}  // namespace minksum::cli
