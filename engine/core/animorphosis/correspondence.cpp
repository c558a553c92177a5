#include "core/animorphosis/correspondence.h"

#include <algorithm>
#include <cmath>

namespace animorph {

int CorrespondenceGraph::find(int nodeA, int nodeB) const {
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].nodeA == nodeA && links[i].nodeB == nodeB) return int(i);
  return -1;
}

int CorrespondenceGraph::findSuggestion(int nodeA, int nodeB) const {
  for (size_t i = 0; i < suggestions.size(); ++i)
    if (suggestions[i].nodeA == nodeA && suggestions[i].nodeB == nodeB) return int(i);
  return -1;
}

std::vector<int> CorrespondenceGraph::linksOfA(int id) const {
  std::vector<int> r;
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].nodeA == id) r.push_back(int(i));
  return r;
}

std::vector<int> CorrespondenceGraph::linksOfB(int id) const {
  std::vector<int> r;
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].nodeB == id) r.push_back(int(i));
  return r;
}

FloatTrack defaultSCurve() { return hermiteRampTrack(0.0f, 0.0f); }

Status checkSCurve(const FloatTrack& s, const std::string& where) {
  const auto& keys = s.keys();
  if (s.driven()) return Error{where + ": an s curve must be key-framed, not driven"};
  if (keys.size() < 2) return Error{where + ": an s curve needs at least two keys, (0, 0) and (1, 1)"};
  for (const auto& k : keys) {
    if (!std::isfinite(k.timeSec) || !std::isfinite(k.value) || !std::isfinite(k.d1) || !std::isfinite(k.d2))
      return Error{where + ": a key holds a non-finite number"};
    if (k.timeSec < 0.0 || k.timeSec > 1.0)
      return Error{where + ": key at u = " + std::to_string(k.timeSec) + " lies outside [0, 1]"};
  }
  if (keys.front().timeSec != 0.0 || keys.front().value != 0.0f)
    return Error{where + ": the first key must be s(0) = 0"};
  if (keys.back().timeSec != 1.0 || keys.back().value != 1.0f)
    return Error{where + ": the last key must be s(1) = 1"};
  return Status::success();
}

float evaluateS(const FloatTrack& s, double u) {
  if (u <= 0.0) return 0.0f;
  if (u >= 1.0) return 1.0f;
  return std::clamp(s.evaluate(u), 0.0f, 1.0f);
}

}  // namespace animorph
