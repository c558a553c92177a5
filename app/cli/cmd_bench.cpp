// animorph-cli bench: runs the registered benchmarks and prints a table.
#include <cstdio>
#include <iostream>

#include "app/cli/bench/bench.h"
#include "app/cli/cli_command.h"

namespace animorph::bench {
std::vector<BenchInfo>& benchRegistry() {
  static std::vector<BenchInfo> benches;
  return benches;
}
}  // namespace animorph::bench

namespace {

int runBench(const std::vector<std::string>& args) {
  using namespace animorph::bench;
  Options opt;
  bool list = false;
  for (const auto& a : args) {
    if (a == "--quick") opt.quick = true;
    else if (a == "--gpu") opt.gpu = true;
    else if (a == "--list") list = true;
    else if (!a.empty() && a[0] == '-') return animorph::cli::fail("bench", "unknown option " + a, 2);
    else opt.filters.push_back(a);
  }
  if (list) {
    for (const auto& b : benchRegistry()) std::printf("%-20s %s\n", b.name, b.summary);
    return 0;
  }
  int ran = 0;
  std::printf("%-52s %12s %-8s %-14s %s\n", "benchmark", "value", "unit", "target", "note");
  for (const auto& b : benchRegistry()) {
    bool match = opt.filters.empty();
    for (const auto& f : opt.filters) match |= std::string(b.name).find(f) != std::string::npos;
    if (!match) continue;
    ++ran;
    for (const Row& r : b.run(opt)) {
      std::printf("%-52s %12.3f %-8s %-14s %s\n", (std::string(b.name) + ": " + r.name).c_str(), r.value,
                  r.unit.c_str(), r.target.c_str(), r.note.c_str());
      std::fflush(stdout);
    }
  }
  if (ran == 0) return animorph::cli::fail("bench", "no benchmark matches (see --list)", 2);
  return 0;
}

}  // namespace

ANIMORPH_CLI_COMMAND("bench", "run the benchmarks and print their figures",
                     "usage: animorph-cli bench [NAME...] [--quick] [--gpu] [--list]\n"
                     "  Runs the benchmarks (all, or those whose name contains NAME) and prints\n"
                     "  one row per figure: value, unit, the target from the issue, and a note.\n"
                     "  Baselines are measured in the same run. --quick uses smaller sizes.\n",
                     runBench);
