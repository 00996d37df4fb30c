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

// A command line CLI11 cannot parse, in the same one-line format with kExitUsage: "Could not convert:
// --mass = 25kg" becomes "--mass: '25kg' is not a value it takes (a number without its unit; see
// --help)", CLI11's other messages are kept on one line. --help and --version (not failures) print as
// CLI11 prints them and return kExitOk.
int report_parse_failure(const CLI::App& app, const CLI::ParseError& failure);

// The message of report_parse_failure, without the command: one line.
std::string parse_failure_message(const CLI::ParseError& failure);

}  // namespace spread::cli
