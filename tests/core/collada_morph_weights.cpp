// Collada morph weight animation (io/collada_morph_weights.h): Blender-written Collada files (its
// shape keys as <morph> controllers) given the <animation>s OpenCOLLADA writes for a morph's
// weights, in the addressing forms exporters use, checked against the same file with the weights
// held at each value (the static path), and malformed channels refused naming the channel.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/io/character_import.h"
#include "core/io/collada_morph_weights.h"
#include "core/io/collada_morphs.h"
#include "core/rig/skinning.h"
#include "util/temp_dir.h"
#include "util/test_characters.h"
#include "util/test_skip.h"

using namespace animorph;
using animorph::test::TempDir;

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string join(const std::vector<float>& v) {
  std::ostringstream s;
  for (size_t i = 0; i < v.size(); ++i) s << (i ? " " : "") << v[i];
  return s.str();
}

// One <animation> as OpenCOLLADA writes it: INPUT (TIME), OUTPUT (values, width a key) and
// INTERPOLATION sources, a sampler, a channel with target.
struct Keys {
  std::vector<float> times, values;
  std::vector<std::string> interpolation;  // one per key; empty: no INTERPOLATION input
  size_t width = 1;
};

std::string animationXml(const std::string& id, const std::string& target, const Keys& k) {
  auto source = [&](const std::string& name, const std::string& array, size_t count, size_t stride,
                    const std::string& param, const std::string& type) {
    return "<source id=\"" + id + "-" + name + "\">" + array + "<technique_common><accessor source=\"#" + id + "-" + name +
           "-array\" count=\"" + std::to_string(count) + "\" stride=\"" + std::to_string(stride) + "\"><param name=\"" +
           param + "\" type=\"" + type + "\"/></accessor></technique_common></source>\n";
  };
  std::string out = "<animation id=\"" + id + "\">\n";
  out += source("input", "<float_array id=\"" + id + "-input-array\" count=\"" + std::to_string(k.times.size()) + "\">" +
                             join(k.times) + "</float_array>",
                k.times.size(), 1, "TIME", "float");
  out += source("output", "<float_array id=\"" + id + "-output-array\" count=\"" + std::to_string(k.values.size()) +
                              "\">" + join(k.values) + "</float_array>",
                k.values.size() / k.width, k.width, "WEIGHT", "float");
  std::string names;
  for (const auto& n : k.interpolation) names += (names.empty() ? "" : " ") + n;
  if (!k.interpolation.empty())
    out += source("interpolation", "<Name_array id=\"" + id + "-interpolation-array\" count=\"" +
                                       std::to_string(k.interpolation.size()) + "\">" + names + "</Name_array>",
                  k.interpolation.size(), 1, "INTERPOLATION", "name");
  out += "<sampler id=\"" + id + "-sampler\"><input semantic=\"INPUT\" source=\"#" + id +
         "-input\"/><input semantic=\"OUTPUT\" source=\"#" + id + "-output\"/>";
  if (!k.interpolation.empty()) out += "<input semantic=\"INTERPOLATION\" source=\"#" + id + "-interpolation\"/>";
  out += "</sampler>\n<channel source=\"#" + id + "-sampler\" target=\"" + target + "\"/>\n</animation>\n";
  return out;
}

// The document with the animations added to its <library_animations> (made when it has none).
std::string withAnimations(std::string dae, const std::string& xml) {
  const std::string open = "<library_animations>";
  if (size_t at = dae.find(open); at != std::string::npos) return dae.insert(at + open.size(), "\n" + xml);
  const size_t at = dae.find("<library_visual_scenes>");
  REQUIRE(at != std::string::npos);
  return dae.insert(at, open + "\n" + xml + "</library_animations>\n");
}

// The document with morph m's weights held at w (its MORPH_WEIGHT array rewritten): the static
// path, which reads the weights as the character's rest weights.
std::string withWeights(std::string dae, const ColladaMorph& m, const std::vector<float>& w) {
  const size_t source = dae.find("<source id=\"" + m.weightSourceId + "\"");
  REQUIRE(source != std::string::npos);
  const size_t open = dae.find('>', dae.find("<float_array", source)) + 1;
  const size_t close = dae.find("</float_array>", open);
  return dae.replace(open, close - open, join(w));
}

