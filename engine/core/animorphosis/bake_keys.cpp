#include "core/animorphosis/bake_keys.h"

#include <algorithm>
#include <cmath>

#include "core/animorphosis/param_blend.h"

namespace animorph {

namespace {

// One side of a channel: sum of weight * track (a track, or a resampled control point).
template <class T>
struct Mix {
  std::vector<std::pair<const Track<T>*, float>> terms;
  T value(double t) const {
    T v(0.0f);
    for (const auto& [tr, w] : terms) v += tr->evaluate(t) * w;
    return v;
  }
  // dT/dt: the derivative of the segment after t, or with `left` of the one before it (where a track
  // starts holding after its last key, the two differ).
  T slope(double t, bool left) const {
    T v(0.0f);
    for (const auto& [tr, w] : terms) v += tr->derivative(left ? t - 1e-6 : t) * w;
    return v;
  }
  std::vector<double> keyTimes() const {
    std::vector<double> r;
    for (const auto& [tr, w] : terms)
      if (!tr->driven())
        for (const auto& k : tr->keys()) r.push_back(k.timeSec);
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    return r;
  }
};

float distance(float a, float b) { return std::abs(a - b); }
float distance(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b); }

float sSlope(const FloatTrack& s, double u) {
  if (u < 0.0 || u > 1.0) return 0.0f;
  return s.derivative(std::min(u, 1.0 - 1e-9));
}

struct Baker {
  const GenericTree& c;
  const AnimorphosisTiming& timing;
  BakeKeysSettings settings;
  BakeKeysReport report;
  double span;
  size_t nodesDone = 0, nodesTotal = 0;

  // The cancel flag is set: the caller drops everything made so far.
  bool stopped() const { return settings.cancel && settings.cancel->load(std::memory_order_relaxed); }

  // Timeline times in [t0, t1] at which a clip plays one of these clip key times.
  void mapTimes(const std::vector<double>& clipTimes, const ClipTiming& clip, std::vector<double>& out) const {
    double t0 = timing.startSec, t1 = timing.endSec;
    for (double k : clipTimes) {
      if (clip.loopSec > 0.0) {
        if (k < 0.0 || k > clip.loopSec) continue;
        double first = clip.offsetSec + k / clip.speed, period = clip.loopSec / clip.speed;
        double m0 = std::ceil((t0 - first) / period), m1 = std::floor((t1 - first) / period);
        for (double m = m0; m <= m1; m += 1.0) out.push_back(first + m * period);
      } else {
        double t = clip.offsetSec + k / clip.speed;
        if (t >= t0 && t <= t1) out.push_back(t);
      }
    }
  }

  std::vector<double> channelTimes(const std::vector<double>& a, const std::vector<double>& b, const FloatTrack& s) const {
    std::vector<double> r;
    mapTimes(a, timing.source, r);
    mapTimes(b, timing.target, r);
    for (const auto& k : s.keys()) r.push_back(timing.startSec + k.timeSec * span);
    r.push_back(timing.startSec);
    r.push_back(timing.endSec);
    std::sort(r.begin(), r.end());
    std::vector<double> u;
    for (double t : r)
      if (u.empty() || t - u.back() > 1e-9 * std::max(1.0, std::abs(t))) u.push_back(t);
    return u;
  }

  void account(int keys, int bound, double deviation, const std::string& where) {
    ++report.parameters;
    report.keys += size_t(keys);
    if (keys > report.mostKeys) {
      report.mostKeys = keys;
      report.mostKeysBound = bound;
    }
    if (keys > bound) report.withinBound = false;
    if (deviation > report.largestDeviation) {
      report.largestDeviation = deviation;
      report.largestDeviationAt = where;
    }
  }

  template <class T>
  Track<T> channel(const Mix<T>& a, const Mix<T>& b, const FloatTrack& s, const std::string& where) {
    if (stopped()) return Track<T>(T(0.0f));
    std::vector<double> ka = a.keyTimes(), kb = b.keyTimes();
    std::vector<double> times = channelTimes(ka, kb, s);
    double speedA = timing.source.speed, speedB = timing.target.speed;
    // p_C at t, and its slope: the segment after t, except at t1, the end of the bake, where the one before.
    auto live = [&](double t, T* slope) {
      double tA = timing.source.localTime(t), tB = timing.target.localTime(t), u = timing.u(t);
      float sv = evaluateS(s, u);
      T va = a.value(tA), vb = b.value(tB);
      bool left = t >= timing.endSec;
      if (slope)
        *slope = a.slope(tA, left) * ((1.0f - sv) * float(speedA)) + b.slope(tB, left) * (sv * float(speedB)) +
                 (vb - va) * float(sSlope(s, u) / span);
      return va * (1.0f - sv) + vb * sv;
    };
    Track<T> out;
    out.clearKeys();
    bool constant = true;
    for (double t : times) {
      TrackKey<T> k;
      k.timeSec = t;
      k.value = live(t, &k.d1);
      k.interp = KeyInterp::Hermite;
      k.userDerivatives = true;
      if (!out.keys().empty() && (k.value != out.keys().front().value)) constant = false;
      if (distance(k.d1, T(0.0f)) != 0.0f) constant = false;
      out.keys().push_back(k);
    }
    if (constant) out = Track<T>(out.keys().front().value);
    double dev = 0.0;
    for (size_t i = 0; i + 1 < times.size(); ++i)
      for (int j = 1; j <= settings.samplesPerInterval; ++j) {
        double t = times[i] + (times[i + 1] - times[i]) * j / (settings.samplesPerInterval + 1);
        dev = std::max(dev, double(distance(out.evaluate(t), live(t, nullptr))));
      }
    account(int(out.keys().size()), int(ka.size() + kb.size() + s.keys().size()), dev, where);
    return out;
  }

