#include "core/scene/morph_runtime.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/blobtree/validate.h"
#include "core/standin_morph/correspondence_morph.h"
#include "core/standin_morph/mesh_distance.h"
#include "core/poly/solid_noise.h"
#include "core/scene/standin_core.h"
#include "core/rig/pose.h"
#include "core/project/actor_time.h"
#include "core/standin/character_pose.h"

namespace animorph {

const char* morphStageName(MorphStage s) {
  switch (s) {
    case MorphStage::Source: return "source";
    case MorphStage::Collapse: return "collapse";
    case MorphStage::Morph: return "morph";
    case MorphStage::Expand: return "expand";
    case MorphStage::Target: return "target";
  }
  return "source";
}

namespace {

// previous: the same role's runtime of an earlier revision (may be null); its binding is reused
// when nothing it depends on changed (the character, the clip and loop, the stand-in, the
// projection settings previousProjection).
Result<MorphActorRuntime> prepareActor(const Project& project, const std::string& baseDir, AssetCache& assets,
                                       const std::string& id, const char* role, std::vector<std::string>& notes,
                                       const MorphActorRuntime* previous, const MorphProjection* previousProjection) {
  namespace fs = std::filesystem;
  MorphActorRuntime out;
  const Actor* a = project.findActor(id);
  if (!a) return Error{std::string("morph.") + role + ": no actor with id '" + id + "'"};
  out.actor = *a;
  if (a->kind == ActorKind::BlobTree) {
    const std::string where = std::string("morph.") + role + ": actor '" + id + "' (BlobTree)";
    if (Status v = validateBlobTree(a->blobTree); !v) return Error{where + ": " + v.error()};
    const FloatTrack& th = a->blobTree.threshold;
    if (!th.isConstant() || std::abs(th.evaluate(0.0) - kStandinThreshold) > 1e-6f)
      return Error{where + ": threshold " + (th.isConstant() ? std::to_string(th.evaluate(0.0)) : "animated") +
                   ": a morph needs T = " + std::to_string(kStandinThreshold) + " (the stand-ins' threshold)"};
    out.tree = std::make_shared<const BlobTree>(a->blobTree);
    return out;
  }
  const fs::path p(a->assetPath);
  const std::string abs = (p.is_absolute() ? p : fs::path(baseDir) / p).lexically_normal().string();
  const AssetCache::Entry& e = assets.get(abs);
  if (!e.character) return Error{"actor '" + id + "': " + e.error};
  out.character = e.character;
  const Character& c = *out.character;
  if (!c.clips.empty()) out.clip = &c.clips[size_t(std::clamp(a->clip, 0, int(c.clips.size()) - 1))];
  else notes.push_back("actor '" + id + "' (" + a->assetPath + "): no animation: a static pose");
  bool skinned = false;
  for (int n : c.meshNodes()) skinned |= c.nodes[size_t(n)].skin >= 0;
  if (!skinned) notes.push_back("actor '" + id + "' (" + a->assetPath + "): no skin: a rigid one-bone actor");
  const ActorMorph* am = project.morph.findActor(id);
  if (!am || am->standin.segments.empty())
    return Error{"morph.actors: actor '" + id + "' has no stand-in (run animorph-cli new, or fit one)"};
  out.morph = *am;
  for (size_t i = 0; i < am->standin.segments.size(); ++i) {
    const int node = am->standin.segments[i].node;
    if (node < 0 || node >= static_cast<int>(c.nodes.size()))
      return Error{"morph.actors['" + id + "'].standin.segments[" + std::to_string(i) + "].node: " +
                   std::to_string(node) + " is not a node of " + a->assetPath + " (" + std::to_string(c.nodes.size()) +
                   " nodes)"};
  }
  out.vertexCount = c.totalVertices();
  size_t drawn = 0;
  for (int n : c.meshNodes()) drawn += c.meshes[size_t(c.nodes[size_t(n)].mesh)].vertexCount();
  out.vertexCount = drawn;
  if (!am->weightMap.empty() && am->weightMap.size() != drawn)
    return Error{"morph.actors['" + id + "'].weight_map: " + std::to_string(am->weightMap.size()) +
                 " values for " + std::to_string(drawn) + " vertices of " + a->assetPath};
  const MorphProjection& mp = project.morph.projection;
  ProjectionSettings ps;
  ps.maxIterations = mp.maxIterations;
  ps.tolerance = mp.tolerance;
  ps.maxStepRadii = mp.maxStepRadii;
  const AnimationClip* bindClip = mp.atClipTime ? out.clip : nullptr;
  const float bindTime = bindClip ? clipTime(*bindClip, mp.clipTimeSec, out.actor.loop) : 0.0f;
  const bool sameBinding = previous && previousProjection && previous->character == out.character &&
                           previous->actor.clip == a->clip && previous->actor.loop == a->loop &&
                           previous->morph.standin == am->standin && *previousProjection == mp;
  // Binding every vertex is the costly part of preparing (fit + projection of a 50k-vertex character:
  // 37-60 ms, docs/morph.md), and the editor prepares a runtime per revision: an edit of the
  // timing, the easing, the noise or the segment tracks keeps it.
  out.binding = sameBinding ? previous->binding : bindToStandin(c, am->standin, bindClip, bindTime, ps);
  out.bindingKept = sameBinding;
  if (out.binding.stats.failures > 0)
    notes.push_back("actor '" + id + "': " + std::to_string(out.binding.stats.failures) + " of " +
                    std::to_string(out.binding.stats.points) + " vertices could not be projected onto the stand-in");
  return out;
}

std::vector<glm::mat4> actorGlobals(const MorphActorRuntime& a, double timeSec) {
  const Character& c = *a.character;
  const float t = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, timeSec)) : 0.0f;
  return poseGlobals(c, a.clip, t);
}

