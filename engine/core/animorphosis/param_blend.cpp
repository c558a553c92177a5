#include "core/animorphosis/param_blend.h"

#include <algorithm>

namespace animorph {

float bridgeQ(const BlobNode& n, double timeSec) {
  if (n.type == NodeType::HyperBlend) return std::max(1.0f, n.floatParam("q").evaluate(timeSec));
  return n.type == NodeType::Union ? kUnionQ : 1.0f;
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

// The list at t resampled to `count` points, written into `out`: each control point's track is
// evaluated once (a resampled point reads two of them, an unresampled one the same one twice),
// then lerp(p[i0], p[i1], w) as resampleWeights gives it.
void pointsAt(const ControlPoints& pts, double t, size_t count, std::vector<glm::vec3>& at,
              std::vector<glm::vec3>& out) {
  at.resize(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) at[i] = pts[i].evaluate(t);
  out.resize(count);
  if (count == pts.size()) {  // weights (k, k, 0): the points themselves (v * 1 + v * 0 == v, v finite)
    std::copy(at.begin(), at.end(), out.begin());
    return;
  }
  const std::vector<ResampleWeight> weights = resampleWeights(pts.size(), count);
  for (size_t k = 0; k < count; ++k) out[k] = at[weights[k].i0] * (1.0f - weights[k].w) + at[weights[k].i1] * weights[k].w;
}

// Per-thread scratch lists for the control points of one parameter (scrubbing allocates nothing).
struct PointScratch {
  std::vector<glm::vec3> at, a, b;
};
PointScratch& pointScratch() {
  thread_local PointScratch s;
  return s;
}

}  // namespace

namespace {

template <class T>
void setOne(ParamValue& slot, const T& v) {
  if (auto* tr = std::get_if<Track<T>>(&slot); tr && tr->keys().size() == 1 && !tr->driven()) {
    TrackKey<T>& k = tr->keys()[0];
    k.timeSec = 0.0;
    k.value = v;
    return;
  }
  slot = Track<T>(v);
}

void setPoints(ParamValue& slot, const std::vector<glm::vec3>& pts) {
  auto* list = std::get_if<ControlPoints>(&slot);
  if (!list) {
    slot = ControlPoints{};
    list = std::get_if<ControlPoints>(&slot);
  }
  list->resize(pts.size());
  for (size_t k = 0; k < pts.size(); ++k) {
    auto& tr = (*list)[k];
    if (tr.keys().size() == 1 && !tr.driven()) tr.keys()[0] = TrackKey<glm::vec3>{0.0, pts[k]};
    else tr = Vec3Track(pts[k]);
  }
}

}  // namespace

float blendFloat(const FloatTrack& a, const FloatTrack& b, double tA, double tB, float s) {
  return (1.0f - s) * a.evaluate(tA) + s * b.evaluate(tB);
}

glm::vec3 blendVec3(const Vec3Track& a, const Vec3Track& b, double tA, double tB, float s) {
  return (1.0f - s) * a.evaluate(tA) + s * b.evaluate(tB);
}

glm::quat blendQuat(const QuatTrack& a, const QuatTrack& b, double tA, double tB, float s) {
  return glm::normalize(glm::slerp(a.evaluate(tA), b.evaluate(tB), s));
}

void constantPoints(const ControlPoints& p, double t, std::vector<glm::vec3>& out) {
  pointsAt(p, t, p.size(), pointScratch().at, out);
}

void blendPoints(const ControlPoints& pa, const ControlPoints& pb, double tA, double tB, float s,
                 std::vector<glm::vec3>& out) {
  size_t n = std::max(pa.size(), pb.size());
  PointScratch& sc = pointScratch();
  pointsAt(pa, tA, n, sc.at, out);
  pointsAt(pb, tB, n, sc.at, sc.b);
  for (size_t k = 0; k < n; ++k) out[k] = (1.0f - s) * out[k] + s * sc.b[k];
}

void writeConstantFloat(ParamValue& slot, float v) { setOne(slot, v); }

void writeConstantParam(ParamValue& slot, const ParamValue& p, double t) {
  if (auto* f = std::get_if<FloatTrack>(&p)) return setOne(slot, f->evaluate(t));
  if (auto* v = std::get_if<Vec3Track>(&p)) return setOne(slot, v->evaluate(t));
  if (auto* q = std::get_if<QuatTrack>(&p)) return setOne(slot, q->evaluate(t));
  PointScratch& s = pointScratch();
  constantPoints(std::get<ControlPoints>(p), t, s.a);
  setPoints(slot, s.a);
}

void writeBlendedParam(ParamValue& slot, const ParamValue& a, const ParamValue& b, double tA, double tB, float s) {
  if (auto* f = std::get_if<FloatTrack>(&a)) return setOne(slot, blendFloat(*f, std::get<FloatTrack>(b), tA, tB, s));
  if (auto* v = std::get_if<Vec3Track>(&a)) return setOne(slot, blendVec3(*v, std::get<Vec3Track>(b), tA, tB, s));
  if (auto* q = std::get_if<QuatTrack>(&a)) return setOne(slot, blendQuat(*q, std::get<QuatTrack>(b), tA, tB, s));
  PointScratch& sc = pointScratch();
  blendPoints(std::get<ControlPoints>(a), std::get<ControlPoints>(b), tA, tB, s, sc.a);
  setPoints(slot, sc.a);
}

}  // namespace animorph
