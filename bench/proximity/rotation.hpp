// The rotation section of bench_proximity (rotation.cpp).
#pragma once

// bench_proximity --rotation [--poses N] [--meshes DIR]: prints the section's
// markdown tables on stdout; returns the exit status.
int rotation_section(int argc, char** argv);
