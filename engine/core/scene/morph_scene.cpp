#include "core/scene/morph_scene.h"

#include <algorithm>
#include <cmath>

#include "core/scene/standin_core.h"
#include "core/scene/transition_frame.h"
#include "core/rig/pose.h"
#include "core/scene/mesh_character.h"

namespace animorph {

namespace {

// The collapse / expansion of one actor as vertex-shader draws, one per mesh node.
void addGpuTransition(SceneFrame& frame, const std::shared_ptr<const MorphRuntime>& rt, bool expand, double timeSec,
                      double u, const MorphFrameSettings& settings, float opacity) {
  const MorphActorRuntime& a = expand ? rt->target : rt->source;
  const Character& c = *a.character;
  auto params = std::make_shared<const TransitionFrame>(transitionFrame(*rt, expand, timeSec, u, settings.reproject));
  const float clipT = a.clip ? float(actorClipTimeSec(a.actor, *a.clip, timeSec)) : 0.0f;
  const std::vector<glm::mat4> globals = poseGlobals(c, a.clip, clipT);
  const glm::mat4 root = a.actor.transform.matrix();
  size_t first = 0;
  for (int node : c.meshNodes()) {
    const int meshIndex = c.nodes[size_t(node)].mesh;
    TransitionDraw t;
    t.mesh.actorId = a.actor.id;
    t.mesh.character = a.character;
    t.mesh.meshNode = node;
    t.mesh.meshIndex = meshIndex;
    t.mesh.model = root * globals[size_t(node)];
    t.mesh.joints = jointMatrices(c, node, globals);
    t.mesh.morphWeights = morphWeightsAt(c, node, a.clip, clipT);
    t.mesh.opacity = opacity;
    t.runtime = rt;
    t.targetActor = expand;
    t.firstVertex = first;
    t.frame = params;
    frame.transitions.push_back(std::move(t));
    first += c.meshes[size_t(meshIndex)].vertexCount();
  }
}

void addMeshDraw(SceneFrame& frame, const std::string& actorId, const TriangleMesh& mesh, float opacity,
                 bool complementDither) {
  if (mesh.positions.empty()) return;
  MeshDraw d;
  d.actorId = actorId;
  d.character = characterFromMesh(mesh, "morph");
  d.meshNode = 0;
  d.meshIndex = 0;
  d.joints = {glm::mat4(1.0f)};
  d.opacity = opacity;
  d.complementDither = complementDither;
  frame.meshes.push_back(std::move(d));
}

MorphSceneInfo apply(SceneFrame& frame, const MorphRuntime& rt, const std::shared_ptr<const MorphRuntime>& shared,
                     double timeSec, const MorphFrameSettings& settings, bool implicitStage) {
  MorphSceneInfo info;
  info.stage = morphStageAt(rt.setup, rt.timeline, timeSec, info.progress);
  const std::string& src = rt.setup.sourceActorId;
  const std::string& dst = rt.setup.targetActorId;
  // Which actor's own skinned mesh stays; the other (or both) go.
  const std::string keep = info.stage == MorphStage::Source ? src : info.stage == MorphStage::Target ? dst : "";
  // The skeleton overlay follows the actor whose shape is on screen.
  const std::string bonesOf = info.stage == MorphStage::Collapse  ? src
                              : info.stage == MorphStage::Expand ? dst
                                                                 : keep;
  auto drop = [&](const std::string& id, const std::string& kept) { return (id == src || id == dst) && id != kept; };
  std::erase_if(frame.meshes, [&](const MeshDraw& d) { return drop(d.actorId, keep); });
  std::erase_if(frame.blobs, [&](const BlobDraw& d) { return drop(d.actorId, keep); });
  frame.blobGuides.dropIf([&](const std::string& id) { return drop(id, bonesOf); });
  std::erase_if(frame.bones, [&](const BoneDraw& b) { return drop(b.actorId, bonesOf); });
  if (!keep.empty()) return info;

  // What is drawn: the transition of one actor at progress meshU, the implicit
  // morph at implicitU, with complementary opacity (1 and 0 outside the cross-fade).
  const MorphSetup& m = rt.setup;
  const double f = timeSec * rt.timeline.fps;
  const bool nearB = std::abs(f - m.markers.b) <= std::abs(f - m.markers.c);
  double implicitOpacity = info.stage == MorphStage::Morph ? 1.0 : 0.0;
  // A BlobTree side has no transition: nothing to fade with near its marker.
  const bool treeNear = nearB ? rt.source.isTree() : rt.target.isTree();
  if (m.crossFade.enabled && !treeNear) {
    const double w = std::max(1, m.crossFade.widthFrames);
    if (nearB && std::abs(f - m.markers.b) < w) implicitOpacity = std::clamp((f - (m.markers.b - w)) / (2.0 * w), 0.0, 1.0);
    if (!nearB && std::abs(f - m.markers.c) < w) implicitOpacity = std::clamp((m.markers.c + w - f) / (2.0 * w), 0.0, 1.0);
  }
  const bool expand = info.stage == MorphStage::Expand || (info.stage == MorphStage::Morph && !nearB);
  const double meshU = info.stage == MorphStage::Morph ? (expand ? 0.0 : 1.0) : info.progress;
  const double implicitU = info.stage == MorphStage::Morph ? info.progress : (expand ? 1.0 : 0.0);
  const float meshOpacity = float(1.0 - implicitOpacity);
  info.implicitOpacity = implicitOpacity;
  info.implicitProgress = implicitU;
  // The collapse and the expansion are drawn around their stand-in core while it lasts.
  const bool transition = info.stage == MorphStage::Collapse || info.stage == MorphStage::Expand;
  if (transition && settings.standinCore && standinCoreField(rt, timeSec, expand, info.progress)) {
    info.implicitOpacity = 1.0;
    info.implicitProgress = info.progress;
    info.implicitCore = true;
  }
  if (meshOpacity > 0.0f) {
    if (shared && settings.gpuTransitions) {
      addGpuTransition(frame, shared, expand, timeSec, meshU, settings, meshOpacity);
    } else {
      MorphFrame t = evaluateMorphTransition(rt, timeSec, expand, meshU, settings);
      addMeshDraw(frame, t.actorId, t.mesh, meshOpacity, false);
    }
  }
  if (info.implicitCore && implicitStage) {
    MorphFrame core;
    core.timeSec = timeSec;
    core.stage = info.stage;
    core.progress = info.progress;
    if (Status st = appendStandinCore(rt, core, settings); !st) {
      info.error = st.error();
      return info;
    }
    addMeshDraw(frame, expand ? dst : src, core.mesh, 1.0f, false);
  } else if (implicitOpacity > 0.0 && implicitStage) {
    auto out = evaluateMorphImplicit(rt, timeSec, implicitU, settings);
    if (!out) {
      info.error = out.error();
      return info;
    }
    addMeshDraw(frame, src, out->mesh, float(implicitOpacity), true);
  }
  return info;
}

}  // namespace

MorphSceneInfo applyMorph(SceneFrame& frame, const MorphRuntime& rt, double timeSec,
                          const MorphFrameSettings& settings, bool implicitStage) {
  return apply(frame, rt, nullptr, timeSec, settings, implicitStage);
}

MorphSceneInfo applyMorph(SceneFrame& frame, const std::shared_ptr<const MorphRuntime>& rt, double timeSec,
                          const MorphFrameSettings& settings, bool implicitStage) {
  return apply(frame, *rt, rt, timeSec, settings, implicitStage);
}

std::string describeMorphStage(const MorphSceneInfo& info) {
  std::string s = morphStageName(info.stage);
  if (info.stage == MorphStage::Collapse || info.stage == MorphStage::Morph || info.stage == MorphStage::Expand)
    s += " " + std::to_string(static_cast<int>(std::lround(100.0 * info.progress))) + "%";
  if (!info.error.empty()) s += " (error: " + info.error + ")";
  return s;
}

std::shared_ptr<const MorphRuntime> MorphCache::get(const Project& project, const std::string& baseDir,
                                                    AssetCache& assets, const void* owner, uint64_t revision) {
  if (!project.morph.enabled()) {
    runtime_.reset();
    error_.clear();
    owner_ = nullptr;
    return nullptr;
  }
  if (owner == owner_ && revision == revision_ && (runtime_ || !error_.empty())) return runtime_;
  owner_ = owner;
  revision_ = revision;
  auto r = prepareMorph(project, baseDir, assets, runtime_.get());
  if (r) {
    runtime_ = *r;
    error_.clear();
  } else {
    runtime_.reset();
    error_ = r.error();
  }
  return runtime_;
}

}  // namespace animorph