// The blend-shape weights of each mesh node of the actor at scene time timeSec (meshNodes() order).
std::vector<std::vector<float>> actorMorphWeights(const MorphActorRuntime& a, double timeSec) {
  const Character& c = *a.character;
  const float t = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, timeSec)) : 0.0f;
  std::vector<std::vector<float>> out;
  for (int node : c.meshNodes()) out.push_back(morphWeightsAt(c, node, a.clip, t));
  return out;
}

// The actor's meshes (concatenated over meshNodes()) with the given vertices;
// their vertex colours when every one of them has colours.
TriangleMesh assemble(const Character& c, std::vector<glm::vec3>&& pos, std::vector<glm::vec3>&& nrm) {
  TriangleMesh m;
  size_t first = 0;
  bool colors = true;
  for (int node : c.meshNodes()) {
    const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
    for (uint32_t i : mesh.indices) m.indices.push_back(uint32_t(first + i));
    first += mesh.vertexCount();
    colors = colors && mesh.colors.size() == mesh.vertexCount();
  }
  if (colors && first > 0)
    for (int node : c.meshNodes()) {
      const Mesh& mesh = c.meshes[size_t(c.nodes[size_t(node)].mesh)];
      m.colors.insert(m.colors.end(), mesh.colors.begin(), mesh.colors.end());
    }
  m.positions = std::move(pos);
  m.normals = std::move(nrm);
  return m;
}

TransitionStats transitionMesh(const MorphActorRuntime& a, double timeSec, const std::vector<float>& alpha,
                               bool reproject, float reprojectFrom, int threads, TriangleMesh& out) {
  const auto globals = actorGlobals(a, timeSec);
  const glm::mat4 root = a.actor.transform.matrix();
  TransitionSettings ts;
  ts.threads = threads;
  ts.reprojectFrom = reprojectFrom;
  ts.morphWeights = actorMorphWeights(a, timeSec);
  std::vector<glm::vec3> pos, nrm;
  TransitionStats st;
  bool anyHigh = false;
  for (float x : alpha) anyHigh |= x > 0.0f;
  if (reproject && anyHigh) {
    const auto segs = poseStandin(a.morph.standin, globals, root);
    const FieldProgram prog = standinProgram(a.morph.standin.kind, a.morph.standin.sharpness, segs);
    st = evaluateTransition(*a.character, a.binding, globals, root, alpha, &prog, &segs, ts, pos, nrm);
  } else {
    st = evaluateTransition(*a.character, a.binding, globals, root, alpha, nullptr, nullptr, ts, pos, nrm);
  }
  out = assemble(*a.character, std::move(pos), std::move(nrm));
  // The transition's colours: the textured colour fading into the stand-in's with the position.
  if (a.binding.hasColors()) transitionColors(a.binding, alpha, out.colors);
  return st;
}

}  // namespace