  QuatTrack quatChannel(const QuatTrack& a, const QuatTrack& b, const FloatTrack& s, const std::string& where) {
    if (stopped()) return QuatTrack();
    auto timesOf = [](const QuatTrack& q) {
      std::vector<double> r;
      if (!q.driven())
        for (const auto& k : q.keys()) r.push_back(k.timeSec);
      return r;
    };
    std::vector<double> ka = timesOf(a), kb = timesOf(b);
    std::vector<double> times = channelTimes(ka, kb, s);
    auto live = [&](double t) {
      float sv = evaluateS(s, timing.u(t));
      return glm::normalize(glm::slerp(a.evaluate(timing.source.localTime(t)), b.evaluate(timing.target.localTime(t)), sv));
    };
    QuatTrack out;
    out.clearKeys();
    for (double t : times) out.setKey(t, live(t));
    bool constant = std::all_of(out.keys().begin(), out.keys().end(),
                                [&](const auto& k) { return k.value == out.keys().front().value; });
    if (constant) out = QuatTrack(out.keys().front().value);
    double dev = 0.0;
    for (size_t i = 0; i + 1 < times.size(); ++i)
      for (int j = 1; j <= settings.samplesPerInterval; ++j) {
        double t = times[i] + (times[i + 1] - times[i]) * j / (settings.samplesPerInterval + 1);
        float d = std::min(1.0f, std::abs(glm::dot(out.evaluate(t), live(t))));
        dev = std::max(dev, 2.0 * std::acos(double(d)));
      }
    account(int(out.keys().size()), int(ka.size() + kb.size() + s.keys().size()), dev, where);
    return out;
  }

  template <class T>
  static Mix<T> single(const Track<T>& t) {
    return Mix<T>{{{&t, 1.0f}}};
  }

  BlobNode node(const GenericNode& g, int& nextId) {
    const FloatTrack& s = g.sCurve >= 0 ? c.sCurves[size_t(g.sCurve)] : timing.globalS;
    const BlobNode& named = g.a.name.empty() ? g.b : g.a;
    BlobNode n;
    n.id = nextId++;
    n.name = named.name;
    std::string where = "node " + std::to_string(n.id) + (n.name.empty() ? "" : " '" + n.name + "'");
    if (g.a.type != g.b.type) {
      n = makeBlobNode(NodeType::HyperBlend, n.id, n.name);
      FloatTrack qa = g.a.type == NodeType::HyperBlend ? g.a.floatParam("q") : FloatTrack(bridgeQ(g.a, 0.0));
      FloatTrack qb = g.b.type == NodeType::HyperBlend ? g.b.floatParam("q") : FloatTrack(bridgeQ(g.b, 0.0));
      n.floatParam("q") = channel(single(qa), single(qb), s, where + " parameter 'q'");
    } else {
      n.type = g.a.type;
      const auto& specs = nodeTypeInfo(n.type).params;
      for (size_t i = 0; i < specs.size(); ++i) {
        std::string at = where + " parameter '" + specs[i].name + "'";
        const ParamValue& pa = g.a.params[i];
        const ParamValue& pb = g.b.params[i];
        if (auto* f = std::get_if<FloatTrack>(&pa)) {
          n.params.push_back(channel(single(*f), single(std::get<FloatTrack>(pb)), s, at));
        } else if (auto* v = std::get_if<Vec3Track>(&pa)) {
          n.params.push_back(channel(single(*v), single(std::get<Vec3Track>(pb)), s, at));
        } else if (auto* q = std::get_if<QuatTrack>(&pa)) {
          n.params.push_back(quatChannel(*q, std::get<QuatTrack>(pb), s, at));
        } else {
          const auto& la = std::get<ControlPoints>(pa);
          const auto& lb = std::get<ControlPoints>(pb);
          size_t count = std::max(la.size(), lb.size());
          auto wa = resampleWeights(la.size(), count), wb = resampleWeights(lb.size(), count);
          ControlPoints out;
          for (size_t k = 0; k < count; ++k) {
            Mix<glm::vec3> ma{{{&la[wa[k].i0], 1.0f - wa[k].w}, {&la[wa[k].i1], wa[k].w}}};
            Mix<glm::vec3> mb{{{&lb[wb[k].i0], 1.0f - wb[k].w}, {&lb[wb[k].i1], wb[k].w}}};
            out.push_back(channel(ma, mb, s, at + " point " + std::to_string(k)));
          }
          n.params.push_back(std::move(out));
        }
      }
    }
    if (settings.progress && !stopped()) settings.progress(++nodesDone, nodesTotal);
    n.children.reserve(g.children.size());
    for (const GenericNode& ch : g.children) {
      if (stopped()) break;
      n.children.push_back(node(ch, nextId));
    }
    return n;
  }
};

}  // namespace

BakedAnimorphosis bakeKeyframes(const GenericTree& c, const AnimorphosisTiming& timing, const BakeKeysSettings& settings) {
  Baker baker{c, timing, settings, {}, timing.endSec - timing.startSec};
  baker.nodesTotal = c.size();
  BakedAnimorphosis out;
  out.tree.threshold = baker.channel(Baker::single(c.thresholdA), Baker::single(c.thresholdB), timing.globalS, "threshold");
  int next = 1;
  out.tree.root = baker.node(c.root, next);
  if (baker.stopped()) {
    out.cancelled = true;
    out.tree = BlobTree{};
    return out;  // the report stays empty: a part of the channels says nothing about the whole
  }
  out.report = baker.report;
  return out;
}

}  // namespace animorph
