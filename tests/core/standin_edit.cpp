#include <catch2/catch.hpp>

#include "core/doc/document.h"
#include "core/project/project_io.h"
#include "core/doc/standin_commands.h"
#include "core/rig/pose.h"
#include "core/scene/scene_frame.h"
#include "core/scene/standin_guides.h"
#include "editor/standin_pick.h"
#include "core/standin/character_pose.h"
#include "core/standin/standin_edit.h"
#include "util/morph_fixtures.h"

using namespace animorph;

namespace {

float distToSegment(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
  glm::vec3 ab = b - a;
  float t = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
  return glm::length(p - (a + t * ab));
}

// The demo morph project with a transform on the source actor and keyed
// segment tracks on segments 1, 2 and 3 of the source's stand-in.
Project editProject() {
  Project p = test::demoMorph().project;
  Actor* src = p.findActor(p.morph.sourceActorId);
  src->transform.translation = {0.3f, 0.1f, -0.2f};
  src->transform.scale = glm::vec3(1.5f);
  ActorMorph* am = p.morph.findActor(p.morph.sourceActorId);
  am->segmentTracks.clear();
  for (int s : {1, 2, 3}) {
    SegmentTracks t;
    t.segment = s;
    t.radiusScale.setKey(0.5, 0.25f * float(s), KeyInterp::Linear);
    am->segmentTracks.push_back(t);
  }
  return p;
}

const Character& sourceCharacter() { return test::demoCreature(); }

}  // namespace

TEST_CASE("standin guides: segments posed where the morph poses them, at the scene time", "[standin_edit]") {
  const Project p = editProject();
  const Actor& actor = *p.findActor(p.morph.sourceActorId);
  const Standin& s = p.morph.findActor(actor.id)->standin;
  const Character& c = sourceCharacter();
  REQUIRE(!c.clips.empty());
  const double t = 0.37;
  StandinGuides g = standinGuides(actor, c, s, t);
  REQUIRE(g.segments.size() == s.segments.size());
  const auto& clip = c.clips[size_t(actor.clip)];
  const auto globals = poseGlobals(c, &clip, float(actorClipTimeSec(actor, clip, t)));
  const auto posed = poseStandin(s, globals, actor.transform.matrix());
  for (size_t i = 0; i < posed.size(); ++i) {
    CHECK(glm::length(g.segments[i].a - posed[i].a) < 1e-5f);
    CHECK(glm::length(g.segments[i].b - posed[i].b) < 1e-5f);
    CHECK(g.segments[i].radius == Approx(posed[i].radius));
    CHECK(g.segments[i].radius == Approx(s.segments[i].radius * 1.5f).epsilon(1e-3));
    // The stored ends come back from the world.
    CHECK(glm::length(standinWorldToNode(g.segments[i], g.segments[i].a) - s.segments[i].a) < 1e-4f);
  }
  // Another time moves the walking creature's segments.
  StandinGuides later = standinGuides(actor, c, s, t + 0.3);
  float moved = 0.0f;
  for (size_t i = 0; i < posed.size(); ++i) moved = std::max(moved, glm::length(later.segments[i].a - g.segments[i].a));
  CHECK(moved > 1e-3f);
}

TEST_CASE("standin guides: the wire capsule lies on the capsule's surface", "[standin_edit]") {
  StandinGuideSegment s;
  s.index = 3;
  s.a = {0.1f, 0.2f, 0.3f};
  s.b = {0.4f, 0.9f, -0.1f};
  s.radius = 0.07f;
  auto lines = standinCapsuleLines(s, 16);
  // The axis, two rings of 16, four sides, four half circles of 8.
  REQUIRE(lines.size() == 1 + 32 + 4 + 32);
  CHECK(glm::length(lines[0].a - s.a) < 1e-6f);
  for (size_t i = 1; i < lines.size(); ++i) {
    CHECK(lines[i].segment == 3);
    CHECK(distToSegment(lines[i].a, s.a, s.b) == Approx(s.radius).margin(1e-5));
    CHECK(distToSegment(lines[i].b, s.a, s.b) == Approx(s.radius).margin(1e-5));
  }
}

