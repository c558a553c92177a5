#include "core/paint/weight_brush.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace animorph {

const char* brushFalloffName(BrushFalloff f) {
  switch (f) {
    case BrushFalloff::Smooth: return "smooth";
    case BrushFalloff::Linear: return "linear";
    case BrushFalloff::Constant: return "constant";
  }
  return "?";
}

const char* brushModeName(BrushMode m) {
  switch (m) {
    case BrushMode::Add: return "add";
    case BrushMode::Subtract: return "subtract";
    case BrushMode::Smooth: return "smooth";
    case BrushMode::Fill: return "fill";
  }
  return "?";
}

float brushFalloff(BrushFalloff f, float t) {
  if (!(t >= 0.0f) || t > 1.0f) return 0.0f;
  switch (f) {
    case BrushFalloff::Smooth: return 1.0f - t * t * (3.0f - 2.0f * t);
    case BrushFalloff::Linear: return 1.0f - t;
    case BrushFalloff::Constant: return 1.0f;
  }
  return 0.0f;
}

namespace {

// A vertex farther than this fraction of its own depth behind the nearest
// surface at its pixel is hidden: covers the interpolation error of the
// rasterised depth on slanted triangles, far less than any body part's thickness.
constexpr float kDepthTolerance = 0.01f;

// Depth buffer (distance along the view direction) of the mesh over a square
// of pixels, with perspective-correct interpolation (1/depth is linear on screen).
struct BrushDepth {
  int x0 = 0, y0 = 0, w = 0, h = 0;
  std::vector<float> depth;

  float at(glm::vec2 px) const {
    int x = static_cast<int>(std::floor(px.x)) - x0, y = static_cast<int>(std::floor(px.y)) - y0;
    if (x < 0 || y < 0 || x >= w || y >= h) return std::numeric_limits<float>::infinity();
    return depth[static_cast<size_t>(y) * w + x];
  }

  void rasterise(const glm::vec2 p[3], const float d[3]) {
    float area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    if (std::abs(area) < 1e-12f) return;
    int bx0 = std::max(x0, static_cast<int>(std::floor(std::min({p[0].x, p[1].x, p[2].x}))));
    int by0 = std::max(y0, static_cast<int>(std::floor(std::min({p[0].y, p[1].y, p[2].y}))));
    int bx1 = std::min(x0 + w - 1, static_cast<int>(std::ceil(std::max({p[0].x, p[1].x, p[2].x}))));
    int by1 = std::min(y0 + h - 1, static_cast<int>(std::ceil(std::max({p[0].y, p[1].y, p[2].y}))));
    const float inv[3] = {1.0f / d[0], 1.0f / d[1], 1.0f / d[2]};
    for (int y = by0; y <= by1; ++y)
      for (int x = bx0; x <= bx1; ++x) {
        glm::vec2 c(x + 0.5f, y + 0.5f);
        float b0 = ((p[1].x - c.x) * (p[2].y - c.y) - (p[2].x - c.x) * (p[1].y - c.y)) / area;
        float b1 = ((p[2].x - c.x) * (p[0].y - c.y) - (p[0].x - c.x) * (p[2].y - c.y)) / area;
        float b2 = 1.0f - b0 - b1;
        if (b0 < 0.0f || b1 < 0.0f || b2 < 0.0f) continue;
        float z = 1.0f / (b0 * inv[0] + b1 * inv[1] + b2 * inv[2]);
        float& slot = depth[static_cast<size_t>(y - y0) * w + (x - x0)];
        slot = std::min(slot, z);
      }
  }
};

}  // namespace

std::vector<BrushHit> verticesUnderBrush(const PaintMesh& mesh, const BrushView& view, glm::vec2 cursorPx,
                                         float radiusPx, BrushFalloff falloff) {
  std::vector<BrushHit> hits;
  const size_t n = mesh.vertexCount();
  if (n == 0 || !(radiusPx > 0.0f)) return hits;
  const glm::vec3 eye = view.camera.eye(), fwd = view.camera.forward();
  const float nearM = view.camera.nearM();
  std::vector<glm::vec2> px(n);
  std::vector<float> depth(n);
  for (size_t i = 0; i < n; ++i) {
    depth[i] = glm::dot(mesh.positions[i] - eye, fwd);
    px[i] = glm::vec2(view.camera.worldToPixel(mesh.positions[i], view.viewportPx));
  }

  BrushDepth zb;
  zb.x0 = static_cast<int>(std::floor(cursorPx.x - radiusPx)) - 1;
  zb.y0 = static_cast<int>(std::floor(cursorPx.y - radiusPx)) - 1;
  zb.w = zb.h = static_cast<int>(std::ceil(2.0f * radiusPx)) + 3;
  zb.depth.assign(static_cast<size_t>(zb.w) * zb.h, std::numeric_limits<float>::infinity());
  const glm::vec2 lo(static_cast<float>(zb.x0), static_cast<float>(zb.y0));
  const glm::vec2 hi = lo + glm::vec2(static_cast<float>(zb.w));
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a >= n || b >= n || c >= n) continue;
    if (depth[a] <= nearM || depth[b] <= nearM || depth[c] <= nearM) continue;
    // Back faces are culled as the renderer culls them (on a closed mesh they lie behind front faces).
    const glm::vec3& pa = mesh.positions[a];
    if (glm::dot(glm::cross(mesh.positions[b] - pa, mesh.positions[c] - pa), eye - pa) <= 0.0f) continue;
    const glm::vec2 p[3] = {px[a], px[b], px[c]};
    if (std::max({p[0].x, p[1].x, p[2].x}) < lo.x || std::min({p[0].x, p[1].x, p[2].x}) > hi.x ||
        std::max({p[0].y, p[1].y, p[2].y}) < lo.y || std::min({p[0].y, p[1].y, p[2].y}) > hi.y)
      continue;
    const float d[3] = {depth[a], depth[b], depth[c]};
    zb.rasterise(p, d);
  }

  for (size_t i = 0; i < n; ++i) {
    if (depth[i] <= nearM) continue;
    float dist = glm::length(px[i] - cursorPx);
    if (dist > radiusPx) continue;
    const glm::vec3& nrm = mesh.normals[i];
    if (glm::dot(nrm, eye - mesh.positions[i]) < 0.0f) continue;  // faces away
    if (depth[i] > zb.at(px[i]) * (1.0f + kDepthTolerance)) continue;  // behind another part
    float f = brushFalloff(falloff, dist / radiusPx);
    if (f > 0.0f) hits.push_back({static_cast<uint32_t>(i), f});
  }
  return hits;
}

