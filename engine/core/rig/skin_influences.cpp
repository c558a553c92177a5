#include "core/rig/skin_influences.h"

#include <algorithm>
#include <cmath>

#include "core/rig/character.h"

namespace animorph {

void packInfluences(std::vector<Influence>& inf, glm::uvec4& j0, glm::vec4& w0, glm::uvec4& j1, glm::vec4& w1,
                    InfluenceStats& stats) {
  j0 = j1 = glm::uvec4(0);
  w0 = w1 = glm::vec4(0.0f);
  // Drop useless entries, then merge repeated joints (exporters write a joint
  // twice with its weight split).
  inf.erase(std::remove_if(inf.begin(), inf.end(),
                           [](const Influence& i) { return !(i.weight > 0.0f) || !std::isfinite(i.weight); }),
            inf.end());
  std::sort(inf.begin(), inf.end(), [](const Influence& a, const Influence& b) { return a.joint < b.joint; });
  size_t out = 0;
  for (size_t i = 0; i < inf.size(); ++i) {
    if (out > 0 && inf[out - 1].joint == inf[i].joint) inf[out - 1].weight += inf[i].weight;
    else inf[out++] = inf[i];
  }
  inf.resize(out);
  if (inf.empty()) {
    ++stats.unweighted;
    w0.x = 1.0f;
    return;
  }
  std::sort(inf.begin(), inf.end(), [](const Influence& a, const Influence& b) {
    return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
  });
  float total = 0.0f;
  for (const auto& i : inf) total += i.weight;
  if (inf.size() > static_cast<size_t>(Mesh::kMaxInfluences)) {
    ++stats.dropped;
    inf.resize(Mesh::kMaxInfluences);
  }
  float kept = 0.0f;
  for (const auto& i : inf) kept += i.weight;
  if (std::abs(total - 1.0f) > kWeightSumTolerance) ++stats.normalised;
  for (size_t k = 0; k < inf.size(); ++k) {
    float w = inf[k].weight / kept;
    if (k < 4) { j0[k] = inf[k].joint; w0[k] = w; }
    else { j1[k - 4] = inf[k].joint; w1[k - 4] = w; }
  }
}

}  // namespace animorph