std::vector<ColladaMorph> morphsOf(const std::string& dae) {
  auto prepared = prepareColladaMorphs("x.dae", dae, size_t(1) << 30);
  INFO(prepared.error());
  REQUIRE(prepared.ok());
  return prepared->morphs;
}

Character importText(TempDir& tmp, const std::string& name, const std::string& dae) {
  std::ofstream(tmp.file(name), std::ios::binary) << dae;
  auto c = importCharacter(tmp.file(name));
  INFO((c.ok() ? std::string("ok") : c.error()));
  REQUIRE(c.ok());
  return std::move(*c);
}

const Channel* weightsChannel(const Character& c) {
  if (c.clips.empty()) return nullptr;
  for (const Channel& ch : c.clips[0].channels)
    if (ch.path == ChannelPath::Weights) return &ch;
  return nullptr;
}

// Largest distance between the two characters' posed vertices (same meshes, same order) at t,
// relative to a's diagonal.
double poseGap(const Character& a, const Character& b, float t) {
  const auto pa = skinnedWorldPositions(a, a.clips.empty() ? nullptr : &a.clips[0], t);
  const auto pb = skinnedWorldPositions(b, b.clips.empty() ? nullptr : &b.clips[0], t);
  REQUIRE(pa.size() == pb.size());
  Bounds box;
  double worst = 0.0;
  for (size_t i = 0; i < pa.size(); ++i) {
    box.add(pa[i]);
    worst = std::max(worst, double(glm::distance(pa[i], pb[i])));
  }
  return worst / box.diagonal();
}

// Linear (or step) weight of keys (times, values) at t, held outside them.
float expected(const std::vector<float>& ts, const std::vector<float>& vs, float t, bool step = false) {
  if (t <= ts.front()) return vs.front();
  if (t >= ts.back()) return vs.back();
  size_t hi = 1;
  while (ts[hi] <= t) ++hi;
  if (step) return vs[hi - 1];
  return vs[hi - 1] + (t - ts[hi - 1]) / (ts[hi] - ts[hi - 1]) * (vs[hi] - vs[hi - 1]);
}

const std::string kRig = std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/collada/rig.dae";

}  // namespace

TEST_CASE("collada morph weights: channels in three addressing forms play the shape as the file held at each "
          "weight does, at the keys and between them",
          "[assimp][blendshape]") {
  const std::string dae = readText(kRig);
  const std::vector<ColladaMorph> morphs = morphsOf(dae);
  REQUIRE(morphs.size() == 1);
  const ColladaMorph& m = morphs[0];
  REQUIRE(m.targets.size() == 1);
  REQUIRE_FALSE(m.weightSourceId.empty());
  TempDir tmp;
  const Keys linear{{0.2f, 0.6f, 1.0f, 2.5f}, {0.0f, 1.0f, 0.3f, 0.6f}, {"LINEAR", "LINEAR", "LINEAR", "LINEAR"}};
  std::map<float, Character> held;  // the static file at each weight
  auto heldAt = [&](float w) -> const Character& {
    auto it = held.find(w);
    if (it == held.end()) it = held.emplace(w, importText(tmp, "held.dae", withWeights(dae, m, {w}))).first;
    return it->second;
  };
  // The shape moves some vertices and leaves others.
  const auto rest = skinnedWorldPositions(heldAt(0.0f), nullptr, 0.0f);
  const auto full = skinnedWorldPositions(heldAt(1.0f), nullptr, 0.0f);
  size_t moved = 0;
  for (size_t i = 0; i < rest.size(); ++i) moved += glm::distance(rest[i], full[i]) > 1e-3f;
  CHECK(moved > 0);
  CHECK(moved < rest.size());

  for (const std::string& target :
       {m.controllerId + "/MorphWeights(0)", m.weightSourceId + "(0)", m.controllerId + "-weights(0)", m.weightSourceId,
        m.weightArrayId + "(0)"}) {
    INFO("channel target " << target);
    const Character c = importText(tmp, "animated.dae", withAnimations(dae, animationXml("w", target, linear)));
    REQUIRE(c.clips.size() == 1);
    const Channel* ch = weightsChannel(c);
    REQUIRE(ch != nullptr);
    CHECK(ch->interpolation == Interpolation::Linear);
    CHECK(c.meshes[size_t(c.nodes[size_t(ch->node)].mesh)].morphTargets.size() == 1);
    CHECK(c.clips[0].durationSec >= 2.5f);  // the clip covers the last weight key
    for (float t : {0.0f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f, 1.75f, 2.5f, 3.0f}) {
      const float w = expected(linear.times, linear.values, t);
      INFO("t " << t << " weight " << w);
      CHECK(poseGap(c, heldAt(w), t) < 1e-5);
    }
  }
}

