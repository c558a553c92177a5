#pragma once
// A subcommand of animorph-cli. Each lives in its own cmd_*.cpp and registers
// itself with ANIMORPH_CLI_COMMAND, so adding one touches no shared file.
#include <string>
#include <vector>

namespace animorph::cli {

using CommandFn = int (*)(const std::vector<std::string>& args);

struct CommandInfo {
  const char* name;
  const char* summary;  // one line for `animorph-cli --help`
  const char* usage;    // full text for `animorph-cli NAME --help`
  CommandFn run;
};

std::vector<CommandInfo>& registry();

struct Registrar {
  explicit Registrar(CommandInfo info) { registry().push_back(info); }
};

// True if args asks for help; prints usage to stdout.
bool wantsHelp(const std::vector<std::string>& args, const CommandInfo& info);

// Prints "animorph-cli NAME: message" to stderr and returns exit code 1 (or code).
int fail(const char* command, const std::string& message, int code = 1);

}  // namespace animorph::cli

#define ANIMORPH_CLI_CONCAT2(a, b) a##b
#define ANIMORPH_CLI_CONCAT(a, b) ANIMORPH_CLI_CONCAT2(a, b)
#define ANIMORPH_CLI_COMMAND(...) \
  static ::animorph::cli::Registrar ANIMORPH_CLI_CONCAT(animorphCliRegistrar_, __LINE__)({__VA_ARGS__})
