#include "core/io/collada_morph_weights.h"

#include <algorithm>
#include <deque>
#include <map>
#include <optional>

#include "core/io/collada_text.h"

namespace animorph {
namespace {

using namespace collada;

// What a channel's target addresses: morph `morph`'s target `target` (whole: every target).
struct Address {
  size_t morph = 0;
  size_t target = 0;
  bool whole = false;
  std::string problem;  // not empty: the channel addresses the morph but cannot be read
};

// The selection after the id or SID: "" (the whole array), "(k)", or a problem.
void readSelection(std::string_view sel, Address& a) {
  if (sel.empty()) {
    a.whole = true;
    return;
  }
  if (sel[0] == '.') {
    a.problem = "the member selection '" + std::string(sel) + "' addresses no weight (an index (k) does)";
    return;
  }
  const size_t close = sel.find(')');
  const std::string_view digits = close == npos ? std::string_view() : sel.substr(1, close - 1);
  if (close == npos || digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != npos) {
    a.problem = "the index '" + std::string(sel) + "' is not (k) with k a whole number";
    return;
  }
  if (close + 1 != sel.size()) {
    a.problem = "the selection '" + std::string(sel) + "' has more than one index; a morph's weights have one";
    return;
  }
  a.target = size_t(std::stoul(std::string(digits)));
}

// The morphs by the ids a channel names them by: controllers (before '/'), and weight sources,
// their arrays and CONTROLLER-weights (a target without '/').
struct MorphIds {
  std::map<std::string, size_t> controllers, weights;
  explicit MorphIds(const std::vector<ColladaMorph>& morphs) {
    for (size_t i = 0; i < morphs.size(); ++i) {
      controllers.emplace(morphs[i].controllerId, i);
      for (const std::string& id : {morphs[i].weightSourceId, morphs[i].weightArrayId, morphs[i].controllerId + "-weights"})
        if (!id.empty()) weights.emplace(id, i);
    }
  }
};

// The morph a channel target addresses (see the header), or nullopt: not a morph's weights.
// An id may hold '.' (not '(' or '/'): without '/', the id is what comes before the first '(', or
// before the last '.' (a member selection), whichever names a morph.
std::optional<Address> addressOf(const std::string& target, const MorphIds& ids) {
  const size_t slash = target.find('/');
  Address a;
  size_t idEnd = npos;
  if (slash != npos) {
    auto it = ids.controllers.find(target.substr(0, slash));
    if (it == ids.controllers.end()) return std::nullopt;
    a.morph = it->second;
    idEnd = slash;
  } else {
    for (const size_t end : {target.find('('), target.rfind('.')}) {
      auto it = ids.weights.find(target.substr(0, end));
      if (it == ids.weights.end()) continue;
      a.morph = it->second;
      idEnd = std::min(end, target.size());
      break;
    }
    if (idEnd == npos) return std::nullopt;
  }
  if (idEnd >= target.size()) {
    a.whole = true;
    return a;
  }
  std::string_view rest = std::string_view(target).substr(idEnd);
  if (slash != npos) {
    rest.remove_prefix(1);
    const size_t sel = std::min(rest.find('('), rest.find('.'));
    if (sel == 0 || rest.empty()) {
      a.problem = "no SID after '/'";
      return a;
    }
    rest = sel == npos ? std::string_view() : rest.substr(sel);
  }
  readSelection(rest, a);
  return a;
}

// One target's keys (or every target's, whole), as its channel gives them.
struct Track {
  const std::vector<float>* times = nullptr;   // parsed once per source (Reader::numbers)
  const std::vector<float>* values = nullptr;  // times->size() x width
  bool step = false;                           // every segment STEP
};

enum class Segment { Linear, Step, Curve, Unknown };

Segment segmentOf(const std::string& name) {
  if (name == "LINEAR") return Segment::Linear;
  if (name == "STEP") return Segment::Step;
  if (name == "BEZIER" || name == "HERMITE" || name == "CARDINAL" || name == "BSPLINE") return Segment::Curve;
  return Segment::Unknown;
}

struct Reader {
  const std::string& file;
  View b;
  Element animations;
  std::map<std::string, Element> samplers, sources;  // by id, indexed on the first weight channel
  std::map<std::string, std::vector<float>> numbers;  // parsed <float_array>s, by source id
  bool indexed = false;

  void index() {
    if (indexed) return;
    indexed = true;
    for (Element e = findElement(b, "sampler", animations.begin, animations.close); e.at != npos;
         e = findElement(b, "sampler", e.end, animations.close))
      samplers.emplace(attribute(b, e, "id"), e);
    for (Element e = findElement(b, "source", animations.begin, animations.close); e.at != npos;
         e = findElement(b, "source", e.end, animations.close))
      sources.emplace(attribute(b, e, "id"), e);
  }

