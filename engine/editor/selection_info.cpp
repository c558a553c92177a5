#include "editor/selection_info.h"

#include <algorithm>
#include <cmath>

#include "core/blobtree/compile.h"
#include "core/blobtree/tree_edit.h"
#include "core/project/animation_end_cache.h"
#include "core/rig/pose.h"
#include "core/scene/scene_frame.h"
#include "core/rig/skinning.h"

namespace animorph {

const Character* actorCharacter(const Document& doc, AssetCache& assets, const Actor& actor) {
  if (actor.assetPath.empty()) return nullptr;
  const AssetCache::Entry& e = assets.get(doc.resolveAsset(actor.assetPath));
  return e.character.get();
}

std::vector<int> selectionKeyFrames(const Document& doc, AssetCache& assets) {
  std::vector<int> frames;
  const Project& p = doc.project();
  const Actor* actor = p.findActor(doc.selection.actorId);
  if (!actor) return frames;
  if (actor->kind == ActorKind::BlobTree) {
    const Timeline& tl = p.timeline;
    if (actor->speed == 0.0 || !(tl.fps > 0.0)) return frames;
    std::vector<double> keys = animatedKeyTimes(actor->blobTree, doc.selection.node);
    double end = cachedAnimationEndSec(actor->blobTree, &doc, doc.revision());
    double cycleSec = end / std::abs(actor->speed);
    double startSec = tl.frameStart / tl.fps, endSec = (tl.frameEnd + 1) / tl.fps;
    long first = 0, last = 0;
    if (actor->loop && cycleSec > 1e-6) {
      first = static_cast<long>(std::floor((startSec - actor->timeOffsetSec) / cycleSec)) - 1;
      last = std::min(first + 10000, static_cast<long>(std::ceil((endSec - actor->timeOffsetSec) / cycleSec)) + 1);
    }
    for (long k = first; k <= last; ++k)
      for (double kt : keys) {
        double local = actor->speed > 0.0 ? kt / actor->speed : (end - kt) / -actor->speed;
        double t = actor->timeOffsetSec + k * cycleSec + local;
        if (t < startSec - 1e-9 || t >= endSec) continue;
        frames.push_back(static_cast<int>(std::lround(t * tl.fps)));
      }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    while (!frames.empty() && frames.back() > tl.frameEnd) frames.pop_back();
    return frames;
  }
  const Character* c = actorCharacter(doc, assets, *actor);
  if (!c || actor->clip < 0 || actor->clip >= static_cast<int>(c->clips.size())) return frames;
  const AnimationClip& clip = c->clips[actor->clip];
  const Timeline& tl = p.timeline;
  if (actor->speed == 0.0 || !(tl.fps > 0.0)) return frames;
  double startSec = tl.frameStart / tl.fps, endSec = (tl.frameEnd + 1) / tl.fps;

  std::vector<float> keyTimes;
  for (const Channel& ch : clip.channels) {
    if (doc.selection.node >= 0 && ch.node != doc.selection.node) continue;
    keyTimes.insert(keyTimes.end(), ch.timesSec.begin(), ch.timesSec.end());
  }
  std::sort(keyTimes.begin(), keyTimes.end());
  keyTimes.erase(std::unique(keyTimes.begin(), keyTimes.end()), keyTimes.end());

  double absSpeed = std::abs(actor->speed);
  double cycleSec = clip.durationSec / absSpeed;  // timeline seconds per clip cycle
  // Cycles that overlap the range; a single pass when not looping.
  long firstCycle = 0, lastCycle = 0;
  if (actor->loop && cycleSec > 1e-6) {
    firstCycle = static_cast<long>(std::floor((startSec - actor->timeOffsetSec) / cycleSec)) - 1;
    lastCycle = static_cast<long>(std::ceil((endSec - actor->timeOffsetSec) / cycleSec)) + 1;
    if (lastCycle - firstCycle > 10000) lastCycle = firstCycle + 10000;  // absurd zoom-out: cap the work
  }
  for (long k = firstCycle; k <= lastCycle; ++k) {
    for (float kt : keyTimes) {
      // Playing backwards, clip time d maps to the mirrored timeline time.
      double local = actor->speed > 0.0 ? kt / absSpeed
                   : actor->loop  ? (clip.durationSec - kt) / absSpeed
                                  : -kt / absSpeed;
      double t = actor->timeOffsetSec + k * cycleSec + local;
      if (t < startSec - 1e-9 || t >= endSec) continue;
      frames.push_back(static_cast<int>(std::lround(t * tl.fps)));
    }
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  while (!frames.empty() && frames.back() > tl.frameEnd) frames.pop_back();
  return frames;
}

Bounds selectionBounds(const Document& doc, AssetCache& assets, double timeSec) {
  Bounds out;
  const Project& p = doc.project();
  for (const Actor& actor : p.actors) {
    bool selected = actor.id == doc.selection.actorId;
    if (!doc.selection.actorId.empty() ? !selected : !actor.visible) continue;
    if (actor.kind == ActorKind::BlobTree) {
      AnimationEndScope ends(p, &doc, doc.revision());
      double t = blobActorTimeSec(actor, timeSec);
      glm::mat4 world = actor.transform.matrix();
      int node = selected ? doc.selection.node : -1;
      Bounds local;
      if (node >= 0) {
        // The node's skeleton drawing, with a margin for the surface around it.
        BlobGuides g = blobGuides(actor.blobTree, t, world);
        Bounds nb;
        for (const auto& l : g.lines)
          if (l.node == node) { nb.add(l.a); nb.add(l.b); }
        for (const auto& m : g.markers)
          if (m.node == node) nb.add(m.position);
        for (const auto& a : g.axes)
          if (a.node == node) { nb.add(a.origin); for (const auto& tip : a.tips) nb.add(tip); }
        if (!nb.empty()) {
          float margin = std::max(0.15f, 0.25f * nb.diagonal());
          out.add(nb.min - glm::vec3(margin));
          out.add(nb.max + glm::vec3(margin));
          continue;
        }
      }
      FieldProgram prog = compileFieldProgram(actor.blobTree, t);
      if (prog.unbounded()) continue;
      local = prog.tightBounds(3);
      if (local.empty()) continue;
      for (int corner = 0; corner < 8; ++corner) {
        glm::vec3 p((corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                    (corner & 4) ? local.max.z : local.min.z);
        out.add(glm::vec3(world * glm::vec4(p, 1.0f)));
      }
      continue;
    }
    const Character* c = actorCharacter(doc, assets, actor);
    if (!c) continue;
    const AnimationClip* clip =
        actor.clip >= 0 && actor.clip < static_cast<int>(c->clips.size()) ? &c->clips[actor.clip] : nullptr;
    float t = clip ? float(actorClipTimeSec(actor, *clip, timeSec)) : 0.0f;
    glm::mat4 world = actor.transform.matrix();
    int node = selected ? doc.selection.node : -1;
    if (node >= 0 && node < static_cast<int>(c->nodes.size())) {
      std::vector<glm::mat4> globals = poseGlobals(*c, clip, t);
      glm::vec3 pos = glm::vec3(world * globals[node] * glm::vec4(0, 0, 0, 1));
      // A joint has no extent of its own: frame it with a margin of a tenth
      // of the character's size (at least 10 cm).
      Bounds all;
      for (const Mesh& m : c->meshes) all.add(m.bounds());
      float margin = std::max(0.1f, 0.1f * all.diagonal());
      out.add(pos - glm::vec3(margin));
      out.add(pos + glm::vec3(margin));
      continue;
    }
    for (const glm::vec3& v : skinnedWorldPositions(*c, clip, t)) out.add(glm::vec3(world * glm::vec4(v, 1.0f)));
  }
  return out;
}

}  // namespace animorph
