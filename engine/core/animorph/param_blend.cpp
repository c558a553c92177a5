#include "animorph/param_blend.h"

#include <algorithm>

namespace animorph {

float bridgeQ(const BlobNode& n, double timeSec) {
  if (n.type == NodeType::HyperBlend) return std::max(1.0f, n.floatParam("q").evaluate(timeSec));
  return n.type == NodeType::Union ? kUnionQ : 1.0f;
}

float bridgeQSlope(const BlobNode& n, double timeSec) {
  return n.type == NodeType::HyperBlend ? n.floatParam("q").derivative(timeSec) : 0.0f;
}

std::vector<ResampleWeight> resampleWeights(size_t from, size_t to) {
  std::vector<ResampleWeight> w(to);
  for (size_t k = 0; k < to; ++k) {
    if (from <= 1 || to <= 1 || from == to) {
      w[k] = {std::min(k, from - 1), std::min(k, from - 1), 0.0f};
      continue;
    }
    double x = double(k) * double(from - 1) / double(to - 1);
    size_t i0 = std::min(size_t(x), from - 2);
    w[k] = {i0, i0 + 1, float(x - double(i0))};
  }
  return w;
}

namespace {

std::vector<glm::vec3> pointsAt(const ControlPoints& pts, double t, size_t count) {
  std::vector<glm::vec3> r;
  r.reserve(count);
  for (const ResampleWeight& w : resampleWeights(pts.size(), count))
    r.push_back(pts[w.i0].evaluate(t) * (1.0f - w.w) + pts[w.i1].evaluate(t) * w.w);
  return r;
}

}  // namespace

ParamValue constantParam(const ParamValue& p, double t) {
  if (auto* f = std::get_if<FloatTrack>(&p)) return FloatTrack(f->evaluate(t));
  if (auto* v = std::get_if<Vec3Track>(&p)) return Vec3Track(v->evaluate(t));
  if (auto* q = std::get_if<QuatTrack>(&p)) return QuatTrack(q->evaluate(t));
  ControlPoints out;
  for (const auto& pt : std::get<ControlPoints>(p)) out.push_back(Vec3Track(pt.evaluate(t)));
  return out;
}

ParamValue blendParam(const ParamValue& a, const ParamValue& b, double tA, double tB, float s) {
  if (auto* f = std::get_if<FloatTrack>(&a))
    return FloatTrack((1.0f - s) * f->evaluate(tA) + s * std::get<FloatTrack>(b).evaluate(tB));
  if (auto* v = std::get_if<Vec3Track>(&a))
    return Vec3Track((1.0f - s) * v->evaluate(tA) + s * std::get<Vec3Track>(b).evaluate(tB));
  if (auto* q = std::get_if<QuatTrack>(&a))
    return QuatTrack(glm::normalize(glm::slerp(q->evaluate(tA), std::get<QuatTrack>(b).evaluate(tB), s)));
  const auto& pa = std::get<ControlPoints>(a);
  const auto& pb = std::get<ControlPoints>(b);
  size_t n = std::max(pa.size(), pb.size());
  std::vector<glm::vec3> va = pointsAt(pa, tA, n), vb = pointsAt(pb, tB, n);
  ControlPoints out;
  for (size_t k = 0; k < n; ++k) out.push_back(Vec3Track((1.0f - s) * va[k] + s * vb[k]));
  return out;
}

}  // namespace animorph
