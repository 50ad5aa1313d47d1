// soundpaint: command-line front end (contract: README.md, "Command line").
// Parses, calls the library, reports; the work lives in the library.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/printable_text.h"
#include "io/standard_streams.h"
#include "io/temporary_files.h"
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

int run_command(std::vector<std::string> args) {
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
    std::fprintf(stderr, "soundpaint: error: unknown command '%s' (try 'soundpaint --help')\n",
                 sp::printable_text(command).c_str());
    return 2;
  } catch (const sp::Exception& e) {
    // Messages quote names from files (escaped where they are made); once
    // more here, so that no message can reach the terminal raw.
    std::fprintf(stderr, "soundpaint: error: %s\n", sp::printable_text(e.what()).c_str());
    return e.error().code == sp::ErrorCode::InvalidArgument ? 2 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "soundpaint: error: %s\n", sp::printable_text(e.what()).c_str());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Before any file is opened: a closed descriptor 1 must not become the
  // next output file.
  if (!sp::reserve_standard_streams()) return 1;
  sp::remove_temporary_files_on_fatal_signals();
  const int status = run_command(std::vector<std::string>(argv + 1, argv + argc));
  // Output lost on a full disk or a closed stdout is a failure, not a 0. A
  // command that failed has said why already (a write to `-` that broke,
  // say): the stream's error would only repeat it, less clearly.
  if (const auto error = sp::standard_output_error()) {
    if (status != 0) return status;
    std::fprintf(stderr, "soundpaint: error: cannot write standard output: %s\n", error->c_str());
    return 1;
  }
  return status;
}