Result<std::shared_ptr<const MorphRuntime>> prepareMorph(const Project& project, const std::string& baseDir,
                                                         AssetCache& assets, const MorphRuntime* previous) {
  const MorphSetup& m = project.morph;
  if (!m.enabled()) return Error{"the project has no morph (morph.source / morph.target not set)"};
  auto rt = std::make_shared<MorphRuntime>();
  rt->setup = m;
  rt->timeline = project.timeline;
  const MorphProjection* pp = previous ? &previous->setup.projection : nullptr;
  auto same = [&](const MorphActorRuntime& r, const std::string& id) { return r.actor.id == id ? &r : nullptr; };
  auto src = prepareActor(project, baseDir, assets, m.sourceActorId, "source", rt->notes,
                          previous ? same(previous->source, m.sourceActorId) : nullptr, pp);
  if (!src) return Error{src.error()};
  auto dst = prepareActor(project, baseDir, assets, m.targetActorId, "target", rt->notes,
                          previous ? same(previous->target, m.targetActorId) : nullptr, pp);
  if (!dst) return Error{dst.error()};
  rt->source = std::move(*src);
  rt->target = std::move(*dst);
  if (m.method == MorphMethod::SkeletonCorrespondence) {
    auto c = morphSkeletonCorrespondence(rt->source, rt->target, m.chainPairs);
    if (c) {
      for (const std::string& w : c->warnings) rt->notes.push_back("skeleton correspondence: morph." + w);
      rt->correspondence = std::make_shared<const SkeletonCorrespondence>(std::move(*c));
    } else rt->notes.push_back("skeleton correspondence: " + c.error() + ": interpolation used instead");
  }
  MorphMarkers& k = rt->setup.markers;
  if (rt->source.isTree()) k.a = k.b;
  if (rt->target.isTree()) k.d = k.c;
  return std::shared_ptr<const MorphRuntime>(std::move(rt));
}

Result<SkeletonCorrespondence> morphSkeletonCorrespondence(const MorphActorRuntime& source,
                                                           const MorphActorRuntime& target,
                                                           const std::vector<ChainPair>& pairs) {
  for (const MorphActorRuntime* a : {&source, &target})
    if (a->isTree() || !a->character)
      return Error{"actor '" + a->actor.id + "' is a BlobTree (no rig to correspond)"};
  SkeletonChains s = skeletonChains(*source.character, source.morph.standin);
  SkeletonChains t = skeletonChains(*target.character, target.morph.standin);
  for (const auto& [chains, a] : {std::pair{&s, &source}, std::pair{&t, &target}})
    if (chains->chains.empty()) return Error{"actor '" + a->actor.id + "': no stand-in segment is on a node of its rig"};
  return correspondSkeletons(std::move(s), std::move(t), pairs);
}

MorphStage morphStageAt(const MorphSetup& s, const Timeline& tl, double timeSec, double& u) {
  const double f = timeSec * tl.fps;
  const double eps = 1e-6;
  const MorphMarkers& k = s.markers;
  u = 0.0;
  auto frac = [&](int a, int b) { return b > a ? std::clamp((f - a) / double(b - a), 0.0, 1.0) : 1.0; };
  if (f < k.a - eps) return MorphStage::Source;
  if (f < k.b - eps) { u = frac(k.a, k.b); return MorphStage::Collapse; }
  if (f <= k.c + eps) { u = k.c > k.b ? frac(k.b, k.c) : 0.0; return MorphStage::Morph; }
  if (f <= k.d + eps) { u = frac(k.c, k.d); return MorphStage::Expand; }
  return MorphStage::Target;
}

bool morphHasColors(const MorphRuntime& rt) {
  for (const MorphActorRuntime* a : {&rt.source, &rt.target})
    if (a->isTree() || a->binding.hasColors()) return true;
  return false;
}