TEST_CASE("collada morph weights: a file with no other animation gets a clip for its weights", "[assimp][blendshape]") {
  std::string dae = readText(kRig);
  const size_t from = dae.find("<library_animations>");
  const size_t to = dae.find("</library_animations>");
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  dae.erase(from, to + std::string("</library_animations>").size() - from);  // Blender's bone keys gone
  const ColladaMorph m = morphsOf(dae).at(0);
  TempDir tmp;
  const Character still = importText(tmp, "still.dae", dae);
  CHECK(still.clips.empty());
  const Keys keys{{0.5f, 1.5f}, {0.0f, 1.0f}, {}};
  const Character c =
      importText(tmp, "animated.dae", withAnimations(dae, animationXml("w", m.controllerId + "/MorphWeights(0)", keys)));
  REQUIRE(c.clips.size() == 1);
  CHECK(c.clips[0].durationSec == Approx(1.5f));
  REQUIRE(weightsChannel(c));
  for (float t : {0.0f, 0.75f, 1.0f, 2.0f}) {
    INFO("t " << t);
    const Character held = importText(tmp, "held.dae", withWeights(dae, m, {expected(keys.times, keys.values, t)}));
    CHECK(poseGap(c, held, t) < 1e-5);
  }
}

TEST_CASE("collada morph weights: STEP holds each key, BEZIER keys play linear and the report says so",
          "[assimp][blendshape]") {
  const std::string dae = readText(kRig);
  const ColladaMorph m = morphsOf(dae).at(0);
  TempDir tmp;
  const Character held0 = importText(tmp, "h0.dae", withWeights(dae, m, {0.0f}));
  const Character held1 = importText(tmp, "h1.dae", withWeights(dae, m, {1.0f}));
  const Character heldHalf = importText(tmp, "h5.dae", withWeights(dae, m, {0.5f}));
  const std::string target = m.controllerId + "/MorphWeights(0)";
  const Character step = importText(
      tmp, "step.dae", withAnimations(dae, animationXml("w", target, {{0.2f, 0.6f, 1.0f}, {0.0f, 1.0f, 0.0f}, {"STEP", "STEP", "STEP"}})));
  REQUIRE(weightsChannel(step));
  CHECK(weightsChannel(step)->interpolation == Interpolation::Step);
  CHECK(poseGap(step, held0, 0.4f) < 1e-5);  // held at the first key's 0 until the second
  CHECK(poseGap(step, held1, 0.8f) < 1e-5);
  CHECK(poseGap(step, held0, 1.2f) < 1e-5);
  const Character bezier = importText(
      tmp, "bezier.dae",
      withAnimations(dae, animationXml("w", target, {{0.2f, 0.6f}, {0.0f, 1.0f}, {"BEZIER", "BEZIER"}})));
  CHECK(poseGap(bezier, heldHalf, 0.4f) < 1e-5);
  const auto& warnings = bezier.report.warnings;
  CHECK(std::any_of(warnings.begin(), warnings.end(),
                    [](const std::string& w) { return w.find("taken as linear") != std::string::npos; }));
}

