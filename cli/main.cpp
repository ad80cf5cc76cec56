// The `minksum` command: dispatches to one file per subcommand (cli/cmd_*.cpp).
//
// Exit status: 0 success, 1 internal error or failed output write,
// 2 bad usage, 3 bad input data.
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "memory.hpp"

using namespace minksum;
using namespace minksum::cli;

namespace {

constexpr const char* kVersion = "0.1.0";

const char* kMainHelp = R"(minksum — exact Minkowski sums of convex polyhedra in 3D

Usage:
  minksum sum A B [C ...] [-o OUT] [--method M] [--exact] [--binary] [--json]
                [--hull] [--scene] [--nonconvex-method sweep|decomposition] [--format F]
  minksum erode|open|close A B [-o OUT] [--method walk|chms] [--exact]
                [--binary] [--json] [--format F]
  minksum stats P [--json] [--hull] [--format F]
  minksum gen NAME -o OUT [--exact] [--binary] [--format F]
  minksum convert IN -o OUT [--hull] [--exact] [--binary] [--format F]
                [--from F] [--json]
  minksum query collide|distance|depth|ddepth P Q [--translate-p X,Y,Z]
                [--translate-q X,Y,Z] [--rotate-p A,B,C,D] [--rotate-q A,B,C,D]
                [--direction X,Y,Z] [--method M] [--trajectory FILE] [--json]
                [--hull] [--format F]
  minksum simulate [--obstacle Q] [--robot P] [--frames N] [--turn A,B,C,D]
                [-o OUT.svg] [--html OUT.html] [--show-m] [--json] [--hull]
  minksum cgm P [Q] [--svg OUT.svg] [--html OUT.html] [-o OUT.wrl] [--stats]
                [--json] [--hull] [--format F]
  minksum view A [B] -o OUT.html [--method M] [--hull] [--title T] [--json]
  minksum view SCENE.wrl -o OUT.html [--title T] [--json]
  minksum play P Q [--port N] [--no-open] [--method M] [--hull]
  minksum batch [FILE] [--threads N] [--method M] [--hull]
  minksum COMMAND --help          help on one command
  minksum --version

A, B, P are files ({formats}, format by extension or --format
{format_names}), '-' for a mesh on standard input, or names of
built-in polytopes such as cube, sphere:4, dioctagonal:17, random:1000:7,
box:1:2:3, sphere:3@rot:5 (see 'minksum gen --help' for the whole catalog).
Files take the catalog's transforms too: part.stl@neg, part.stl@scale:2@rot:5.
-o - writes the mesh to standard output (with --format; the summary then goes
to stderr).  What minksum writes reads back as a valid convex polytope, or,
for a non-convex result, as a valid closed solid: sum, stats, convert and view
take closed solids that are not convex (docs/nonconvex.md), and erode, open and
close offset such a solid inwards, or both ways, by a convex B.

Every computation is exact: coordinates are rationals, every geometric
decision is the sign of an exact polynomial.

Exit status: 0 success, 1 internal error or output not writable,
2 bad usage, 3 bad input data (one line on stderr names the file, the place
and the problem).
)";

struct Command {
  const char* name;
  int (*run)(const std::vector<std::string>&);
};
constexpr Command kCommands[] = {
    {"sum", run_sum},
    {"erode", run_erode},
    {"open", run_open},
    {"close", run_close},
    {"stats", run_stats},
    {"gen", run_gen},
    {"query", run_query},
    {"simulate", run_simulate},
    {"cgm", run_cgm},
    {"batch", run_batch},
    {"convert", run_convert},
    {"view", run_view},
    {"play", run_play},
};

}  // namespace

namespace {

int run_command(const std::vector<std::string>& args) {
  try {
    if (args.empty()) {
      std::cerr << expand_help(kMainHelp);
      return 2;
    }
    const std::string command = args[0];
    std::vector<std::string> rest(args.begin() + 1, args.end());
    if (command == "-h" || command == "--help" || command == "help") {
      if (!rest.empty())
        for (const auto& c : kCommands)
          if (rest[0] == c.name) return c.run({"--help"});
      std::cout << expand_help(kMainHelp);
      return 0;
    }
    if (command == "--version" || command == "version") {
      std::cout << "minksum " << kVersion << "\n";
      return 0;
    }
    for (const auto& c : kCommands)
      if (command == c.name) return c.run(rest);
    throw UsageError("unknown command '" + command + "' (see 'minksum --help')");
  } catch (const UsageError& e) {
    std::cerr << "minksum: " << printable(e.what()) << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "minksum: " << printable(e.what()) << "\n";
    return 3;
  } catch (const OutputError& e) {
    std::cerr << "minksum: " << printable(e.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "minksum: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "minksum: internal error: " << printable(e.what()) << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  tune_memory();
  pool_gmp_memory();
  std::vector<std::string> args(argv + 1, argv + argc);
  std::ios::sync_with_stdio(false);
  int status = run_command(args);
  // Nothing is reported as success that was not written: standard output is
  // flushed and checked here (a full disk, /dev/full, a closed pipe), and a
  // failed write to standard error (where nothing more can be said) fails too.
  // (After a failure, whose one line is already printed, nothing more is said.)
  if (status == 0) {
    try {
      check_stdout();
    } catch (const OutputError& e) {
      std::cerr << "minksum: " << e.what() << "\n";
      status = 1;
    }
  }
  if (!std::cerr && status == 0) status = 1;
  return status;
}
