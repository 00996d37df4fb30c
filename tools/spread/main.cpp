// spread: command-line front end of libspread. Subcommands live in cmd_*.cpp.
#include <algorithm>
#include <exception>

#include "tools/spread/command_registry.hpp"
#include "tools/spread/error_exit.hpp"
#include "tools/spread/report_args.hpp"

int main(int argc, char** argv) {
  spread::cli::remember_command_line(argc, argv);
  CLI::App app{"spread: centrifugal fertiliser spreader prediction (libspread " SPREAD_VERSION_STRING ")"};
  app.require_subcommand(1);
  app.set_version_flag("--version", SPREAD_VERSION_STRING);
  int exit_code = spread::cli::kExitOk;
  auto& commands = spread::cli::registered_commands();
  // Static-initialisation order across files is unspecified; sort for a stable --help.
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  for (auto& command : commands) command.setup(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return spread::cli::report_parse_failure(app, e);
  } catch (const std::exception& e) {
    // Commands throw; this is the one place a failure becomes a stderr line and an exit code.
    return spread::cli::report_failure(spread::cli::command_path(app), e);
  }
  return exit_code;
}
