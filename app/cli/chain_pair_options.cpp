#include "app/cli/chain_pair_options.h"

#include "core/doc/chain_pair_commands.h"

namespace animorph::cli {
namespace {

std::string chainList(const SkeletonChains& chains) {
  std::string out;
  for (const SkeletonChain& c : chains.chains) out += (out.empty() ? "" : ", ") + c.name;
  return out;
}

bool known(const SkeletonChains& chains, const char* side, const std::string& option, const std::string& name,
           std::string& error) {
  if (chainNamed(chains, name) >= 0) return true;
  error = option + ": no " + side + " chain starts at joint '" + name + "' (chains: " + chainList(chains) + ")";
  return false;
}

}  // namespace

bool readChainPairOption(const std::vector<std::string>& args, size_t& i, std::vector<ChainPairEdit>& edits,
                         std::string& error) {
  const std::string& a = args[i];
  if (a == "--auto-all") {
    edits.push_back({ChainPairEdit::Kind::AllAutomatic, {}, {}});
    return true;
  }
  ChainPairEdit::Kind kind;
  if (a == "--pair") kind = ChainPairEdit::Kind::Pair;
  else if (a == "--unpair") kind = ChainPairEdit::Kind::Unpair;
  else if (a == "--auto") kind = ChainPairEdit::Kind::Automatic;
  else return false;
  if (i + 1 >= args.size() || args[i + 1].empty()) {
    error = a + ": expected " + (kind == ChainPairEdit::Kind::Pair ? "SOURCE_JOINT=TARGET_JOINT" : "SOURCE_JOINT");
    return true;
  }
  const std::string v = args[++i];
  ChainPairEdit e{kind, v, {}};
  if (kind == ChainPairEdit::Kind::Pair) {
    const size_t eq = v.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == v.size()) {
      error = a + " " + v + ": expected SOURCE_JOINT=TARGET_JOINT";
      return true;
    }
    e.source = v.substr(0, eq);
    e.target = v.substr(eq + 1);
  }
  edits.push_back(std::move(e));
  return true;
}

bool applyChainPairEdits(const std::vector<ChainPairEdit>& edits, const SkeletonCorrespondence& c,
                         std::vector<ChainPair>& pairs, std::string& error) {
  for (const ChainPairEdit& e : edits) {
    switch (e.kind) {
      case ChainPairEdit::Kind::AllAutomatic: pairs.clear(); break;
      case ChainPairEdit::Kind::Pair:
        if (!known(c.source, "source", "--pair " + e.source + "=" + e.target, e.source, error) ||
            !known(c.target, "target", "--pair " + e.source + "=" + e.target, e.target, error))
          return false;
        setChainPair(pairs, {e.source, e.target});
        break;
      case ChainPairEdit::Kind::Unpair:
        if (!known(c.source, "source", "--unpair " + e.source, e.source, error)) return false;
        setChainPair(pairs, {e.source, std::nullopt});
        break;
      case ChainPairEdit::Kind::Automatic:
        if (!known(c.source, "source", "--auto " + e.source, e.source, error)) return false;
        resetChainPair(pairs, e.source);
        break;
    }
  }
  return true;
}

}  // namespace animorph::cli
