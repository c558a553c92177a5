#include "core/blobtree/meta_primitives.h"

#include <algorithm>
#include <cmath>

#include <glm/gtx/quaternion.hpp>

#include "core/field/spline_curve.h"

namespace animorph {

std::vector<glm::vec3> evaluatePoints(const ControlPoints& pts, double t) {
  std::vector<glm::vec3> out;
  evaluatePoints(pts, t, out);
  return out;
}

void evaluatePoints(const ControlPoints& pts, double t, std::vector<glm::vec3>& out) {
  out.resize(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) out[i] = pts[i].evaluate(t);
}

std::vector<SpaceMap> splineOfNodesFrames(const BlobNode& node, double t) {
  MetaScratch scratch;
  std::vector<SpaceMap> frames;
  splineOfNodesFrames(node, t, scratch, frames);
  return frames;
}

void splineOfNodesFrames(const BlobNode& node, double t, MetaScratch& scratch, std::vector<SpaceMap>& frames) {
  std::vector<glm::vec3>& pts = scratch.points[0];
  evaluatePoints(node.pointsParam("points"), t, pts);
  splineOfNodesFrames(pts, node.floatParam("count").evaluate(t), node.floatParam("scaleStart").evaluate(t),
                      node.floatParam("scaleEnd").evaluate(t), frames);
}

void splineOfNodesFrames(const std::vector<glm::vec3>& pts, float countValue, float scaleStart, float scaleEnd,
                         std::vector<SpaceMap>& frames) {
  int count = std::clamp(int(std::lround(countValue)), 1, 1000);
  float s0 = std::max(1e-4f, scaleStart);
  float s1 = std::max(1e-4f, scaleEnd);
  frames.clear();
  frames.reserve(size_t(count));
  for (int i = 0; i < count; ++i) {
    float s = count == 1 ? 0.0f : float(i) / float(count - 1);
    CurvePoint c = evaluateCurve(pts, s);
    glm::vec3 dir = glm::length(c.tangent) > 1e-9f ? glm::normalize(c.tangent) : glm::vec3(0, 0, 1);
    glm::quat rot = glm::rotation(glm::vec3(0, 0, 1), dir);
    float scale = s0 + (s1 - s0) * s;
    frames.push_back(makeAffineMap(c.position, rot, glm::vec3(scale)));
  }
}

std::vector<std::array<glm::vec3, 3>> coonsPatchTriangles(const BlobNode& node, double t) {
  MetaScratch scratch;
  std::vector<std::array<glm::vec3, 3>> tris;
  coonsPatchTriangles(node, t, scratch, tris);
  return tris;
}

void coonsPatchTriangles(const BlobNode& node, double t, MetaScratch& scratch,
                         std::vector<std::array<glm::vec3, 3>>& tris) {
  static constexpr const char* kCurves[4] = {"bottom", "top", "left", "right"};
  for (int k = 0; k < 4; ++k) evaluatePoints(node.pointsParam(kCurves[k]), t, scratch.points[k]);
  coonsPatchTriangles(scratch.points[0], scratch.points[1], scratch.points[2], scratch.points[3],
                      node.floatParam("resolution").evaluate(t), scratch, tris);
}

void coonsPatchTriangles(const std::vector<glm::vec3>& bottom, const std::vector<glm::vec3>& top,
                         const std::vector<glm::vec3>& left, const std::vector<glm::vec3>& right, float resolution,
                         MetaScratch& scratch, std::vector<std::array<glm::vec3, 3>>& tris) {
  int res = std::clamp(int(std::lround(resolution)), 1, 64);
  // The four boundary curves sampled once at the grid's parameters (not once per grid point).
  for (auto& samples : scratch.samples) samples.resize(size_t(res + 1));
  std::vector<glm::vec3>&atBottom = scratch.samples[0], &atTop = scratch.samples[1], &atLeft = scratch.samples[2],
  &atRight = scratch.samples[3];
  for (int i = 0; i <= res; ++i) {
    float w = float(i) / res;
    atBottom[size_t(i)] = curvePosition(bottom, w);
    atTop[size_t(i)] = curvePosition(top, w);
    atLeft[size_t(i)] = curvePosition(left, w);
    atRight[size_t(i)] = curvePosition(right, w);
  }
  // The corners: the samples at 0 / res = 0 and res / res = 1 exactly.
  const glm::vec3 p00 = atBottom[0], p10 = atBottom[size_t(res)], p01 = atTop[0], p11 = atTop[size_t(res)];
  auto surface = [&](int i, int j) {
    float u = float(i) / res, v = float(j) / res;
    glm::vec3 ruled = (1.0f - v) * atBottom[size_t(i)] + v * atTop[size_t(i)] + (1.0f - u) * atLeft[size_t(j)] +
                      u * atRight[size_t(j)];
    glm::vec3 bilinear = (1.0f - u) * (1.0f - v) * p00 + u * (1.0f - v) * p10 + (1.0f - u) * v * p01 + u * v * p11;
    return ruled - bilinear;
  };
  std::vector<glm::vec3>& grid = scratch.grid;
  grid.resize(size_t((res + 1) * (res + 1)));
  for (int j = 0; j <= res; ++j)
    for (int i = 0; i <= res; ++i) grid[size_t(j * (res + 1) + i)] = surface(i, j);
  tris.clear();
  tris.reserve(size_t(2 * res * res));
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      glm::vec3 a = grid[size_t(j * (res + 1) + i)], b = grid[size_t(j * (res + 1) + i + 1)];
      glm::vec3 c = grid[size_t((j + 1) * (res + 1) + i)], d = grid[size_t((j + 1) * (res + 1) + i + 1)];
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
}

}  // namespace animorph
