#include "blobtree/meta_primitives.h"

#include <algorithm>
#include <cmath>

#include <glm/gtx/quaternion.hpp>

#include "field/spline_curve.h"

namespace animorph {

std::vector<glm::vec3> evaluatePoints(const ControlPoints& pts, double t) {
  std::vector<glm::vec3> out;
  out.reserve(pts.size());
  for (const auto& p : pts) out.push_back(p.evaluate(t));
  return out;
}

std::vector<SpaceMap> splineOfNodesFrames(const BlobNode& node, double t) {
  std::vector<glm::vec3> pts = evaluatePoints(node.pointsParam("points"), t);
  int count = std::clamp(int(std::lround(node.floatParam("count").evaluate(t))), 1, 1000);
  float s0 = std::max(1e-4f, node.floatParam("scaleStart").evaluate(t));
  float s1 = std::max(1e-4f, node.floatParam("scaleEnd").evaluate(t));
  std::vector<SpaceMap> frames;
  frames.reserve(size_t(count));
  for (int i = 0; i < count; ++i) {
    float s = count == 1 ? 0.0f : float(i) / float(count - 1);
    CurvePoint c = evaluateCurve(pts, s);
    glm::vec3 dir = glm::length(c.tangent) > 1e-9f ? glm::normalize(c.tangent) : glm::vec3(0, 0, 1);
    glm::quat rot = glm::rotation(glm::vec3(0, 0, 1), dir);
    float scale = s0 + (s1 - s0) * s;
    frames.push_back(makeAffineMap(c.position, rot, glm::vec3(scale)));
  }
  return frames;
}

std::vector<std::array<glm::vec3, 3>> coonsPatchTriangles(const BlobNode& node, double t) {
  std::vector<glm::vec3> bottom = evaluatePoints(node.pointsParam("bottom"), t);
  std::vector<glm::vec3> top = evaluatePoints(node.pointsParam("top"), t);
  std::vector<glm::vec3> left = evaluatePoints(node.pointsParam("left"), t);
  std::vector<glm::vec3> right = evaluatePoints(node.pointsParam("right"), t);
  int res = std::clamp(int(std::lround(node.floatParam("resolution").evaluate(t))), 1, 64);
  glm::vec3 p00 = evaluateCurve(bottom, 0.0f).position, p10 = evaluateCurve(bottom, 1.0f).position;
  glm::vec3 p01 = evaluateCurve(top, 0.0f).position, p11 = evaluateCurve(top, 1.0f).position;
  // The four boundary curves sampled once at the grid's parameters (not once per grid point).
  std::vector<glm::vec3> atBottom(size_t(res + 1)), atTop(size_t(res + 1)), atLeft(size_t(res + 1)),
      atRight(size_t(res + 1));
  for (int i = 0; i <= res; ++i) {
    float w = float(i) / res;
    atBottom[size_t(i)] = evaluateCurve(bottom, w).position;
    atTop[size_t(i)] = evaluateCurve(top, w).position;
    atLeft[size_t(i)] = evaluateCurve(left, w).position;
    atRight[size_t(i)] = evaluateCurve(right, w).position;
  }
  auto surface = [&](int i, int j) {
    float u = float(i) / res, v = float(j) / res;
    glm::vec3 ruled = (1.0f - v) * atBottom[size_t(i)] + v * atTop[size_t(i)] + (1.0f - u) * atLeft[size_t(j)] +
                      u * atRight[size_t(j)];
    glm::vec3 bilinear = (1.0f - u) * (1.0f - v) * p00 + u * (1.0f - v) * p10 + (1.0f - u) * v * p01 + u * v * p11;
    return ruled - bilinear;
  };
  std::vector<glm::vec3> grid(size_t((res + 1) * (res + 1)));
  for (int j = 0; j <= res; ++j)
    for (int i = 0; i <= res; ++i) grid[size_t(j * (res + 1) + i)] = surface(i, j);
  std::vector<std::array<glm::vec3, 3>> tris;
  tris.reserve(size_t(2 * res * res));
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      glm::vec3 a = grid[size_t(j * (res + 1) + i)], b = grid[size_t(j * (res + 1) + i + 1)];
      glm::vec3 c = grid[size_t((j + 1) * (res + 1) + i)], d = grid[size_t((j + 1) * (res + 1) + i + 1)];
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
  return tris;
}

}  // namespace animorph
