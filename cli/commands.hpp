// The minksum subcommands: each file cli/cmd_<name>.cpp defines one run_<name>.
// To add a command: declare it here and add a line to kCommands in main.cpp.
#pragma once

#include <string>
#include <vector>

namespace minksum::cli {

// Each returns the exit status; throws UsageError / InputError / OutputError.
int run_sum(const std::vector<std::string>& args);
int run_erode(const std::vector<std::string>& args);  // cmd_morphology.cpp
int run_open(const std::vector<std::string>& args);
int run_close(const std::vector<std::string>& args);
int run_stats(const std::vector<std::string>& args);
int run_gen(const std::vector<std::string>& args);
int run_query(const std::vector<std::string>& args);
int run_simulate(const std::vector<std::string>& args);
int run_cgm(const std::vector<std::string>& args);
int run_batch(const std::vector<std::string>& args);
int run_convert(const std::vector<std::string>& args);
int run_view(const std::vector<std::string>& args);
int run_play(const std::vector<std::string>& args);

}  // namespace minksum::cli