TEST_CASE("collada morph weights: malformed channels are refused naming the file, the channel, its byte offset and "
          "the reason",
          "[assimp][blendshape]") {
  const std::string dae = readText(kRig);
  const ColladaMorph m = morphsOf(dae).at(0);
  const std::string ctl = m.controllerId + "/MorphWeights";
  const Keys good{{0.2f, 0.6f, 1.0f}, {0.0f, 1.0f, 0.5f}, {"LINEAR", "LINEAR", "LINEAR"}};
  auto refused = [&](const std::string& xml, const std::string& target, const std::string& reason) {
    INFO("target " << target << ", expecting " << reason);
    const std::string bad = withAnimations(dae, xml);
    auto r = prepareColladaMorphs("rig.dae", bad, 1000000);
    REQUIRE_FALSE(r.ok());
    INFO(r.error());
    const size_t at = bad.rfind("<channel ", bad.find("target=\"" + target + "\""));
    CHECK(r.error().rfind("rig.dae: <channel target=\"" + target + "\"> at byte ", 0) == 0);
    CHECK(r.error().find("at byte " + std::to_string(at) + ":") != std::string::npos);
    CHECK(r.error().find(reason) != std::string::npos);
  };
  refused(animationXml("w", ctl + "(3)", good), ctl + "(3)", "target 3 does not exist");
  refused(animationXml("w", ctl + "(0)(0)", good), ctl + "(0)(0)", "more than one index");
  refused(animationXml("w", ctl + ".X", good), ctl + ".X", "member selection");
  refused(animationXml("w", m.weightSourceId + ".X", good), m.weightSourceId + ".X", "member selection");
  refused(animationXml("w", ctl + "(0)", {{0.2f, 0.6f, 1.0f}, {0.0f, 1.0f}, {}}), ctl + "(0)",
          "2 OUTPUT values for 3 keys");
  refused(animationXml("w", ctl + "(0)", {{0.2f, 0.6f, 1.0f}, {0.0f, 1.0f, 0.5f}, {"LINEAR"}}), ctl + "(0)",
          "1 INTERPOLATION names for 3 keys");
  refused(animationXml("w", ctl + "(0)", {{0.2f, 1.0f, 0.6f}, {0.0f, 1.0f, 0.5f}, {}}), ctl + "(0)",
          "key times decrease at key 2");
  refused(animationXml("w", ctl + "(0)", {{0.2f, 0.6f}, {0.0f, 1.0f}, {"SMOOTH", "LINEAR"}}), ctl + "(0)",
          "interpolation 'SMOOTH' is not Collada's");
  {
    std::string nan = animationXml("w", ctl + "(0)", good);
    nan.replace(nan.find("0 1 0.5"), 7, "0 nan 0.5");
    refused(nan, ctl + "(0)", "not a finite number at byte");
  }
  {
    std::string missing = animationXml("w", ctl + "(0)", good);
    missing.replace(missing.find("source=\"#w-output\""), 18, "source=\"#nowhere\"");
    refused(missing, ctl + "(0)", "OUTPUT source '#nowhere' is missing");
  }
  refused(animationXml("a", ctl + "(0)", good) + animationXml("b", m.weightSourceId + "(0)", good),
          m.weightSourceId + "(0)", "animated by another channel too");
  // Through the importer, the path as given leads the message; a channel for a node is not read here.
  TempDir tmp;
  std::ofstream(tmp.file("bad.dae"), std::ios::binary) << withAnimations(dae, animationXml("w", ctl + "(3)", good));
  auto r = importCharacter(tmp.file("bad.dae"));
  REQUIRE_FALSE(r.ok());
  CHECK(r.error().rfind(tmp.file("bad.dae") + ": <channel target=", 0) == 0);
  auto fine = prepareColladaMorphs("rig.dae", dae, 1000000);
  REQUIRE(fine.ok());
  CHECK(fine->morphs[0].weightTimesSec.empty());  // Blender's own channels address bones only
}