TEST_CASE("standin guides: the morph actors on screen at the time, the selected one always, hidden ones skipped",
          "[standin_edit]") {
  const auto& dm = test::demoMorph();
  Project p = dm.project;
  AssetCache assets;
  const MorphMarkers mk = p.morph.markers;
  const double during = p.timeline.frameToSec((mk.b + mk.c) / 2.0);  // the implicit morph: both stand-ins
  auto all = projectStandinGuides(p, dm.dir, assets, during);
  REQUIRE(all.size() == 2);
  CHECK(all[0].segments.size() == p.morph.actors[0].standin.segments.size());
  const double before = p.timeline.frameToSec(mk.a - 1), after = p.timeline.frameToSec(mk.d + 1);
  auto early = projectStandinGuides(p, dm.dir, assets, before);
  REQUIRE(early.size() == 1);
  CHECK(early[0].actorId == p.morph.sourceActorId);
  auto late = projectStandinGuides(p, dm.dir, assets, after);
  REQUIRE(late.size() == 1);
  CHECK(late[0].actorId == p.morph.targetActorId);
  CHECK(projectStandinGuides(p, dm.dir, assets, before, p.morph.targetActorId).size() == 2);  // selected: shown
  p.findActor(p.morph.targetActorId)->visible = false;
  auto some = projectStandinGuides(p, dm.dir, assets, during, p.morph.targetActorId);
  REQUIRE(some.size() == 1);
  CHECK(some[0].actorId == p.morph.sourceActorId);
  p.morph.sourceActorId.clear();
  CHECK(projectStandinGuides(p, dm.dir, assets, during).empty());
}

TEST_CASE("standin pick: rays against capsules, sides and caps", "[standin_edit]") {
  const glm::vec3 a{0, 0, 0}, b{0, 0, 2};
  // Side: from x = 5 towards -x at z = 1 enters at x = 0.5.
  auto t = rayCapsule({{5, 0, 1}, {-1, 0, 0}}, a, b, 0.5f);
  REQUIRE(t);
  CHECK(*t == Approx(4.5f));
  // Along the axis: the cap at z = 2 + r.
  t = rayCapsule({{0, 0, 10}, {0, 0, -1}}, a, b, 0.5f);
  REQUIRE(t);
  CHECK(*t == Approx(7.5f));
  // Past the end, the spherical cap: ray at z = 2.3 enters the sphere of b.
  t = rayCapsule({{5, 0, 2.3f}, {-1, 0, 0}}, a, b, 0.5f);
  REQUIRE(t);
  CHECK(*t == Approx(5.0f - std::sqrt(0.25f - 0.09f)).epsilon(1e-4));
  CHECK_FALSE(rayCapsule({{5, 0, 2.6f}, {-1, 0, 0}}, a, b, 0.5f));
  CHECK_FALSE(rayCapsule({{5, 0.6f, 1}, {-1, 0, 0}}, a, b, 0.5f));
  CHECK_FALSE(rayCapsule({{5, 0, 1}, {1, 0, 0}}, a, b, 0.5f));  // behind

  OrbitCamera cam;
  cam.target = {0, 0, 0};
  cam.distanceM = 4.0f;
  const glm::vec2 vp{800, 600};
  StandinGuides g;
  g.actorId = "x";
  StandinGuideSegment near_, far_;
  near_.index = 0;
  near_.a = {-0.5f, 0, 0};
  near_.b = {0.5f, 0, 0};
  near_.radius = 0.1f;
  far_ = near_;
  far_.index = 1;
  far_.a -= cam.forward() * 1.0f;  // behind the first, seen from the camera
  far_.b -= cam.forward() * 1.0f;
  far_.a += cam.forward() * 2.0f;
  far_.b += cam.forward() * 2.0f;
  g.segments = {far_, near_};
  glm::vec2 centre = glm::vec2(cam.worldToPixel({0, 0, 0}, vp));
  auto pick = pickStandinSegment({g}, cam, vp, centre);
  REQUIRE(pick);
  CHECK(pick->actorId == "x");
  CHECK(pick->segment == 0);  // the nearer one along the ray
  CHECK_FALSE(pickStandinSegment({g}, cam, vp, centre + glm::vec2(0, 200)));
  // A capsule too thin to hit is still picked near its axis line.
  g.segments = {near_};
  g.segments[0].radius = 1e-5f;
  auto thin = pickStandinSegment({g}, cam, vp, centre + glm::vec2(0, 4));
  REQUIRE(thin);
  CHECK(thin->segment == 0);
}

