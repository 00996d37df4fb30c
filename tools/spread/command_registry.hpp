#pragma once
// Subcommands of the `spread` CLI register themselves here at static-initialisation time, so adding a
// command is adding one cmd_<name>.cpp file. Its helpers go in namespace spread::cli::cmd_<name> (an
// anonymous namespace inside it): the files are compiled together in unity batches (CMakeLists.txt), where
// two files' anonymous namespaces at the same level would be one.
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace spread::cli {

// Called once with the top-level app; must add exactly one subcommand and set its callback.
// The callback returns the process exit code through `exit_code`.
using CommandSetup = std::function<void(CLI::App& app, int& exit_code)>;

struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup);
};

struct RegisteredCommand {
  std::string name;
  CommandSetup setup;
};
std::vector<RegisteredCommand>& registered_commands();

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitUsage = 2;    // bad arguments or input (message on stderr names the problem)
inline constexpr int kExitFailure = 1;  // a run that could not complete

}  // namespace spread::cli
