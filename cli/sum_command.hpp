// The minksum command line: `sum`, `erode`, `open` and `close` once their
// options are parsed (cli/cmd_sum.cpp, cli/cmd_morphology.cpp): the operands
// loaded and summed by the library (<minksum/sum.hpp>: the choice between
// kinds of operands is made there), the result written, and its report
// printed as text or JSON.
#pragma once

#include <minksum/sum.hpp>

#include <optional>
#include <string>
#include <vector>

#include "mesh_io.hpp"

namespace minksum::cli {

struct SumCommand {
  std::vector<std::string> names;  // the operands as named: files, catalog names, '-'
  bool hull = false;               // --hull
  std::optional<Format> format;    // --format
  std::optional<MeshOutput> output;
  bool json = false;
  bool scene = false;  // --scene (sum only; operands and sum as one VRML scene)
  SumRequest request;  // operation, method, non-convex method
};

// Loads, computes, writes and reports; returns the exit status.
int run_sum_command(const SumCommand& command);

// One operand named on the command line ('-': standard input in `format`).
Operand load_command_operand(const std::string& spec, bool hull, std::optional<Format> format,
                             LoadPhases* phases = nullptr);

// A sum's report as the one JSON object of `minksum sum --json` (and erode,
// open, close; docs/json.md): `names` as given on the command line (the
// report's own are the files' names in messages), the phases of reading,
// validating and writing added around the computation's, the output and the
// rounding's JSON text.
std::string sum_report_json(const SumReport& report, const std::vector<std::string>& names, const LoadPhases& load,
                            double write_seconds, const std::optional<MeshOutput>& output,
                            const std::string& rounding_json);

}  // namespace minksum::cli
