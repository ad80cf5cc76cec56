// Compiled with the include context of one layer (see tests/CMakeLists.txt):
// the header named by MINKSUM_PROBE_HEADER must, or must not, be visible.
#include MINKSUM_PROBE_HEADER

int minksum_layer_probe = 0;
