#include "util/test_characters.h"

#include <fstream>

namespace animorph::test {

std::vector<nlohmann::json> testCharacterEntries(const std::string& dir, const std::string& format) {
  std::ifstream in(dir + "/manifest.json");
  if (!in) return {};
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  std::vector<nlohmann::json> out;
  if (manifest.is_discarded() || !manifest.contains("files")) return out;
  for (const auto& e : manifest.at("files"))
    if (format.empty() || e.value("format", "") == format) out.push_back(e);
  return out;
}

}  // namespace animorph::test