  // The source of the sampler input `semantic` (at == npos: the sampler has none).
  Result<Element> input(const std::string& where, const Element& sampler, const std::string& semantic) {
    for (Element in = findElement(b, "input", sampler.begin, sampler.close); in.at != npos;
         in = findElement(b, "input", in.end, sampler.close)) {
      if (attribute(b, in, "semantic") != semantic) continue;
      const std::string ref = attribute(b, in, "source");
      auto s = ref.size() > 1 && ref[0] == '#' ? sources.find(ref.substr(1)) : sources.end();
      if (s == sources.end()) return Error{where + ": " + semantic + " source '" + ref + "' is missing"};
      return s->second;
    }
    return Element{};
  }

  Result<const std::vector<float>*> floatsOf(const std::string& where, const Element& source) {
    const std::string id = attribute(b, source, "id");
    if (auto it = numbers.find(id); it != numbers.end()) return &it->second;
    const Element arr = findElement(b, "float_array", source.begin, source.close);
    if (arr.at == npos) return Error{where + ": source '" + id + "' has no <float_array>"};
    auto v = collada::floats(where + ": source '" + id + "'", b, arr);
    if (!v) return Error{v.error()};
    return &numbers.emplace(id, std::move(*v)).first->second;
  }

  // A sampler's keys, checked once however many channels use it.
  struct Keys {
    const std::vector<float>* times = nullptr;
    const std::vector<float>* values = nullptr;
    size_t steps = 0, curves = 0;  // segments (keys but the last) of each kind
  };
  std::map<std::string, Keys> keysOfSampler;

