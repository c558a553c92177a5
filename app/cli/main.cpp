// animorph-cli: dispatches to the registered subcommands.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "app/cli/cli_command.h"

namespace animorph::cli {

std::vector<CommandInfo>& registry() {
  static std::vector<CommandInfo> commands;
  return commands;
}

bool wantsHelp(const std::vector<std::string>& args, const CommandInfo& info) {
  for (const auto& a : args)
    if (a == "--help" || a == "-h") {
      std::cout << info.usage;
      return true;
    }
  return false;
}

int fail(const char* command, const std::string& message, int code) {
  std::cerr << "animorph-cli " << command << ": " << message << "\n";
  return code;
}

}  // namespace animorph::cli

namespace {

void printHelp() {
  auto cmds = animorph::cli::registry();
  std::sort(cmds.begin(), cmds.end(), [](auto& a, auto& b) { return std::strcmp(a.name, b.name) < 0; });
  std::cout << "animorph-cli: headless Animorph (metamorphosis of animated 3D characters)\n\n"
               "usage: animorph-cli COMMAND [ARGS...]   (animorph-cli COMMAND --help for details)\n\ncommands:\n";
  for (const auto& c : cmds) std::printf("  %-15s %s\n", c.name, c.summary);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    printHelp();
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "animorph-cli 0.1.0\n";
    return 0;
  }
  std::vector<std::string> args(argv + 2, argv + argc);
  for (const auto& c : animorph::cli::registry())
    if (c.name == std::string(argv[1])) {
      if (animorph::cli::wantsHelp(args, c)) return 0;
      try {
        return c.run(args);
      } catch (const std::exception& e) {
        return animorph::cli::fail(c.name, std::string("internal error: ") + e.what(), 3);
      }
    }
  std::cerr << "animorph-cli: unknown command '" << argv[1] << "' (see animorph-cli --help)\n";
  return 2;
}