TEST_CASE("standin commands: a segment edit undoes exactly, a drag is one step", "[standin_edit]") {
  Document doc;
  doc.reset(editProject(), "");
  const Project before = doc.project();
  const std::string id = before.morph.sourceActorId;
  StandinSegment s = before.morph.findActor(id)->standin.segments[2];
  for (int step = 1; step <= 5; ++step) {
    if (step == 1) doc.beginDrag();
    StandinSegment next = s;
    next.radius = s.radius * (1.0f + 0.1f * float(step));
    next.a += glm::vec3(0.01f * float(step), 0, 0);
    auto cmd = setStandinSegmentCommand(doc.project(), id, 2, next, "Stand-in radius", "standin/radius");
    REQUIRE(cmd);
    doc.execute(std::move(*cmd));
  }
  doc.endDrag();
  CHECK(doc.history().size() == 1);
  CHECK(doc.project().morph.findActor(id)->standin.segments[2].radius == Approx(s.radius * 1.5f));
  CHECK(doc.project().morph.findActor(id)->standin.segments[3] == before.morph.findActor(id)->standin.segments[3]);
  REQUIRE(doc.undo());
  CHECK(doc.project() == before);
  REQUIRE(doc.redo());
  CHECK(doc.project().morph.findActor(id)->standin.segments[2].radius == Approx(s.radius * 1.5f));

  // Refused edits name the reason and build nothing.
  StandinSegment bad = s;
  bad.radius = 0.0f;
  auto r = setStandinSegmentCommand(doc.project(), id, 2, bad, "x");
  REQUIRE_FALSE(r);
  CHECK(r.error().find("radius") != std::string::npos);
  auto out = setStandinSegmentCommand(doc.project(), id, 999, s, "x");
  REQUIRE_FALSE(out);
  CHECK(out.error().find("999") != std::string::npos);
  CHECK_FALSE(setStandinSegmentCommand(doc.project(), "nobody", 0, s, "x"));
}

TEST_CASE("standin commands: adding and deleting segments keeps segment tracks on their segments", "[standin_edit]") {
  Document doc;
  doc.reset(editProject(), "");
  const Project before = doc.project();
  const std::string id = before.morph.sourceActorId;
  const ActorMorph& am0 = *before.morph.findActor(id);
  const size_t n = am0.standin.segments.size();
  auto trackOf = [&](int segment) -> const SegmentTracks* {
    for (const auto& t : doc.project().morph.findActor(id)->segmentTracks)
      if (t.segment == segment) return &t;
    return nullptr;
  };
  // Tracks are told apart by their radius key (0.25 * original index).
  auto keyOf = [](const SegmentTracks* t) { return t ? t->radiusScale.evaluate(0.5) : -1.0f; };

  SECTION("delete drops the deleted segment's tracks and renumbers the later ones") {
    auto cmd = deleteStandinSegmentCommand(doc.project(), id, 2);
    REQUIRE(cmd);
    doc.execute(std::move(*cmd));
    const ActorMorph& am = *doc.project().morph.findActor(id);
    CHECK(am.standin.segments.size() == n - 1);
    CHECK(am.standin.segments[2] == am0.standin.segments[3]);
    CHECK(am.segmentTracks.size() == 2);
    CHECK(keyOf(trackOf(1)) == Approx(0.25f));
    CHECK(keyOf(trackOf(2)) == Approx(0.75f));  // was segment 3
    CHECK(trackOf(3) == nullptr);
    REQUIRE(doc.undo());
    CHECK(doc.project() == before);
  }
  SECTION("insert (duplicate) shifts the tracks of later segments") {
    auto cmd = insertStandinSegmentCommand(doc.project(), id, 2, am0.standin.segments[1], "Duplicate");
    REQUIRE(cmd);
    doc.execute(std::move(*cmd));
    const ActorMorph& am = *doc.project().morph.findActor(id);
    CHECK(am.standin.segments.size() == n + 1);
    CHECK(am.standin.segments[2] == am0.standin.segments[1]);
    CHECK(am.standin.segments[3] == am0.standin.segments[2]);
    CHECK(keyOf(trackOf(1)) == Approx(0.25f));
    CHECK(trackOf(2) == nullptr);  // the copy has none
    CHECK(keyOf(trackOf(3)) == Approx(0.5f));
    CHECK(keyOf(trackOf(4)) == Approx(0.75f));
    REQUIRE(doc.undo());
    CHECK(doc.project() == before);
  }
  SECTION("out of range") {
    CHECK_FALSE(deleteStandinSegmentCommand(doc.project(), id, int(n)));
    CHECK_FALSE(deleteStandinSegmentCommand(doc.project(), id, -1));
  }
}

