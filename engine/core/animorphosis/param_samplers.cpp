#include "core/animorphosis/param_samplers.h"

#include <algorithm>

namespace animorph {

namespace {

glm::vec4 quatSlot(const glm::quat& q) { return {q.x, q.y, q.z, q.w}; }
glm::quat slotQuat(const glm::vec4& x) { return glm::quat(x.w, x.x, x.y, x.z); }

// Per-thread scratch for the points of one list (scrubbing allocates nothing once warm).
struct PointScratch {
  std::vector<glm::vec3> at, b;
};
PointScratch& scratch() {
  thread_local PointScratch s;
  return s;
}

}  // namespace

uint32_t ParamSamplers::add(const BlobNode& n, const std::vector<size_t>* blendCounts) {
  const uint32_t first = uint32_t(slots_.size());
  for (size_t k = 0; k < n.params.size(); ++k) {
    const ParamValue& v = n.params[k];
    Slot s;
    if (auto* f = std::get_if<FloatTrack>(&v)) {
      s.kind = ParamKind::Float;
      s.animated = !f->isConstant();
      s.index = uint32_t(s.animated ? floats_.size() : constants_.size());
      if (s.animated) floats_.emplace_back(*f);
      else constants_.push_back(glm::vec4(f->evaluate(0.0), 0.0f, 0.0f, 0.0f));
    } else if (auto* x = std::get_if<Vec3Track>(&v)) {
      s.kind = ParamKind::Vec3;
      s.animated = !x->isConstant();
      s.index = uint32_t(s.animated ? vec3s_.size() : constants_.size());
      if (s.animated) vec3s_.emplace_back(*x);
      else constants_.push_back(glm::vec4(x->evaluate(0.0), 0.0f));
    } else if (auto* q = std::get_if<QuatTrack>(&v)) {
      s.kind = ParamKind::Quat;
      s.animated = !q->isConstant();
      s.index = uint32_t(s.animated ? quats_.size() : constants_.size());
      if (s.animated) quats_.emplace_back(*q);
      else constants_.push_back(quatSlot(q->evaluate(0.0)));
    } else {
      const ControlPoints& pts = std::get<ControlPoints>(v);
      s.kind = ParamKind::Vec3List;
      s.index = uint32_t(lists_.size());
      PointList list;
      list.first = uint32_t(points_.size());
      list.count = uint32_t(pts.size());
      for (const Vec3Track& p : pts) points_.emplace_back(p);
      const size_t to = blendCounts && k < blendCounts->size() ? (*blendCounts)[k] : pts.size();
      if (to != pts.size()) list.toBlend = resampleWeights(pts.size(), to);
      if (list.count > 0 && std::all_of(points_.begin() + list.first, points_.end(),
                                        [](const TrackSampler<glm::vec3>& p) { return p.constant(); })) {
        list.fixedAt = int32_t(fixedValues_.size());
        for (uint32_t i = 0; i < list.count; ++i) fixedValues_.push_back(points_[list.first + i].sample(0.0));
        if (!list.toBlend.empty()) {
          std::vector<glm::vec3>& r = scratch().b;
          resampled(list, fixedValues_.data() + list.fixedAt, r);
          list.fixedResampledAt = int32_t(fixedValues_.size());
          fixedValues_.insert(fixedValues_.end(), r.begin(), r.end());
        }
      }
      lists_.push_back(std::move(list));
    }
    slots_.push_back(s);
  }
  return first;
}

uint32_t ParamSamplers::addBridgeQ(const BlobNode& n) {
  Slot s;
  s.kind = ParamKind::Float;
  if (n.type == NodeType::HyperBlend && !n.floatParam("q").isConstant()) {
    s.animated = true;
    s.index = uint32_t(floats_.size());
    floats_.emplace_back(n.floatParam("q"));
  } else {
    s.index = uint32_t(constants_.size());
    // bridgeQ's value; max(1, v) leaves it unchanged (a hyper-blend's q is clamped the same way).
    constants_.push_back(glm::vec4(animorph::bridgeQ(n, 0.0), 0.0f, 0.0f, 0.0f));
  }
  slots_.push_back(s);
  return uint32_t(slots_.size() - 1);
}

bool ParamSamplers::animated(uint32_t first, uint32_t count) const {
  for (uint32_t k = first; k < first + count && k < slots_.size(); ++k) {
    const Slot& s = slots_[k];
    if (s.kind != ParamKind::Vec3List ? s.animated : lists_[s.index].count > 0 && lists_[s.index].fixedAt < 0)
      return true;
  }
  return false;
}

float ParamSamplers::floatAt(uint32_t slot, double t) const {
  const Slot& s = slots_[slot];
  return s.animated ? floats_[s.index].sample(t) : constants_[s.index].x;
}

glm::vec3 ParamSamplers::vec3At(const Slot& s, double t) const {
  return s.animated ? vec3s_[s.index].sample(t) : glm::vec3(constants_[s.index]);
}

glm::quat ParamSamplers::quatAt(const Slot& s, double t) const {
  return s.animated ? quats_[s.index].sample(t) : slotQuat(constants_[s.index]);
}

// As param_blend.cpp's pointsAt: each point evaluated once, then lerp(p[i0], p[i1], w) when resampled.
const glm::vec3* ParamSamplers::pointsAt(const PointList& p, double t, bool resample, std::vector<glm::vec3>& out,
                                         size_t& n) const {
  const bool resampling = resample && !p.toBlend.empty();
  n = resampling ? p.toBlend.size() : p.count;
  // The same values, sampled and resampled once (a constant track's sample ignores t).
  if (p.fixedAt >= 0) return fixedValues_.data() + (resampling ? p.fixedResampledAt : p.fixedAt);
  std::vector<glm::vec3>& at = resampling ? scratch().at : out;
  at.resize(p.count);
  for (uint32_t i = 0; i < p.count; ++i) at[i] = points_[p.first + i].sample(t);
  if (resampling) resampled(p, at.data(), out);
  return out.data();
}

void ParamSamplers::resampled(const PointList& p, const glm::vec3* at, std::vector<glm::vec3>& out) {
  out.resize(p.toBlend.size());
  for (size_t k = 0; k < p.toBlend.size(); ++k) {
    const ResampleWeight& w = p.toBlend[k];
    out[k] = at[w.i0] * (1.0f - w.w) + at[w.i1] * w.w;
  }
}

void ParamSamplers::constant(uint32_t slot, double t, glm::vec4& out, std::vector<glm::vec3>& list) const {
  const Slot& s = slots_[slot];
  switch (s.kind) {
    case ParamKind::Float: out.x = floatAt(slot, t); break;
    case ParamKind::Vec3: out = glm::vec4(vec3At(s, t), 0.0f); break;
    case ParamKind::Quat: out = quatSlot(quatAt(s, t)); break;
    case ParamKind::Vec3List: {
      size_t n;
      const glm::vec3* points = pointsAt(lists_[s.index], t, false, list, n);
      if (points != list.data()) list.assign(points, points + n);
      break;
    }
  }
}

// blendFloat, blendVec3, blendQuat and blendPoints of param_blend.cpp.
void ParamSamplers::blend(uint32_t a, uint32_t b, double tA, double tB, float s, glm::vec4& out,
                          std::vector<glm::vec3>& list) const {
  const Slot& sa = slots_[a];
  const Slot& sb = slots_[b];
  switch (sa.kind) {
    case ParamKind::Float: out.x = blendFloatAt(a, b, tA, tB, s); break;
    case ParamKind::Vec3: out = glm::vec4((1.0f - s) * vec3At(sa, tA) + s * vec3At(sb, tB), 0.0f); break;
    case ParamKind::Quat: out = quatSlot(glm::normalize(glm::slerp(quatAt(sa, tA), quatAt(sb, tB), s))); break;
    case ParamKind::Vec3List: {
      size_t na, nb;
      const glm::vec3* pa = pointsAt(lists_[sa.index], tA, true, list, na);
      const glm::vec3* pb = pointsAt(lists_[sb.index], tB, true, scratch().b, nb);
      list.resize(na);  // (pa may be list's own data: same size, not moved)
      for (size_t k = 0; k < na; ++k) list[k] = (1.0f - s) * pa[k] + s * pb[k];
      break;
    }
  }
}

}  // namespace animorph