  Result<const Keys*> keys(const std::string& where, const std::string& ref);
  Result<Track> track(const std::string& where, const Element& channel, size_t width, std::vector<std::string>& notes);
};

// The keys of the sampler ref ("#ID"): INPUT (increasing times), OUTPUT, INTERPOLATION.
Result<const Reader::Keys*> Reader::keys(const std::string& where, const std::string& ref) {
  index();
  if (auto it = keysOfSampler.find(ref); it != keysOfSampler.end()) return &it->second;
  auto sampler = ref.size() > 1 && ref[0] == '#' ? samplers.find(ref.substr(1)) : samplers.end();
  if (sampler == samplers.end()) return Error{where + ": sampler '" + ref + "' is missing"};
  auto in = input(where, sampler->second, "INPUT");
  auto out = in ? input(where, sampler->second, "OUTPUT") : Result<Element>(Error{in.error()});
  auto interp = out ? input(where, sampler->second, "INTERPOLATION") : Result<Element>(Error{out.error()});
  if (!interp) return Error{interp.error()};
  if (in->at == npos || out->at == npos) return Error{where + ": the sampler has no INPUT or no OUTPUT"};
  auto times = floatsOf(where, *in);
  auto values = times ? floatsOf(where, *out) : Result<const std::vector<float>*>(Error{times.error()});
  if (!values) return Error{values.error()};
  Keys k{*times, *values, 0, 0};
  const std::vector<float>& ts = **times;
  if (ts.empty()) return Error{where + ": no keys"};
  for (size_t i = 1; i < ts.size(); ++i)
    if (ts[i] < ts[i - 1]) return Error{where + ": key times decrease at key " + std::to_string(i)};
  if (interp->at != npos) {
    const Element arr = findElement(b, "Name_array", interp->begin, interp->close);
    const std::vector<std::string> names = arr.at != npos ? tokens(b, arr) : std::vector<std::string>{};
    if (names.size() != ts.size())
      return Error{where + ": " + std::to_string(names.size()) + " INTERPOLATION names for " +
                   std::to_string(ts.size()) + " keys"};
    for (size_t i = 0; i + 1 < names.size(); ++i) {  // the last key's interpolation leads nowhere
      const Segment seg = segmentOf(names[i]);
      if (seg == Segment::Unknown)
        return Error{where + ": key " + std::to_string(i) + ": interpolation '" + names[i] + "' is not Collada's"};
      k.steps += seg == Segment::Step;
      k.curves += seg == Segment::Curve;
    }
  }
  return &keysOfSampler.emplace(ref, k).first->second;
}

// The keys of channel (its sampler's), width values a key.
Result<Track> Reader::track(const std::string& where, const Element& channel, size_t width,
                            std::vector<std::string>& notes) {
  auto k = keys(where, attribute(b, channel, "source"));
  if (!k) return Error{k.error()};
  const size_t n = (*k)->times->size();
  if ((*k)->values->size() != n * width)
    return Error{where + ": " + std::to_string((*k)->values->size()) + " OUTPUT values for " + std::to_string(n) +
                 " keys of " + std::to_string(width) + " weight" + (width == 1 ? "" : "s")};
  Track t{(*k)->times, (*k)->values, n > 1 && (*k)->steps == n - 1};
  if ((*k)->curves > 0)
    notes.push_back(where + ": " + std::to_string((*k)->curves) + " curve keys (BEZIER ...) taken as linear");
  if ((*k)->steps > 0 && !t.step) notes.push_back(where + ": STEP keys among linear ones taken as linear");
  return t;
}

// Value v (of width a key) of keys (ts, vals) at time t: held outside the keys, step or linear between.
float keyedValue(const std::vector<float>& ts, const std::vector<float>& vals, size_t width, size_t v, bool step,
                 float t) {
  if (t <= ts.front()) return vals[v];
  if (t >= ts.back()) return vals[(ts.size() - 1) * width + v];
  const size_t hi = size_t(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()), lo = hi - 1;
  const float a = vals[lo * width + v], z = vals[hi * width + v];
  if (step || ts[hi] <= ts[lo]) return a;
  return a + (t - ts[lo]) / (ts[hi] - ts[lo]) * (z - a);
}

// Morph m's tracks (per target; a whole-array track under every target) merged into its keys.
Status merge(const std::string& file, ColladaMorph& m, const std::vector<std::pair<const Track*, size_t>>& perTarget,
             std::vector<std::string>& notes) {
  const size_t n = m.targets.size();
  std::vector<float> times;
  bool step = true, linear = true;
  for (const auto& [tr, width] : perTarget) {
    if (!tr) continue;
    times.insert(times.end(), tr->times->begin(), tr->times->end());
    step = step && tr->step;
    linear = linear && !tr->step;
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  if (times.size() * n > kMaxColladaWeightKeys)
    return Error{file + ": controller '" + m.controllerId + "': weight animation of " + std::to_string(times.size()) +
                 " keys x " + std::to_string(n) + " targets, more than " + std::to_string(kMaxColladaWeightKeys) +
                 " values"};
  if (!step && !linear)
    notes.push_back("controller '" + m.controllerId + "': targets keyed STEP beside linear ones play linear");
  m.weightsStep = step;
  m.weightKeys.resize(times.size() * n);
  for (size_t k = 0; k < n; ++k) {
    const auto& [tr, width] = perTarget[k];
    const size_t v = width == 1 ? 0 : k;
    for (size_t i = 0; i < times.size(); ++i)
      m.weightKeys[i * n + k] =
          tr ? keyedValue(*tr->times, *tr->values, width, v, tr->step, times[i]) : m.defaultWeights[k];
  }
  m.weightTimesSec = std::move(times);
  return {};
}

}  // namespace

Result<std::vector<std::pair<size_t, size_t>>> readColladaMorphWeights(const std::string& file, std::string_view b,
                                                                       std::vector<ColladaMorph>& morphs,
                                                                       std::vector<std::string>& notes) {
  std::vector<std::pair<size_t, size_t>> read;
  Reader r{file, b, findElement(b, "library_animations", 0, b.size()), {}, {}, {}, false, {}};
  if (r.animations.at == npos || r.animations.close == r.animations.end) return read;
  std::deque<Track> tracks;  // pointers into it stay valid
  const MorphIds ids(morphs);
  // Per morph, per target: the track that animates it and the width of its values.
  std::vector<std::vector<std::pair<const Track*, size_t>>> animated(morphs.size());
  for (size_t i = 0; i < morphs.size(); ++i) animated[i].assign(morphs[i].targets.size(), {nullptr, 0});
  for (Element ch = findElement(b, "channel", r.animations.begin, r.animations.close); ch.at != npos;
       ch = findElement(b, "channel", ch.end, r.animations.close)) {
    const std::string target = attribute(b, ch, "target");
    auto address = addressOf(target, ids);
    if (!address) continue;
    const std::string where = file + ": <channel target=\"" + target + "\"> at byte " + std::to_string(ch.at);
    if (!address->problem.empty()) return Error{where + ": " + address->problem};
    ColladaMorph& m = morphs[address->morph];
    const size_t n = m.targets.size();
    if (!address->whole && address->target >= n)
      return Error{where + ": target " + std::to_string(address->target) + " does not exist (controller '" +
                   m.controllerId + "' has " + std::to_string(n) + ")"};
    const size_t width = address->whole ? n : 1;
    auto t = r.track(where, ch, width, notes);
    if (!t) return Error{t.error()};
    tracks.push_back(std::move(*t));
    for (size_t k = address->whole ? 0 : address->target; k < (address->whole ? n : address->target + 1); ++k) {
      if (animated[address->morph][k].first)
        return Error{where + ": target " + std::to_string(k) + " of controller '" + m.controllerId +
                     "' is animated by another channel too"};
      animated[address->morph][k] = {&tracks.back(), width};
    }
    read.push_back({ch.at, ch.end});
  }
  for (size_t i = 0; i < morphs.size(); ++i) {
    const bool any = std::any_of(animated[i].begin(), animated[i].end(), [](const auto& a) { return a.first; });
    if (!any) continue;
    if (Status st = merge(file, morphs[i], animated[i], notes); !st) return Error{st.error()};
  }
  return read;
}

float colladaMorphWeightAt(const ColladaMorph& m, size_t k, float t) {
  if (m.weightTimesSec.empty() || k >= m.targets.size()) return k < m.defaultWeights.size() ? m.defaultWeights[k] : 0.0f;
  return keyedValue(m.weightTimesSec, m.weightKeys, m.targets.size(), k, m.weightsStep, t);
}

}  // namespace animorph