MorphOperand posedOperand(const MorphActorRuntime& a, double timeSec, double u) {
  if (a.isTree()) {
    MorphOperand op;
    op.tree = a.tree;
    op.treeTimeSec = blobActorTimeSec(a.actor, timeSec);
    op.transform = a.actor.transform;
    return op;
  }
  Standin s = a.morph.standin;
  std::vector<float> scale(s.segments.size(), 1.0f);
  if (u >= 0.0) {
    for (const SegmentTracks& t : a.morph.segmentTracks) {
      if (t.segment < 0 || t.segment >= static_cast<int>(s.segments.size())) continue;
      StandinSegment& seg = s.segments[size_t(t.segment)];
      seg.a += t.aOffset.evaluate(u);
      seg.b += t.bOffset.evaluate(u);
      const float k = std::max(0.0f, t.radiusScale.evaluate(u));
      seg.radius *= std::max(k, 1e-4f);
      scale[size_t(t.segment)] = std::min(1.0f, 4.0f * k);
    }
  }
  MorphOperand op;
  op.kind = s.kind;
  op.sharpness = s.sharpness;
  op.segments = poseStandin(s, actorGlobals(a, timeSec), a.actor.transform.matrix());
  for (size_t i = 0; i < scale.size(); ++i) op.segments[i].weightScale = scale[i];
  if (a.binding.segmentColors.size() == op.segments.size())
    for (size_t i = 0; i < op.segments.size(); ++i) op.segments[i].colors = a.binding.segmentColors[i];
  return op;
}

MorphImplicitField morphImplicitField(const MorphRuntime& rt, double timeSec, int resolution, double progress) {
  MorphImplicitField out;
  const MorphSetup& m = rt.setup;
  morphStageAt(m, rt.timeline, timeSec, out.progress);
  if (progress >= 0.0) out.progress = std::min(progress, 1.0);
  out.blend = std::clamp(m.blend.evaluate(out.progress), 0.0f, 1.0f);
  const MorphOperand src = posedOperand(rt.source, timeSec, out.progress);
  const MorphOperand dst = posedOperand(rt.target, timeSec, out.progress);
  auto build = [&](bool colorProfiles) {
    return rt.correspondence
               ? buildCorrespondenceMorphProgram(*rt.correspondence, src, dst, m.correspondenceBlend, out.blend,
                                                 m.spaceTime, m.interpolationBound, colorProfiles)
               : buildMorphProgram(src, dst, m.method, out.blend, m.spaceTime, m.interpolationBound, colorProfiles);
  };
  out.program = build(false);
  if (morphHasColors(rt)) out.colorProgram = std::make_shared<const FieldProgram>(build(true));
  out.noiseAmplitude = m.noiseAmplitude.evaluate(out.progress);
  if (out.program.unbounded()) {
    // Space-time blending: the bound solid makes the field positive far
    // away in principle; the grid covers both stand-ins with a margin.
    Bounds box;
    if (out.blend < 1.0f) box.add(morphOperandBounds(src));
    if (out.blend > 0.0f) box.add(morphOperandBounds(dst));
    const float cell =
        box.empty() ? 0.0f : std::max(box.size().x, std::max(box.size().y, box.size().z)) / float(std::max(2, resolution));
    box.min -= glm::vec3(2.0f * cell);
    box.max += glm::vec3(2.0f * cell);
    out.bounds = box;
  }
  return out;
}

std::optional<MorphImplicitField> morphFrameField(const MorphRuntime& rt, double timeSec, int resolution) {
  double u = 0.0;
  switch (morphStageAt(rt.setup, rt.timeline, timeSec, u)) {
    case MorphStage::Morph: return morphImplicitField(rt, timeSec, resolution, std::clamp(u, 0.0, 1.0));
    case MorphStage::Source:
      if (rt.source.isTree()) return morphImplicitField(rt, timeSec, resolution, 0.0);
      return std::nullopt;
    case MorphStage::Target:
      if (rt.target.isTree()) return morphImplicitField(rt, timeSec, resolution, 1.0);
      return std::nullopt;
    case MorphStage::Collapse:
    case MorphStage::Expand: return std::nullopt;
  }
  return std::nullopt;
}

