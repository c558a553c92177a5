#include "core/standin/standin_edit.h"

#include <limits>
#include <string>

namespace animorph {

namespace {

glm::mat4 nodeMatrix(const std::vector<glm::mat4>& globals, int node) {
  return node >= 0 && node < int(globals.size()) ? globals[size_t(node)] : glm::mat4(1.0f);
}

}  // namespace

StandinSegment rebindSegment(const StandinSegment& seg, int newNode, const std::vector<glm::mat4>& globals) {
  const glm::mat4 from = nodeMatrix(globals, seg.node), to = nodeMatrix(globals, newNode);
  const glm::mat4 carry = glm::inverse(to) * from;
  StandinSegment out = seg;
  out.node = newNode;
  out.a = glm::vec3(carry * glm::vec4(seg.a, 1.0f));
  out.b = glm::vec3(carry * glm::vec4(seg.b, 1.0f));
  const float sTo = radiusScale(to);
  out.radius = sTo > 0.0f ? seg.radius * radiusScale(from) / sTo : seg.radius;
  return out;
}

Result<StandinSegment> refitSegment(const Character& c, const StandinSegment& seg, const FitSettings& settings) {
  FitSettings fs = settings;
  fs.measure = false;
  auto fit = fitStandin(c, fs);
  if (!fit) return Error{fit.error()};
  const StandinSegment* best = nullptr;
  float bestD = std::numeric_limits<float>::max();
  for (const StandinSegment& f : fit->standin.segments) {
    if (f.node != seg.node) continue;
    float d = glm::length(f.a - seg.a) + glm::length(f.b - seg.b);
    if (d < bestD) {
      bestD = d;
      best = &f;
    }
  }
  if (!best) {
    std::string name = seg.node >= 0 && seg.node < int(c.nodes.size()) ? c.nodes[size_t(seg.node)].name : "";
    return Error{"node " + std::to_string(seg.node) + (name.empty() ? "" : " (" + name + ")") +
                 ": the fit puts no segment there (it dominates no vertex)"};
  }
  return *best;
}

}  // namespace animorph