void applyDab(std::vector<float>& weights, const std::vector<BrushHit>& hits, const BrushSettings& s,
              const std::vector<std::vector<uint32_t>>& neighbours, const std::vector<int32_t>& mirror) {
  const float strength = std::clamp(s.strength, 0.0f, 1.0f);
  if (s.mode == BrushMode::Fill) {
    std::fill(weights.begin(), weights.end(), strength);
    return;
  }
  // Influence per vertex, the mirrored side included (the larger one where both sides hit).
  std::vector<BrushHit> all = hits;
  if (s.mirrorX && !mirror.empty()) {
    for (const BrushHit& h : hits)
      if (h.vertex < mirror.size() && mirror[h.vertex] >= 0)
        all.push_back({static_cast<uint32_t>(mirror[h.vertex]), h.influence});
    std::sort(all.begin(), all.end(), [](const BrushHit& a, const BrushHit& b) {
      return a.vertex != b.vertex ? a.vertex < b.vertex : a.influence > b.influence;
    });
    all.erase(std::unique(all.begin(), all.end(), [](const BrushHit& a, const BrushHit& b) { return a.vertex == b.vertex; }),
              all.end());
  }
  const std::vector<float> before = s.mode == BrushMode::Smooth ? weights : std::vector<float>();
  for (const BrushHit& h : all) {
    if (h.vertex >= weights.size()) continue;
    float& w = weights[h.vertex];
    const float amount = strength * h.influence;
    switch (s.mode) {
      case BrushMode::Add: w += amount; break;
      case BrushMode::Subtract: w -= amount; break;
      case BrushMode::Smooth: {
        if (h.vertex >= neighbours.size() || neighbours[h.vertex].empty()) break;
        float sum = 0.0f;
        for (uint32_t k : neighbours[h.vertex]) sum += before[k];
        w += amount * (sum / static_cast<float>(neighbours[h.vertex].size()) - w);
        break;
      }
      case BrushMode::Fill: break;
    }
    w = std::clamp(w, 0.0f, 1.0f);
  }
}

WeightStroke::WeightStroke(PaintMesh mesh, std::vector<float> startWeights, BrushSettings settings, BrushView view)
    : mesh_(std::move(mesh)), start_(std::move(startWeights)), settings_(settings), view_(view) {
  if (start_.size() != mesh_.vertexCount()) start_.assign(mesh_.vertexCount(), 0.0f);
  weights_ = start_;
  if (settings_.mode == BrushMode::Smooth) neighbours_ = vertexNeighbours(mesh_.vertexCount(), mesh_.indices);
  if (settings_.mirrorX && !mesh_.restLocal.empty()) {
    Bounds b;
    for (const auto& p : mesh_.restLocal) b.add(p);
    mirror_ = mirrorVertexMap(mesh_.restLocal, std::max(1e-5f, 0.01f * b.diagonal()));
  }
}

void WeightStroke::dab(glm::vec2 p) {
  ++dabs_;
  if (settings_.mode == BrushMode::Fill) {
    applyDab(weights_, {}, settings_, neighbours_, mirror_);
    return;
  }
  applyDab(weights_, verticesUnderBrush(mesh_, view_, p, settings_.radiusPx, settings_.falloff), settings_,
           neighbours_, mirror_);
}

int WeightStroke::moveTo(glm::vec2 cursorPx) {
  if (!started_) {
    started_ = true;
    last_ = cursorPx;
    dab(cursorPx);
    return 1;
  }
  if (settings_.mode == BrushMode::Fill) return 0;  // one fill per stroke
  const float step = std::max(1.0f, settings_.spacing * settings_.radiusPx);
  int made = 0;
  glm::vec2 d = cursorPx - last_;
  float len = glm::length(d);
  while (len >= step) {
    last_ += d / len * step;
    dab(last_);
    ++made;
    d = cursorPx - last_;
    len = glm::length(d);
  }
  return made;
}

size_t WeightStroke::verticesTouched() const {
  size_t k = 0;
  for (size_t i = 0; i < weights_.size(); ++i) k += weights_[i] != start_[i];
  return k;
}

}  // namespace animorph