Result<MorphFrame> evaluateMorphFrame(const MorphRuntime& rt, double timeSec, const MorphFrameSettings& settings) {
  MorphFrame fr;
  fr.timeSec = timeSec;
  fr.stage = morphStageAt(rt.setup, rt.timeline, timeSec, fr.progress);
  switch (fr.stage) {
    case MorphStage::Source:
    case MorphStage::Target: {
      const MorphActorRuntime& a = fr.stage == MorphStage::Source ? rt.source : rt.target;
      if (a.isTree()) {  // the tree itself: the implicit morph at its end
        auto r = evaluateMorphImplicit(rt, timeSec, fr.stage == MorphStage::Source ? 0.0 : 1.0, settings);
        if (!r) return r;
        r->stage = fr.stage;
        r->progress = 0.0;
        r->actorId = a.actor.id;
        return r;
      }
      fr.actorId = a.actor.id;
      std::vector<float> zero(a.vertexCount, 0.0f);
      fr.transition = transitionMesh(a, timeSec, zero, false, 1.0f, settings.threads, fr.mesh);
      break;
    }
    case MorphStage::Collapse:
    case MorphStage::Expand: {
      MorphFrame t = evaluateMorphTransition(rt, timeSec, fr.stage == MorphStage::Expand, fr.progress, settings);
      if (settings.standinCore)
        if (Status s = appendStandinCore(rt, t, settings); !s) return Error{s.error()};
      return t;
    }
    case MorphStage::Morph: return evaluateMorphImplicit(rt, timeSec, fr.progress, settings);
  }
  return fr;
}

MorphFrame evaluateMorphTransition(const MorphRuntime& rt, double timeSec, bool expand, double u,
                                   const MorphFrameSettings& settings) {
  const MorphSetup& m = rt.setup;
  MorphFrame fr;
  fr.timeSec = timeSec;
  fr.stage = expand ? MorphStage::Expand : MorphStage::Collapse;
  fr.progress = std::clamp(u, 0.0, 1.0);
  const MorphActorRuntime& a = expand ? rt.target : rt.source;
  fr.actorId = a.actor.id;
  std::vector<float> alpha;
  transitionAlphas(fr.progress, m.easing, a.morph.weightMap, m.weightMapShift, expand, a.vertexCount, alpha);
  fr.transition = transitionMesh(a, timeSec, alpha, settings.reproject && m.projection.reprojectFrom < 1.0f,
                                 m.projection.reprojectFrom, settings.threads, fr.mesh);
  return fr;
}

Result<MorphFrame> evaluateMorphImplicit(const MorphRuntime& rt, double timeSec, double u,
                                         const MorphFrameSettings& settings) {
  MorphImplicitField field = morphImplicitField(rt, timeSec, settings.resolution, std::clamp(u, 0.0, 1.0));
  MorphFrame fr;
  fr.timeSec = timeSec;
  fr.stage = MorphStage::Morph;
  fr.progress = field.progress;
  fr.blend = field.blend;
  PolygonizeSettings ps;
  ps.resolution = settings.resolution;
  ps.threads = settings.threads;
  ps.cancel = settings.cancel;
  ps.bounds = field.bounds;
  ps.colors = settings.colors && field.colorProgram;
  ps.colorProgram = field.colorProgram.get();
  auto r = polygonize(field.program, ps);
  if (!r) return Error{"morph at " + std::to_string(timeSec) + " s: " + r.error()};
  fr.cancelled = r->cancelled;
  fr.mesh = std::move(r->mesh);
  fr.polygonize = r->stats;
  displaceBySolidNoise(fr.mesh, field.noiseAmplitude, rt.setup.noiseFrequency);
  return fr;
}

Result<SeamGap> measureSeamGap(const MorphRuntime& rt, bool atB, int resolution) {
  const MorphSetup& m = rt.setup;
  const double timeSec = rt.timeline.frameToSec(atB ? m.markers.b : m.markers.c);
  const MorphActorRuntime& a = atB ? rt.source : rt.target;
  if (a.isTree()) return SeamGap{};  // no transition: the morph starts (ends) on the tree itself
  std::vector<float> one(a.vertexCount, 1.0f);
  TriangleMesh transition;
  transitionMesh(a, timeSec, one, m.projection.reprojectFrom < 1.0f, m.projection.reprojectFrom, 0, transition);
  MorphFrameSettings fs;
  fs.resolution = resolution;
  auto frame = evaluateMorphFrame(rt, timeSec, fs);
  if (!frame) return Error{frame.error()};
  if (frame->stage != MorphStage::Morph) return Error{"the morph stage is empty (B and C are not in order)"};
  const PointMeshDistances d = pointsToMeshDistance(transition.positions, frame->mesh);
  SeamGap g;
  g.maxDistance = d.maxDistance;
  g.meanDistance = d.meanDistance;
  g.cellSize = frame->polygonize.cellSize;
  return g;
}

}  // namespace animorph
