#include "tools/spread/error_exit.hpp"

#include <iostream>
#include <regex>
#include <stdexcept>

#include "libspread/core/error.hpp"
#include "tools/spread/command_registry.hpp"

namespace spread::cli {

int exit_code_for(const std::exception& failure) {
  if (const auto* error = dynamic_cast<const spread::Error*>(&failure)) {
    return error->kind() == ErrorKind::kIo ? kExitFailure : kExitUsage;
  }
  // Library preconditions on values the user chose (a disc speed outside the table, an impossible
  // width) still arrive as std::invalid_argument: still the user's input.
  if (dynamic_cast<const std::invalid_argument*>(&failure) != nullptr) return kExitUsage;
  return kExitFailure;
}

std::string command_path(const CLI::App& app) {
  std::string path = "spread";
  const CLI::App* level = &app;
  while (level != nullptr) {
    const auto parsed = level->get_subcommands();
    if (parsed.empty()) break;
    level = parsed.front();
    path += " " + level->get_name();
  }
  return path;
}

int report_failure(const std::string& command, const std::exception& failure) {
  std::cerr << command << ": error: " << failure.what() << "\n";
  return exit_code_for(failure);
}

std::string parse_failure_message(const CLI::ParseError& failure) {
  std::string message = failure.what();
  const std::regex conversion(R"(^Could not convert: (\S+) = (.*)$)");
  std::smatch m;
  if (std::regex_match(message, m, conversion)) {
    message = m[1].str() + ": '" + m[2].str() + "' is not a value it takes (a number without its unit; see --help)";
  }
  // One line, whatever CLI11 says.
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return message;
}

int report_parse_failure(const CLI::App& app, const CLI::ParseError& failure) {
  if (failure.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
    return app.exit(failure) == 0 ? kExitOk : kExitUsage;
  }
  std::cerr << command_path(app) << ": error: " << parse_failure_message(failure) << "\n";
  return kExitUsage;
}

}  // namespace spread::cli
