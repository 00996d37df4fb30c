#pragma once
// The one place the `spread` CLI turns a failure into its exit code and stderr line. Commands throw;
// main() catches once and calls these. The kinds of spread::Error (libspread/core/error.hpp) decide:
// a problem with what the user gave (a scene, a table or tray file, an option) exits kExitUsage; a
// read/write failure of a good input, or anything unexpected, exits kExitFailure.
#include <CLI/CLI.hpp>

#include <exception>
#include <string>

#include "libspread/core/error.hpp"

namespace spread::cli {

// A bad command-line value; the message names the option (exit kExitUsage).
class BadInput : public Error {
 public:
  explicit BadInput(const std::string& message) : Error(ErrorKind::kArgument, {}, message) {}
};

// kExitUsage or kExitFailure for a failure thrown by a command.
int exit_code_for(const std::exception& failure);

// "spread calibrate tray" for the subcommand chain parsed on `app` (just "spread" before one was).
std::string command_path(const CLI::App& app);

// Writes "<command>: error: <what>" to stderr and returns exit_code_for(failure).
int report_failure(const std::string& command, const std::exception& failure);

}  // namespace spread::cli