TEST_CASE("standin edit: rebinding keeps the segment in place, refit restores the fit", "[standin_edit]") {
  const Character& c = sourceCharacter();
  const Project p = editProject();
  const std::string id = p.morph.sourceActorId;
  const Standin& s = p.morph.findActor(id)->standin;
  REQUIRE(s.segments.size() >= 3);
  const auto& clip = c.clips[0];
  const auto globals = poseGlobals(c, &clip, 0.4f);
  const StandinSegment& seg = s.segments[2];
  int other = -1;
  for (const auto& x : s.segments)
    if (x.node != seg.node) other = x.node;
  REQUIRE(other >= 0);
  StandinSegment re = rebindSegment(seg, other, globals);
  CHECK(re.node == other);
  auto world = [&](const StandinSegment& x, const glm::vec3& v) {
    return glm::vec3(globals[size_t(x.node)] * glm::vec4(v, 1.0f));
  };
  CHECK(glm::length(world(re, re.a) - world(seg, seg.a)) < 1e-4f);
  CHECK(glm::length(world(re, re.b) - world(seg, seg.b)) < 1e-4f);
  CHECK(glm::length(re.a - seg.a) > 1e-4f);  // the stored ends did change space
  CHECK(re.radius == Approx(seg.radius).epsilon(1e-3));

  // Refit one segment: a moved, re-radiused segment returns to the automatic fit.
  FitSettings fs;
  fs.kind = s.kind;
  auto fitted = fitStandin(c, fs);
  REQUIRE(fitted);
  StandinSegment edited = fitted->standin.segments[2];
  edited.radius *= 3.0f;
  edited.b += glm::vec3(0.02f, 0, 0);
  auto back = refitSegment(c, edited, fs);
  REQUIRE(back);
  CHECK(*back == fitted->standin.segments[2]);
  StandinSegment nowhere = edited;
  nowhere.node = 9999;
  auto err = refitSegment(c, nowhere, fs);
  REQUIRE_FALSE(err);
  CHECK(err.error().find("9999") != std::string::npos);

  // Refit everything: tracks stay on the segment of the same node, undo restores.
  Document doc;
  doc.reset(p, "");
  Standin changed = fitted->standin;
  changed.segments.erase(changed.segments.begin() + 1);  // segment 1's node loses its segment
  auto cmd = replaceStandinCommand(doc.project(), id, changed, "Refit stand-in");
  REQUIRE(cmd);
  doc.execute(std::move(*cmd));
  const ActorMorph& am = *doc.project().morph.findActor(id);
  CHECK(am.standin == changed);
  for (const auto& t : am.segmentTracks) {
    REQUIRE(t.segment < int(changed.segments.size()));
    // Track k was on old segment k (radius key 0.25 k); it now sits on that segment's node.
    const int oldIndex = int(std::lround(t.radiusScale.evaluate(0.5) / 0.25f));
    CHECK(changed.segments[size_t(t.segment)].node == s.segments[size_t(oldIndex)].node);
  }
  REQUIRE(doc.undo());
  CHECK(doc.project() == p);
}

TEST_CASE("standin edits and the Stand-ins view switch are saved in the project", "[standin_edit]") {
  Document doc;
  doc.reset(editProject(), "");
  const std::string id = doc.project().morph.sourceActorId;
  StandinSegment s = doc.project().morph.findActor(id)->standin.segments[4];
  s.radius *= 2.0f;
  s.b += glm::vec3(0.0f, 0.03f, 0.0f);
  auto cmd = setStandinSegmentCommand(doc.project(), id, 4, s, "edit");
  REQUIRE(cmd);
  doc.execute(std::move(*cmd));
  auto del = deleteStandinSegmentCommand(doc.project(), id, 1);
  REQUIRE(del);
  doc.execute(std::move(*del));
  Project p = doc.project();
  p.view.showStandins = true;
  auto back = projectFromJson(projectToJson(p), "edited.animorph");
  REQUIRE(back);
  CHECK(back->view.showStandins);
  CHECK(back->morph == p.morph);
  CHECK(back->morph.findActor(id)->standin.segments[3] == s);  // renumbered after the delete
  p.view.showStandins = false;
  auto off = projectFromJson(projectToJson(p), "edited.animorph");
  REQUIRE(off);
  CHECK_FALSE(off->view.showStandins);
}
