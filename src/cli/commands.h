// The subcommands of the soundpaint executable. Each returns the exit status
// and throws sp::Exception for bad input, which main() reports in one line.
#pragma once

#include <string>
#include <vector>

namespace sp::cli {

int run_simulate(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_render(const std::vector<std::string>& args);
int run_check(const std::vector<std::string>& args);
int run_view(const std::vector<std::string>& args);

}  // namespace sp::cli
