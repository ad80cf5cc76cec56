// minksum play P Q: the interactive proximity application
// (cli/play/server.cpp).  Its server links cpp-httplib, which Debian ships as
// a shared library only, while the command is linked statically (it starts
// faster): so the build makes a second, dynamically linked executable,
// minksum-play, from the same sources plus the server, and 'minksum play
// ARGS' becomes 'minksum-play play ARGS' (exec: the same process id,
// standard output and signals).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"

namespace minksum::cli {

// Defined only in minksum-play (cli/play/server.cpp); null in the command.
[[gnu::weak]] int run_play_server(const std::vector<std::string>& argv);

int run_play(const std::vector<std::string>& argv) {
  if (run_play_server) return run_play_server(argv);
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot find the minksum command's own path: " + ec.message());
  const std::string server = (self.parent_path() / "minksum-play").string();
  std::vector<std::string> all = {server, "play"};
  all.insert(all.end(), argv.begin(), argv.end());
  std::vector<char*> args;
  for (auto& a : all) args.push_back(a.data());
  args.push_back(nullptr);
  std::cout.flush();
  ::execv(server.c_str(), args.data());
  throw OutputError("cannot run the server of 'minksum play', " + server + ": " + std::strerror(errno) +
                    " (it is built and installed beside minksum)");
}

}  // namespace minksum::cli
