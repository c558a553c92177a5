// FBX, Collada and OBJ import (io/assimp_import.h) and the importer dispatch
// (io/character_import.h), on files made by real exporters: Debian's assimp-testmodels and
// the test characters Blender writes (tests/tools/make_test_characters.py).
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "core/io/assimp_import.h"
#include "core/io/character_import.h"
#include "core/io/collada_morphs.h"
#include "core/io/declared_size_check.h"
#include "core/io/fbx_shape_values.h"
#include "core/rig/skinning.h"
#include "util/bounded_run.h"
#include "util/temp_dir.h"
#include "util/test_characters.h"
#include "util/test_skip.h"

using namespace animorph;
using animorph::test::BoundedRun;
using animorph::test::runBounded;
using animorph::test::TempDir;

namespace {

namespace fs = std::filesystem;
const std::string kModels = "/usr/share/assimp/models/";

std::string outcome(const Result<Character>& r) { return r.ok() ? std::string("ok") : r.error(); }

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

bool haveAssimpCommand() { return std::system("command -v assimp > /dev/null 2>&1") == 0; }

// Largest distance from a point of `from` to its nearest point of `to` (a grid of cells of
// `cell` side: points farther than one cell count as the brute-force distance).
double oneSidedDistance(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to, float cell) {
  auto key = [&](const glm::vec3& p) {
    const glm::ivec3 c = glm::ivec3(glm::floor(p / cell));
    return (int64_t(c.x) * 73856093) ^ (int64_t(c.y) * 19349663) ^ (int64_t(c.z) * 83492791);
  };
  std::unordered_multimap<int64_t, size_t> grid;
  for (size_t i = 0; i < to.size(); ++i) grid.emplace(key(to[i]), i);
  double worst = 0.0;
  for (const glm::vec3& p : from) {
    double best = 1e30;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto range = grid.equal_range(key(p + cell * glm::vec3(dx, dy, dz)));
          for (auto it = range.first; it != range.second; ++it) best = std::min(best, double(glm::distance(p, to[it->second])));
        }
    if (best > cell)
      for (const glm::vec3& q : to) best = std::min(best, double(glm::distance(p, q)));
    worst = std::max(worst, best);
  }
  return worst;
}

double setDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, float cell) {
  return std::max(oneSidedDistance(a, b, cell), oneSidedDistance(b, a, cell));
}

Bounds boundsOf(const std::vector<glm::vec3>& points) {
  Bounds b;
  for (const auto& p : points) b.add(p);
  return b;
}

std::vector<glm::vec3> scaled(std::vector<glm::vec3> points, float k) {
  for (auto& p : points) p *= k;
  return points;
}

// The first key time over a clip's channels (Blender's glTF clips start at frame 1's time).
float firstKey(const AnimationClip& clip) {
  float t = 1e30f;
  for (const Channel& ch : clip.channels) t = std::min(t, ch.timesSec.front());
  return clip.channels.empty() ? 0.0f : t;
}

// Blender's glTF exporter keeps the 4 strongest influences of a vertex (renormalised); the
// FBX keeps them all. To compare the two files, the FBX side is reduced the same way.
size_t keepFourInfluences(Character& c) {
  size_t reduced = 0;
  for (Mesh& m : c.meshes) {
    if (m.weights1.empty()) continue;
    for (size_t v = 0; v < m.weights0.size(); ++v) {
      if (m.weights1[v].x > 0.0f) ++reduced;
      const glm::vec4& w = m.weights0[v];
      m.weights0[v] = w / (w.x + w.y + w.z + w.w);
    }
    m.joints1.clear();
    m.weights1.clear();
  }
  return reduced;
}

}  // namespace

