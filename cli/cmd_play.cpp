// minksum play P Q: runs the server of the interactive proximity application,
// the executable minksum-play beside this one (cli/play/server.cpp).  The
// server is a separate executable because it links cpp-httplib, which Debian
// ships as a shared library only, while this command is linked statically
// (it starts faster).  The server takes over this process (exec): the same
// process id, standard output and signals.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "common.hpp"

namespace minksum::cli {

int run_play(const std::vector<std::string>& argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot find the minksum command's own path: " + ec.message());
  const std::string server = (self.parent_path() / "minksum-play").string();
  std::vector<std::string> all = {server};
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
