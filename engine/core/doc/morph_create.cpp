#include "core/doc/morph_create.h"

#include <algorithm>
#include <filesystem>

#include "core/doc/chain_pair_commands.h"
#include "core/standin/fit_standin.h"

namespace animorph {

MorphMarkers collapseTreeMarkers(const Project& p, const MorphChoice& c) {
  MorphMarkers k = c.markers;
  const Actor* s = p.findActor(c.sourceActorId);
  const Actor* t = p.findActor(c.targetActorId);
  if (s && s->kind == ActorKind::BlobTree) k.a = k.b;
  if (t && t->kind == ActorKind::BlobTree) k.d = k.c;
  return k;
}

Result<MorphSetup> proposeMorph(const Project& p, const std::string& baseDir, AssetCache& assets,
                                const MorphChoice& c, std::vector<std::string>* messages) {
  namespace fs = std::filesystem;
  MorphSetup m = p.morph;
  for (const auto& [role, id] : {std::pair{"source", &c.sourceActorId}, std::pair{"target", &c.targetActorId}})
    if (!p.findActor(*id)) return Error{std::string("morph.") + role + ": no actor with id '" + *id + "'"};
  if (c.sourceActorId == c.targetActorId)
    return Error{"morph: the source and the target are the same actor ('" + c.sourceActorId + "')"};
  const MorphMarkers k = collapseTreeMarkers(p, c);
  if (!(k.a <= k.b && k.b <= k.c && k.c <= k.d))
    return Error{"morph.markers: A <= B <= C <= D is needed (got " + std::to_string(k.a) + ", " +
                 std::to_string(k.b) + ", " + std::to_string(k.c) + ", " + std::to_string(k.d) + ")"};
  // Chain pairs name the two rigs' joints: kept for the same sides, reversed for swapped ones.
  if (c.sourceActorId == m.targetActorId && c.targetActorId == m.sourceActorId) m.chainPairs = swappedChainPairs(m.chainPairs);
  else if (c.sourceActorId != m.sourceActorId || c.targetActorId != m.targetActorId) m.chainPairs.clear();
  m.sourceActorId = c.sourceActorId;
  m.targetActorId = c.targetActorId;
  m.method = c.method;
  m.markers = k;
  // Per-actor data of actors that no longer take part goes; a glTF side keeps its own.
  std::erase_if(m.actors, [&](const ActorMorph& a) { return a.actorId != c.sourceActorId && a.actorId != c.targetActorId; });
  for (const std::string* id : {&c.sourceActorId, &c.targetActorId}) {
    const Actor& a = *p.findActor(*id);
    ActorMorph* am = m.findActor(*id);
    if (a.kind == ActorKind::BlobTree) {
      if (am) std::erase_if(m.actors, [&](const ActorMorph& x) { return x.actorId == *id; });
      continue;
    }
    if (am && !am->standin.segments.empty()) continue;
    const fs::path path(a.assetPath);
    const std::string abs = (path.is_absolute() ? path : fs::path(baseDir) / path).lexically_normal().string();
    const AssetCache::Entry& e = assets.get(abs);
    if (!e.character) return Error{"actor '" + *id + "' (" + a.assetPath + "): " + e.error};
    auto fit = fitStandin(*e.character);
    if (!fit) return Error{"actor '" + *id + "' (" + a.assetPath + "): " + fit.error()};
    if (!am) {
      m.actors.push_back(ActorMorph{});
      am = &m.actors.back();
      am->actorId = *id;
    }
    am->standin = fit->standin;
    am->segmentTracks.clear();
    if (messages)
      messages->push_back("actor '" + *id + "': stand-in of " + std::to_string(fit->report.segments) + " segments fitted");
  }
  return m;
}

std::optional<ActorAlignment> proposeTargetAlignment(const Project& p, const std::string& baseDir, AssetCache& assets,
                                                     const std::string& sourceId, const std::string& targetId) {
  namespace fs = std::filesystem;
  const Actor* s = p.findActor(sourceId);
  const Actor* t = p.findActor(targetId);
  if (!s || !t || s == t || s->kind != ActorKind::Gltf || t->kind != ActorKind::Gltf) return std::nullopt;
  auto load = [&](const Actor& a) {
    const fs::path path(a.assetPath);
    return assets.get((path.is_absolute() ? path : fs::path(baseDir) / path).lexically_normal().string()).character;
  };
  const auto sc = load(*s), tc = load(*t);
  if (!sc || !tc) return std::nullopt;
  ActorAlignment out;
  out.alignment = alignTargetToSource(*sc, *tc);
  // In the source actor's frame: the target goes where the source actor's transform puts the source.
  out.targetTransform = decompose(s->transform.matrix() * out.alignment.transform.matrix());
  return out;
}

std::unique_ptr<Command> createMorphCommand(const Project& p, MorphSetup after, const std::optional<Transform>& targetTransform,
                                            std::string label) {
  if (!targetTransform) return setMorphCommand(p, std::move(after), std::move(label));
  const std::string targetId = after.targetActorId;
  const Actor* t = p.findActor(targetId);
  const Transform before = t ? t->transform : Transform{};
  const MorphSetup morphBefore = p.morph;
  const Transform placed = *targetTransform;
  return std::make_unique<LambdaCommand>(
      std::move(label),
      [after, targetId, placed](Project& q) {
        q.morph = after;
        if (Actor* a = q.findActor(targetId)) a->transform = placed;
      },
      [morphBefore, targetId, before](Project& q) {
        q.morph = morphBefore;
        if (Actor* a = q.findActor(targetId)) a->transform = before;
      });
}

std::unique_ptr<Command> setMorphCommand(const Project& p, MorphSetup after, std::string label) {
  return std::make_unique<SetValueCommand<MorphSetup>>(
      std::move(label), [](Project& q) { return &q.morph; }, p.morph, std::move(after));
}

std::unique_ptr<Command> swapMorphSidesCommand(const Project& p) {
  MorphSetup m = p.morph;
  std::swap(m.sourceActorId, m.targetActorId);
  m.chainPairs = swappedChainPairs(m.chainPairs);
  const MorphMarkers k = m.markers;
  // Mirrored inside [A, D]: the target's expansion becomes the new source's collapse.
  m.markers = {k.a, k.a + (k.d - k.c), k.d - (k.b - k.a), k.d};
  return setMorphCommand(p, std::move(m), "Swap morph source and target");
}

}  // namespace animorph
