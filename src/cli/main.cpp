// soundpaint: command-line front end (contract: README.md, "Command line").
// Parses, calls the library, reports; the work lives in the library.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "soundpaint/result.h"

namespace {

constexpr const char* kUsage =
    "usage: soundpaint <command> [options]\n"
    "\n"
    "Makes game sound visible: sources cast rays through a glTF scene and\n"
    "leave coloured indicators where they strike surfaces.\n"
    "\n"
    "commands:\n"
    "  simulate SCENE   run the ray model for N steps; write indicators / stats\n"
    "  info SCENE       print triangles, layers, sources, listener and BVH facts\n"
    "  render SCENE     simulate N steps, then draw the scene and its indicators to a PNG\n"
    "  check SCENE      does the level suit the model? open meshes, flipped faces, units, a probe\n"
    "  view SCENE       a window: fly through the level and watch sound travel, live\n"
    "\n"
    "Run 'soundpaint <command> --help' for the options of a command.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(kUsage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "simulate") return sp::cli::run_simulate(args);
    if (command == "info") return sp::cli::run_info(args);
    if (command == "render") return sp::cli::run_render(args);
    if (command == "check") return sp::cli::run_check(args);
    if (command == "view") return sp::cli::run_view(args);
    std::fprintf(stderr, "soundpaint: error: unknown command '%s' (try 'soundpaint --help')\n", command.c_str());
    return 2;
  } catch (const sp::Exception& e) {
    std::fprintf(stderr, "soundpaint: error: %s\n", e.what());
    return e.error().code == sp::ErrorCode::InvalidArgument ? 2 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "soundpaint: error: %s\n", e.what());
    return 1;
  }
}
