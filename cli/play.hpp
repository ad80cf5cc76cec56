// minksum play P Q: what the command (cli/cmd_play.cpp) and its server
// (cli/play/server.cpp, in the executable minksum-play) share.
#pragma once

#include <minksum/minkowski.hpp>

#include <string>
#include <vector>

namespace minksum::cli {

// The command line of 'minksum play', checked (UsageError otherwise).
struct PlayOptions {
  std::string p, q;   // the operands
  int port = 0;       // 0: a port the system chooses
  bool open = true;   // open the page with xdg-open
  Method method = Method::automatic;
  bool hull = false;
};

// Serves the page until SIGINT or SIGTERM (then returns 0).  Defined only in
// minksum-play; a weak symbol, null in the static command, which runs
// minksum-play instead.
[[gnu::weak]] int run_play_server(const PlayOptions& options);

}  // namespace minksum::cli