TEST_CASE("collada morph weights: each test character's Collada with OpenCOLLADA weight channels added plays its "
          "shapes as the file held at each weight, the clip covering the keys",
          "[.daeweights]") {
  const std::string dir = ANIMORPH_TEST_CHARACTERS;
  const auto entries = test::testCharacterEntries(dir, "dae");
  if (entries.empty()) ANIMORPH_SKIP("the test characters are missing (" << dir << "/manifest.json; the fixture needs Blender)");
  int checked = 0;
  for (const auto& entry : entries) {
    const std::string file = entry.at("file").get<std::string>();
    INFO(file);
    const std::string dae = readText(dir + "/" + file);
    const std::vector<ColladaMorph> morphs = morphsOf(dae);
    REQUIRE(morphs.size() == 1);
    const ColladaMorph& m = morphs[0];
    const size_t n = m.targets.size();
    REQUIRE(n >= 1);
    TempDir tmp;
    const Character still = importText(tmp, "still.dae", dae);
    REQUIRE(still.clips.size() == 1);
    const float start = still.clips[0].durationSec * 0.1f, end = still.clips[0].durationSec + 0.5f;
    CHECK(still.clips[0].durationSec < end);  // the keys outlast Blender's clip
    // Target k: keys of its own (the first at 0 and 1, the others between), in a form by k and file.
    std::vector<std::vector<float>> times(n), values(n);
    std::string xml;
    const bool whole = file.find("_cm") != std::string::npos;  // the whole array, one channel
    for (size_t k = 0; k < n; ++k) {
      times[k] = whole ? std::vector<float>{start, end} : std::vector<float>{start + 0.1f * float(k), 0.5f * (start + end), end};
      values[k] = whole ? std::vector<float>{0.9f - 0.3f * float(k), 0.1f}
                        : std::vector<float>{0.0f, 1.0f - 0.2f * float(k), 0.4f};
      const std::string forms[] = {m.controllerId + "/MorphWeights(" + std::to_string(k) + ")",
                                   m.weightSourceId + "(" + std::to_string(k) + ")",
                                   m.controllerId + "-weights(" + std::to_string(k) + ")"};
      if (!whole) xml += animationXml("w" + std::to_string(k), forms[k % 3], {times[k], values[k], {}});
    }
    if (whole) {
      Keys all{times[0], {}, {}, n};
      for (size_t i = 0; i < 2; ++i)
        for (size_t k = 0; k < n; ++k) all.values.push_back(values[k][i]);
      xml = animationXml("w", m.weightSourceId, all);
    }
    const Character c = importText(tmp, "animated.dae", withAnimations(dae, xml));
    REQUIRE(c.clips.size() == 1);
    CHECK(c.clips[0].durationSec >= end - 1e-6f);
    std::vector<float> at{0.0f};
    for (size_t k = 0; k < n; ++k)
      for (size_t i = 0; i < times[k].size(); ++i) {
        at.push_back(times[k][i]);
        if (i + 1 < times[k].size()) at.push_back(0.5f * (times[k][i] + times[k][i + 1]));
      }
    // The file held at the first time's weights is read once; at the other times the character
    // read from it holds its shapes at the weights there (what that file would give, without
    // reading 19,000 vertices again at every time).
    std::vector<float> w0(n);
    for (size_t k = 0; k < n; ++k) w0[k] = expected(times[k], values[k], at[0]);
    const Character heldFile = importText(tmp, "held.dae", withWeights(dae, m, w0));
    for (float t : at) {
      Character held = heldFile;
      for (Mesh& mesh : held.meshes)
        if (mesh.morphTargets.size() == n)
          for (size_t k = 0; k < n; ++k) mesh.defaultMorphWeights[k] = expected(times[k], values[k], t);
      INFO("t " << t);
      CHECK(poseGap(c, held, t) < 1e-5);
    }
    CHECK(poseGap(c, heldFile, at[0]) < 1e-5);
    ++checked;
  }
  CHECK(checked == 9);
}