TEST_CASE("assimp import: skinned, animated FBX and Collada files of assimp-testmodels import with joints and clips",
          "[assimp]") {
  if (!fs::exists(kModels + "FBX/huesitos.fbx")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  for (const std::string rel : {"FBX/huesitos.fbx", "FBX/animation_with_skeleton.fbx", "Collada/box_nested_animation.dae"}) {
    INFO(rel);
    auto c = importCharacter(kModels + rel);
    REQUIRE(c.ok());
    CHECK(c->format == (rel.rfind(".fbx") != std::string::npos ? "FBX" : "Collada"));
    CHECK(c->totalJoints() > 0);
    REQUIRE(!c->clips.empty());
    const AnimationClip& clip = c->clips[0];
    CHECK(clip.durationSec > 0.0f);
    for (const Channel& ch : clip.channels) {
      REQUIRE(ch.node >= 0);
      REQUIRE(ch.node < int(c->nodes.size()));
      CHECK(ch.timesSec.size() == ch.values.size());
    }
    for (const Mesh& m : c->meshes) {
      CHECK(m.material >= 0);
      CHECK(m.material < int(c->materials.size()));
      for (size_t v = 0; v < m.vertexCount(); ++v) {
        float sum = glm::dot(m.weights0[v], glm::vec4(1.0f));
        if (!m.weights1.empty()) sum += glm::dot(m.weights1[v], glm::vec4(1.0f));
        REQUIRE(std::abs(sum - 1.0f) < 1e-4f);
      }
    }
    // The clip moves the mesh: its middle differs from its start by a visible part of the size.
    const auto start = skinnedWorldPositions(*c, &clip, 0.0f);
    const auto middle = skinnedWorldPositions(*c, &clip, 0.5f * clip.durationSec);
    REQUIRE(start.size() == c->totalVertices());
    double moved = 0.0;
    for (size_t i = 0; i < start.size(); ++i) moved = std::max(moved, double(glm::distance(start[i], middle[i])));
    CHECK(moved > 0.01 * boundsOf(start).diagonal());
  }
}

TEST_CASE("assimp import: an FBX in centimetres reads its declared unit and keeps its own numbers",
          "[assimp]") {
  // huesitos.fbx (Blender 2.79, FBX) and the character Blender imports from it: same joints and
  // clip; box_nested_animation.dae: a Collada rig whose root carries the file's unit and up axis.
  if (!fs::exists(kModels + "FBX/huesitos.fbx")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  auto c = importCharacter(kModels + "FBX/huesitos.fbx");
  REQUIRE(c.ok());
  CHECK(c->unit.metresPerUnit == Approx(0.01));  // UnitScaleFactor 1: centimetres
  CHECK(c->unit.name == "centimetres");
  CHECK(c->unit.declared);
  CHECK(c->totalJoints() == 9);
  // At the first key the pose is the bind pose: skinned == rigid placement of the mesh.
  const auto skinned = skinnedWorldPositions(*c, &c->clips[0], 0.0f);
  CHECK(boundsOf(skinned).diagonal() == Approx(828.4).epsilon(0.01));
}

TEST_CASE("assimp import: static FBX, Collada and OBJ files place every vertex where assimp's own pre-transformed "
          "export does, in the file's units",
          "[assimp]") {
  if (!fs::exists(kModels + "FBX/spider.fbx")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  if (!haveAssimpCommand()) ANIMORPH_SKIP("the assimp command (assimp-utils) is not installed");
  TempDir tmp;
  // Collada: assimp's export is in metres (it scales the root by <unit meter>), ours in the file's units.
  for (const std::string rel : {"FBX/cubes_with_mirroring_and_pivot.fbx", "FBX/close_to_identity_transforms.fbx",
                                "FBX/spider.fbx", "FBX/global_settings.fbx", "Collada/duck.dae",
                                "Collada/teapot_instancenodes.DAE", "OBJ/spider.obj"}) {
    INFO(rel);
    const std::string reference = tmp.file(fs::path(rel).stem().string() + "_ptv.obj");
    const std::string cmd = "assimp export '" + kModels + rel + "' '" + reference + "' -ptv > /dev/null 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    auto ref = importCharacter(reference);
    REQUIRE(ref.ok());
    auto c = importCharacter(kModels + rel);
    REQUIRE(c.ok());
    const bool collada = rel.rfind("Collada/", 0) == 0;
    const auto ours = scaled(skinnedWorldPositions(*c, nullptr, 0.0f), collada ? float(c->unit.metresPerUnit) : 1.0f);
    const auto theirs = skinnedWorldPositions(*ref, nullptr, 0.0f);
    const float diagonal = boundsOf(theirs).diagonal();
    REQUIRE(diagonal > 0.0f);
    CHECK(setDistance(ours, theirs, 1e-3f * diagonal) < 1e-4 * diagonal);
  }
  auto duck = importCharacter(kModels + "Collada/duck.dae");
  REQUIRE(duck.ok());
  CHECK(duck->unit.name == "centimetres");
  CHECK(duck->materials.at(0).baseColorTextureUri == "duckCM.tga");
  auto obj = importCharacter(kModels + "OBJ/spider.obj");
  REQUIRE(obj.ok());
  CHECK_FALSE(obj->unit.declared);
  CHECK(obj->materials.size() == 6);
}

TEST_CASE("assimp import: malformed, truncated and oversized files are refused quickly, naming the path and reason",
          "[assimp][reliability]") {
  if (!fs::exists(kModels + "FBX/huesitos.fbx")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  TempDir tmp;
  const std::string fbx = readBytes(kModels + "FBX/huesitos.fbx");
  const std::string dae = readBytes(kModels + "Collada/box_nested_animation.dae");
  auto refused = [&](const std::string& name, const std::string& bytes, const std::string& expected) {
    const std::string path = tmp.file(name);
    writeBytes(path, bytes);
    const BoundedRun r = runBounded([&] { return outcome(importCharacter(path)); }, 20);
    INFO(name << ": " << r.output << " (" << r.seconds << " s, +" << r.peakGrowthMiB << " MiB)");
    CHECK(r.finished);
    CHECK_THAT(r.output, Catch::StartsWith(path + ": "));
    CHECK_THAT(r.output, Catch::Contains(expected));
    CHECK(r.seconds < 5.0);
    CHECK(r.peakGrowthMiB < 200);
  };
  refused("cut20.fbx", fbx.substr(0, 20), "header too short");
  for (size_t keep : {size_t(500), fbx.size() / 3, fbx.size() - 200})
    refused("cut" + std::to_string(keep) + ".fbx", fbx.substr(0, keep), "outside the file");
  refused("cut.dae", dae.substr(0, dae.size() / 2), "cannot be read as Collada");
  refused("empty.fbx", "", "cannot be read as FBX");
  refused("garbage.obj", std::string(4000, '\x07'), "cannot be read as OBJ");

  // A binary FBX array that claims 2^31 doubles in a few bytes: refused before assimp allocates.
  std::string huge = fbx;
  const size_t at = huge.find("Vertices");
  REQUIRE(at != std::string::npos);
  const size_t count = at + 8 + 1;  // the name, then the array's type 'd', then its u32 element count
  REQUIRE(huge[at + 8] == 'd');
  huge[count] = '\x00', huge[count + 1] = '\x00', huge[count + 2] = '\x00', huge[count + 3] = '\x40';
  refused("huge_array.fbx", huge, "FBX record 'Vertices'");
  // A Collada float array that declares four billion elements.
  std::string counted = dae;
  const size_t c = counted.find("count=\"");
  REQUIRE(c != std::string::npos);
  counted.insert(c + 7, "4000000000");
  refused("huge_count.dae", counted, "declares 4000000000");
  // Index lists that libassimp would read forever, appending zeros (a real number, a stray byte: a
  // fuzzed Blender file made it allocate over 1 GiB): refused before assimp reads them.
  const size_t list = dae.find("<p>");
  REQUIRE(list != std::string::npos);
  for (const auto& [name, inserted] : {std::pair<std::string, std::string>{"real_index.dae", "1.5 "},
                                       {"stray_byte.dae", "\xd7" "5 "}, {"signed_index.dae", "-1 "}}) {
    std::string bad = dae;
    bad.insert(list + 3, inserted);
    refused(name, bad, "<p> at byte " + std::to_string(list) + ": ");
    CHECK_THAT(outcome(importCharacter(tmp.file(name))), Catch::Contains("is not a digit or white space"));
  }
  // Skin weights whose count disagrees with their lists (fuzz_collada: count="4" over 8 vertices made
  // libassimp read a null pointer): refused before assimp reads them, naming the element.
  const std::string rig = readBytes(std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/collada/rig.dae");
  const size_t weights = rig.find("<vertex_weights count=\"8\">");
  REQUIRE(weights != std::string::npos);
  std::string fewer = rig;
  fewer.replace(weights, 26, "<vertex_weights count=\"4\">");
  refused("weights_count.dae", fewer,
          "<vertex_weights> at byte " + std::to_string(weights) + ": count=\"4\" but its <vcount> lists 8 numbers");
  std::string shortV = rig;
  const size_t v = shortV.find("<v>", weights);
  REQUIRE(v != std::string::npos);
  shortV.replace(v, 7, "<v>");  // the first influence's two indices gone
  refused("weights_v.dae", shortV, "adds up to 8 influences of 2 indices each, but its <v> lists 14");
  // Accessors that read past their array or hold something else than <param>s (fuzz_collada: a
  // broken <param> made libassimp assert and abort the process).
  const size_t accessor = rig.find("<accessor source=\"#Cube-mesh-positions-array\" count=\"8\"");
  REQUIRE(accessor != std::string::npos);
  std::string longer = rig;
  longer.replace(longer.find("count=\"8\"", accessor), 9, "count=\"9\"");
  refused("accessor_count.dae", longer, "reads 9 x 3 values from 0 in 'Cube-mesh-positions-array', which holds 24");
  std::string broken = rig;
  broken[broken.find("<param", accessor) + 4] = '\xd7';
  refused("accessor_param.dae", broken, "<accessor> at byte " + std::to_string(accessor) + ": holds <par?m");
  CHECK(importCharacter(std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/collada/rig.dae").ok());
  // Not a file: a folder named like one.
  fs::create_directory(tmp.file("folder.fbx"));
  CHECK_THAT(outcome(importCharacter(tmp.file("folder.fbx"))), Catch::StartsWith(tmp.file("folder.fbx")));
  CHECK_THAT(outcome(importCharacter(tmp.file("missing.dae"))), Catch::StartsWith(tmp.file("missing.dae")));
}

TEST_CASE("assimp import: files an OBJ names outside its folder are not read, and texture paths stay inside it",
          "[assimp]") {
  TempDir tmp;
  fs::create_directory(tmp.file("sub"));
  writeBytes(tmp.file("secret.mtl"), "newmtl leaked\nKd 1 0 0\n");
  writeBytes(tmp.file("sub/inside.mtl"),
             "newmtl near\nKd 0 1 0\nmap_Kd tex/skin.png\nnewmtl far\nKd 0 0 1\nmap_Kd ../../etc/passwd\n"
             "newmtl root\nKd 1 1 1\nmap_Kd /etc/passwd\n");
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  writeBytes(tmp.file("sub/escape.obj"), "mtllib ../secret.mtl\n" + quad + "usemtl leaked\nf 1 2 3 4\n");
  writeBytes(tmp.file("sub/textures.obj"), "mtllib inside.mtl\n" + quad +
                                               "usemtl near\nf 1 2 3\nusemtl far\nf 1 3 4\nusemtl root\nf 2 3 4\n");
  auto escape = importCharacter(tmp.file("sub/escape.obj"));
  REQUIRE(escape.ok());
  // assimp names a material after the usemtl line even without its library: the library's red
  // must not have been read.
  bool leaked = false;
  for (const Material& m : escape->materials) leaked |= m.baseColorFactor == glm::vec4(1, 0, 0, 1);
  CHECK_FALSE(leaked);
  bool named = false;
  for (const auto& w : escape->report.warnings) named |= w.find("secret.mtl") != std::string::npos &&
                                                         w.find("outside the file's folder") != std::string::npos;
  CHECK(named);

  auto tex = importCharacter(tmp.file("sub/textures.obj"));
  REQUIRE(tex.ok());
  std::map<std::string, Material> byName;
  for (const Material& m : tex->materials) byName[m.name] = m;
  CHECK(byName.at("near").baseColorTextureUri == "tex/skin.png");
  CHECK(byName.at("near").baseColorFactor == glm::vec4(0, 1, 0, 1));
  CHECK(byName.at("far").baseColorTextureUri.empty());
  CHECK(byName.at("root").baseColorTextureUri.empty());
  std::string warnings;
  for (const auto& w : tex->report.warnings) warnings += w + "\n";
  CHECK_THAT(warnings, Catch::Contains("'../../etc/passwd': resolves outside the file's folder; not used"));
  CHECK_THAT(warnings, Catch::Contains("'/etc/passwd': absolute paths are not allowed; not used"));
}

TEST_CASE("character import: one entry point picks the importer by extension, in any case", "[assimp]") {
  CHECK(characterFormatOf("a/b.GLB") == CharacterFormat::Gltf);
  CHECK(characterFormatOf("hero.gltf") == CharacterFormat::Gltf);
  CHECK(characterFormatOf("hero.Fbx") == CharacterFormat::Fbx);
  CHECK(characterFormatOf("hero.DAE") == CharacterFormat::Collada);
  CHECK(characterFormatOf("hero.obj") == CharacterFormat::Obj);
  CHECK(characterFormatOf("scene.animorph") == CharacterFormat::Unknown);
  CHECK_FALSE(isCharacterPath("notes.txt"));
  CHECK(characterFileExtensions().size() == 5);
  TempDir tmp;
  writeBytes(tmp.file("notes.txt"), "not a character");
  CHECK_THAT(outcome(importCharacter(tmp.file("notes.txt"))),
             Catch::Equals(tmp.file("notes.txt") +
                           ": not a character file of a known format (expected .gltf, .glb, .fbx, .dae or .obj)"));
  // Not a regular file: why, as reading it would say, before a byte is read.
  CHECK_THAT(outcome(importCharacter("/dev/zero")), Catch::StartsWith("/dev/zero: is a character device"));
  const std::string glb = std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/gear.glb";
  auto gear = importCharacter(glb);
  REQUIRE(gear.ok());
  CHECK(gear->format == "glTF");
  CHECK(gear->unit.metresPerUnit == 1.0);
}

TEST_CASE("declared sizes: a binary FBX's every record is walked and the test files pass", "[assimp]") {
  if (!fs::exists(kModels + "FBX/huesitos.fbx")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  for (const std::string rel : {"FBX/huesitos.fbx", "FBX/spider.fbx", "FBX/animation_with_skeleton.fbx"}) {
    const std::string bytes = readBytes(kModels + rel);
    REQUIRE(isFbxBinary(bytes));
    const Status s = checkFbxBinaryDeclaredSizes(rel, bytes);
    INFO(rel << ": " << s.error());
    CHECK(s.ok());
  }
}

TEST_CASE("assimp import: each test character's FBX poses like the glTF Blender wrote from the same scene, "
          "within 1e-4 of the diagonal at 10 times",
          "[.fbxtwins]") {
  const std::string dir = ANIMORPH_TEST_CHARACTERS;
  const auto entries = test::testCharacterEntries(dir, "fbx");
  if (entries.empty()) ANIMORPH_SKIP("the test characters are missing (" << dir << "/manifest.json; the fixture needs Blender)");
  int compared = 0;
  for (const auto& entry : entries) {
    const std::string name = entry.at("character").get<std::string>() + "_" + entry.at("variant").get<std::string>();
    // The glTF of the same scene; FBX_SCALE_UNITS files have no glTF twin but the metre one.
    std::string glb = dir + "/" + name + ".glb";
    if (!fs::exists(glb)) glb = dir + "/" + entry.at("character").get<std::string>() + "_m.glb";
    INFO(name << " against " << glb);
    auto fbx = importCharacter(dir + "/" + entry.at("file").get<std::string>());
    REQUIRE(fbx.ok());
    auto gltf = importCharacter(glb);
    REQUIRE(gltf.ok());
    CHECK(fbx->unit.declared);
    CHECK(fbx->unit.metresPerUnit == Approx(entry.at("unit") == "cm" ? 0.01 : 1.0));
    REQUIRE(fbx->clips.size() == 1);
    REQUIRE(gltf->clips.size() == 1);
    REQUIRE(fbx->totalVertices() == gltf->totalVertices());
    keepFourInfluences(*fbx);
    // Skeleton, skin and blend shapes with their weight animation on both sides: the FBX's shapes
    // are as many as the glTF's (the two files order their meshes differently).
    size_t fbxShapes = 0, gltfShapes = 0;
    for (const Mesh& m : fbx->meshes) fbxShapes += m.morphTargets.size();
    for (const Mesh& m : gltf->meshes) gltfShapes += m.morphTargets.size();
    CHECK(fbxShapes == gltfShapes);
    // Both in metres: the FBX by its declared unit, Blender's glTF numbers by the scene's unit.
    const float fbxToMetres = float(fbx->unit.metresPerUnit);
    const float gltfToMetres = entry.at("scene_unit_scale").get<float>();
    const AnimationClip &a = fbx->clips[0], &b = gltf->clips[0];
    const float startA = firstKey(a), startB = firstKey(b), length = a.durationSec - startA;
    CHECK(b.durationSec - startB == Approx(length).margin(1e-4));
    double worst = 0.0, diagonal = 0.0;
    for (int i = 0; i < 10; ++i) {
      const float t = length * float(i) / 9.0f;
      const auto pa = scaled(skinnedWorldPositions(*fbx, &a, startA + t), fbxToMetres);
      const auto pb = scaled(skinnedWorldPositions(*gltf, &b, startB + t), gltfToMetres);
      diagonal = boundsOf(pb).diagonal();
      worst = std::max(worst, setDistance(pa, pb, float(1e-3 * diagonal)) / diagonal);
    }
    INFO("worst distance " << worst << " of the diagonal");
    CHECK(worst < 1e-4);
    ++compared;
  }
  CHECK(compared >= 10);
}

TEST_CASE("fbx shape values: channels' DeformPercent from ASCII and binary FBX, a cut file never read past its end",
          "[assimp]") {
  const std::string ascii =
      "Objects:  {\n"
      "\tDeformer: 11, \"SubDeformer::smile\", \"BlendShapeChannel\" {\n\t\tVersion: 100\n"
      "\t\tDeformPercent: 35\n\t\tFullWeights: *1 {\n\t\t\ta: 100\n\t\t}\n\t}\n"
      "\tDeformer: 12, \"SubDeformer::blink\", \"BlendShapeChannel\" {\n\t\tDeformPercent: 10\n"
      "\t\tProperties70:  {\n\t\t\tP: \"DeformPercent\", \"Number\", \"\", \"A\",80.5\n\t\t}\n\t}\n"
      "\tDeformer: 13, \"Deformer::Body\", \"BlendShape\" {\n\t\tVersion: 100\n\t}\n}\n";
  auto a = readFbxShapeValues("a.fbx", ascii);
  INFO(a.error());
  REQUIRE(a.ok());
  CHECK(a->percentByChannel.size() == 2);
  CHECK(a->percentByChannel.count("smile") == 1);
  CHECK(a->percentByChannel.count("blink") == 1);
  if (a->percentByChannel.size() == 2) {
    CHECK(a->percentByChannel.at("smile") == 35.0);
    CHECK(a->percentByChannel.at("blink") == 80.5);  // the Properties70 value over the record's
  }

  // Blender's binary FBX of the fuzz seed: one shape key held at 0.35.
  const std::string rig = readBytes(std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/fbx/rig.fbx");
  REQUIRE(isFbxBinary(rig));
  auto b = readFbxShapeValues("rig.fbx", rig);
  INFO(b.error());
  REQUIRE(b.ok());
  REQUIRE(b->percentByChannel.count("squash") == 1);
  CHECK(b->percentByChannel.at("squash") == Approx(35.0).margin(1e-4));
  // Every cut of it is read or refused naming the file, never past its bytes (ASan builds check that).
  int refused = 0;
  for (size_t cut = 0; cut < rig.size(); cut += 7) {
    auto r = readFbxShapeValues("rig.fbx", rig.substr(0, cut));
    if (!r.ok()) {
      CHECK(r.error().rfind("rig.fbx: ", 0) == 0);
      ++refused;
    }
  }
  CHECK(refused > 0);
  // The importer gives the shape its value.
  auto c = importCharacter(std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/fbx/rig.fbx");
  INFO(outcome(c));
  REQUIRE(c.ok());
  REQUIRE(c->meshes.size() == 1);
  REQUIRE(c->meshes[0].morphTargets.size() == 1);
  CHECK(c->meshes[0].defaultMorphWeights[0] == Approx(0.35f));
}

TEST_CASE("collada morphs: Blender's skin and shape key open with the shape at its value, bad morphs are refused "
          "naming the controller",
          "[assimp]") {
  const std::string path = std::string(ANIMORPH_SOURCE_DIR) + "/tests/fuzz/corpus/collada/rig.dae";
  const std::string dae = readBytes(path);
  REQUIRE(dae.find("<morph") != std::string::npos);
  auto prepared = prepareColladaMorphs("rig.dae", dae, 1000000);
  INFO(prepared.error());
  REQUIRE(prepared.ok());
  REQUIRE(prepared->morphs.size() == 1);
  const ColladaMorph& m = prepared->morphs[0];
  REQUIRE(m.targets.size() == 1);
  CHECK(m.targets[0].name == "squash");
  CHECK(m.defaultWeights == std::vector<float>{0.35f});
  CHECK(m.targets[0].deltas.size() == m.basePositions.size());
  CHECK(prepared->document.find("<morph") == std::string::npos);
  CHECK(prepared->document.find("set=\"" + std::to_string(kColladaIndexSet) + "\"") != std::string::npos);
  // Opened: the box's vertices split per face keep the shape (z x 0.8 where the base is z).
  auto c = importCharacter(path);
  INFO(outcome(c));
  REQUIRE(c.ok());
  REQUIRE(c->meshes.size() == 1);
  const Mesh& mesh = c->meshes[0];
  REQUIRE(mesh.morphTargets.size() == 1);
  CHECK(mesh.defaultMorphWeights[0] == Approx(0.35f));
  CHECK(mesh.texcoords0.size() == mesh.positions.size());
  for (const glm::vec2& uv : mesh.texcoords0) CHECK(uv.y != Approx(1.0f - kColladaIndexTag));  // the tag is not a UV set
  size_t checked = 0;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    // Blender's geometry is Z up: the shape scales z (the file's third coordinate) by 0.8.
    const glm::vec3 d = mesh.morphTargets[0].positionDeltas[v];
    CHECK(d.x == Approx(0.0f).margin(1e-6));
    CHECK(d.y == Approx(0.0f).margin(1e-6));
    CHECK(d.z == Approx(-0.2f * mesh.positions[v].z).margin(1e-5));
    ++checked;
  }
  CHECK(checked >= 8);

  // Broken morphs: a target of another size, a base that is not a geometry, a missing target.
  auto refused = [&](const std::string& from, const std::string& to, const std::string& reason) {
    std::string bad = dae;
    const size_t at = bad.find(from);
    REQUIRE(at != std::string::npos);
    bad.replace(at, from.size(), to);
    auto r = prepareColladaMorphs("rig.dae", bad, 1000000);
    REQUIRE_FALSE(r.ok());
    INFO(r.error());
    CHECK(r.error().rfind("rig.dae: ", 0) == 0);
    CHECK(r.error().find(reason) != std::string::npos);
  };
  const size_t morphAt = dae.find("<morph source=\"#");
  const size_t baseEnd = dae.find('"', morphAt + 16);
  const std::string base = dae.substr(morphAt + 16, baseEnd - morphAt - 16);
  // A skin whose source is the morph controller (as other exporters chain them) opens the same.
  {
    std::string chained = dae;
    const std::string skinSource = "<skin source=\"#" + base + "\"";
    const size_t at = chained.find(skinSource);
    REQUIRE(at != std::string::npos);
    chained.replace(at, skinSource.size(), "<skin source=\"#" + m.controllerId + "\"");
    TempDir tmp;
    writeBytes(tmp.file("chained.dae"), chained);
    auto d = importCharacter(tmp.file("chained.dae"));
    INFO(outcome(d));
    REQUIRE(d.ok());
    REQUIRE(d->meshes.size() == 1);
    CHECK(d->meshes[0].morphTargets.size() == 1);
    CHECK(d->meshes[0].positions.size() == mesh.positions.size());
    CHECK(d->skins.size() == 1);
  }
  refused("<morph source=\"#" + base + "\"", "<morph source=\"#nothing\"", "names no geometry");
  refused(base + "_morph_squash</IDREF_array>", "missing_target</IDREF_array>", "geometry 'missing_target': missing");
  CHECK(prepareColladaMorphs("rig.dae", dae, 3).ok() == false);  // over the shape budget
}

namespace {

// The character with every blend shape at weight w and no weight animation (the glTF's weights
// channels dropped: Blender's Collada has none), to compare two files' shapes at the same weights.
Character withShapesAt(Character c, float w) {
  for (Mesh& m : c.meshes) std::fill(m.defaultMorphWeights.begin(), m.defaultMorphWeights.end(), w);
  for (AnimationClip& clip : c.clips)
    clip.channels.erase(std::remove_if(clip.channels.begin(), clip.channels.end(),
                                       [](const Channel& ch) { return ch.path == ChannelPath::Weights; }),
                        clip.channels.end());
  return c;
}

// The worst distance between a's and b's vertex sets, relative to b's diagonal, at 10 times of
// their first clips from each clip's first key; each side scaled to metres.
double worstOverClip(const Character& a, float aToMetres, const Character& b, float bToMetres) {
  const AnimationClip &ca = a.clips[0], &cb = b.clips[0];
  const float startA = firstKey(ca), startB = firstKey(cb), length = ca.durationSec - startA;
  double worst = 0.0;
  for (int i = 0; i < 10; ++i) {
    const float t = length * float(i) / 9.0f;
    const auto pa = scaled(skinnedWorldPositions(a, &ca, startA + t), aToMetres);
    const auto pb = scaled(skinnedWorldPositions(b, &cb, startB + t), bToMetres);
    const double diagonal = boundsOf(pb).diagonal();
    worst = std::max(worst, setDistance(pa, pb, float(1e-3 * diagonal)) / diagonal);
  }
  return worst;
}

// The largest distance a vertex moves at rest when every shape goes from weight 0 to 1, relative
// to the character's diagonal.
double largestShapeMove(const Character& c) {
  const auto p0 = skinnedWorldPositions(withShapesAt(c, 0.0f), nullptr, 0.0f);
  const auto p1 = skinnedWorldPositions(withShapesAt(c, 1.0f), nullptr, 0.0f);
  double worst = 0.0;
  for (size_t i = 0; i < p0.size() && i < p1.size(); ++i) worst = std::max(worst, double(glm::distance(p0[i], p1[i])));
  return worst / boundsOf(p0).diagonal();
}

}  // namespace

TEST_CASE("assimp import: each test character's Collada opens with its shape keys and poses like the glTF Blender "
          "wrote from the same scene, shapes at 0 and at 1, within 1e-4 of the diagonal at 10 times",
          "[.daetwins]") {
  const std::string dir = ANIMORPH_TEST_CHARACTERS;
  const auto entries = test::testCharacterEntries(dir, "dae");
  if (entries.empty()) ANIMORPH_SKIP("the test characters are missing (" << dir << "/manifest.json; the fixture needs Blender)");
  int compared = 0;
  for (const auto& entry : entries) {
    const std::string name = entry.at("character").get<std::string>() + "_" + entry.at("variant").get<std::string>();
    INFO(name);
    auto dae = importCharacter(dir + "/" + entry.at("file").get<std::string>());
    INFO(outcome(dae));
    REQUIRE(dae.ok());
    auto gltf = importCharacter(dir + "/" + name + ".glb");
    REQUIRE(gltf.ok());
    CHECK(dae->unit.declared);
    CHECK(dae->unit.metresPerUnit == Approx(entry.at("unit") == "cm" ? 0.01 : 1.0));
    // Every shape key, by name, at the value of the frame Blender exported at (frame 1: 0).
    std::map<std::string, float> shapes;
    for (const Mesh& m : dae->meshes)
      for (size_t k = 0; k < m.morphTargets.size(); ++k) shapes[m.morphTargets[k].name] = m.defaultMorphWeights[k];
    CHECK(shapes.size() == entry.at("shape_keys").size());
    for (const auto& item : entry.at("shape_keys").items()) {
      const std::string key = item.key();
      INFO("shape key " << key);
      REQUIRE(shapes.count(key) == 1);
      CHECK(shapes[key] == 0.0f);
    }
    REQUIRE(dae->clips.size() == 1);
    REQUIRE(gltf->clips.size() == 1);
    keepFourInfluences(*dae);
    const float daeToMetres = float(dae->unit.metresPerUnit), gltfToMetres = entry.at("scene_unit_scale").get<float>();
    const double atZero = worstOverClip(withShapesAt(*dae, 0.0f), daeToMetres, withShapesAt(*gltf, 0.0f), gltfToMetres);
    const double atOne = worstOverClip(withShapesAt(*dae, 1.0f), daeToMetres, withShapesAt(*gltf, 1.0f), gltfToMetres);
    const double moved = largestShapeMove(*dae);  // the shapes matter: at weight 1 they move vertices
    INFO("worst distance, shapes at 0: " << atZero << ", at 1: " << atOne << " of the diagonal; shapes move " << moved);
    CHECK(atZero < 1e-4);
    CHECK(atOne < 1e-4);
    CHECK(moved > 1e-3);
    ++compared;
  }
  CHECK(compared == 9);
}

TEST_CASE("character import: glTF materials give the same base colour and texture fields as FBX's", "[assimp]") {
  const std::string dir = "/usr/share/assimp/models/glTF2/";
  if (!fs::exists(dir + "BoxTextured-glTF/BoxTextured.gltf")) ANIMORPH_SKIP("assimp-testmodels is not installed");
  auto external = importCharacter(dir + "BoxTextured-glTF/BoxTextured.gltf");
  REQUIRE(external.ok());
  REQUIRE(external->materials.size() == 1);
  CHECK(external->materials[0].baseColorTextureUri == "CesiumLogoFlat.png");
  CHECK_FALSE(external->materials[0].baseColorTextureEmbedded);
  REQUIRE(external->meshes.size() == 1);
  CHECK(external->meshes[0].material == 0);
  auto embedded = importCharacter(dir + "BoxTextured-glTF-Embedded/BoxTextured.gltf");
  REQUIRE(embedded.ok());
  CHECK(embedded->materials.at(0).baseColorTextureUri.empty());
  CHECK(embedded->materials.at(0).baseColorTextureEmbedded);
}
