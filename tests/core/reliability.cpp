// Hostile and careless input: every case gives a clear error in bounded time
// and memory. The bad files are generated here, at run time; the work that
// could crash, hang or allocate gigabytes runs in a forked child
// (util/bounded_run.h) so a regression fails the test instead of the runner.
#include <catch2/catch.hpp>

#include <sys/file.h>
#include <sys/stat.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/tree_edit.h"
#include "core/doc/actor_removal.h"
#include "core/project/asset_cache.h"
#include "core/util/atomic_file.h"
#include "core/project/project_io.h"
#include "core/io/gltf_import.h"
#include "util/blob_builders.h"
#include "util/bounded_run.h"
#include "core/util/json_text.h"
#include "util/mini_gltf.h"
#include "util/temp_dir.h"

using namespace animorph;
using animorph::test::BoundedRun;
using animorph::test::MiniGltf;
using animorph::test::runBounded;
using animorph::test::TempDir;

namespace {

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A BlobTree root: `depth` frame nodes nested in each other around one point.
std::string nestedFrames(int depth) {
  std::string s;
  for (int i = 0; i < depth; ++i) s += R"({"id":)" + std::to_string(i) + R"(,"type":"frame","children":[)";
  s += R"({"id":)" + std::to_string(depth) + R"(,"type":"point","params":{"center":[0,0,0],"radius":1}})";
  for (int i = 0; i < depth; ++i) s += "]}";
  return s;
}

std::string sceneText(int depth) {
  return R"({"format":"animorph-blobtree","version":1,"root":)" + nestedFrames(depth) + "}";
}

std::string projectWithTree(int depth) {
  return R"({"format":"animorph","version":1,"actors":[{"id":"blob","kind":"blobtree","blobtree":{"root":)" +
         nestedFrames(depth) + "}}]}";
}

// What a loader said: "ok" or its error.
template <class R>
std::string outcome(const R& r) {
  return r.ok() ? std::string("ok") : r.error();
}

// The run ended normally, quickly, and said `expected`.
void checkRefusedQuickly(const BoundedRun& r, const std::string& expected, double maxSeconds = 5.0,
                         long maxGrowthMiB = 200) {
  INFO("output: " << r.output << "\nsignal " << r.signal << ", " << r.seconds << " s, +" << r.peakGrowthMiB
                  << " MiB");
  CHECK(r.finished);
  CHECK_THAT(r.output, Catch::Contains(expected));
  CHECK(r.seconds < maxSeconds);
  CHECK(r.peakGrowthMiB < maxGrowthMiB);
}

// A valid one-triangle glTF whose JSON text starts with `prefix` members.
std::string triangleGltf(const TempDir& tmp, const std::string& name, const std::string& prefix) {
  MiniGltf g;
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  g.addMesh(pos, -1);
  g.json()["nodes"].push_back({{"mesh", 0}});
  const std::string path = g.write(tmp.path().string(), name);
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(text.front() == '{');
  text.insert(1, prefix);
  writeText(path, text);
  return path;
}

}  // namespace

// ---------------------------------------------------------------------------
// 1. Nesting depth

TEST_CASE("the JSON depth scan counts only real nesting and says where it is too deep", "[reliability][json]") {
  CHECK_FALSE(jsonDepthError(R"({"a": [1, {"b": []}]})", 4));
  CHECK(jsonDepthError(R"({"a": [1, {"b": []}]})", 3));
  // Brackets inside strings, escaped quotes included, do not nest.
  CHECK_FALSE(jsonDepthError(R"(["[[[[", "\"[[[[", "\\", "{{{{"])", 1));
  auto deep = jsonDepthError("{\"a\": [0,\n {\"b/c\": [[[]]]}]}", 4);
  REQUIRE(deep);
  CHECK_THAT(*deep, Catch::Contains("nesting deeper than 4 levels at line 2, column 11"));
  CHECK_THAT(*deep, Catch::Contains("/a/1/b~1c/0/0"));
  // A syntax error gives the line and column.
  auto bad = parseJsonText("{\n  \"a\": tru }", "x.json");
  REQUIRE_FALSE(bad.ok());
  CHECK_THAT(bad.error(), Catch::StartsWith("x.json: not valid JSON: parse error at line 2, column"));
}

TEST_CASE("20,000 nested frame nodes are refused, not a stack overflow", "[reliability][blobtree][project]") {
  // The generator makes valid trees: a shallow one loads.
  REQUIRE(outcome(parseBlobTreeScene(sceneText(3), "ok.json")) == "ok");
  REQUIRE(outcome(projectFromJson(projectWithTree(3), "ok.animorph")) == "ok");
  TempDir tmp;
  writeText(tmp.file("deep.animorph"), projectWithTree(20000));
  writeText(tmp.file("deep.blobtree.json"), sceneText(20000));
  checkRefusedQuickly(runBounded([&] { return outcome(loadProject(tmp.file("deep.animorph"))); }, 20),
                      tmp.file("deep.animorph") +
                          ": nesting deeper than 256 levels at line 1, column 4646 (in "
                          "/actors/0/blobtree/root/children/0/children/0/.../0/children/0)");
  checkRefusedQuickly(runBounded([&] { return outcome(loadBlobTreeScene(tmp.file("deep.blobtree.json"))); }, 20),
                      "nesting deeper than 256 levels at line 1, column");
}

TEST_CASE("a BlobTree deeper than the node limit names the first node too deep", "[reliability][blobtree]") {
  CHECK(outcome(parseBlobTreeScene(sceneText(kMaxBlobTreeDepth - 1), "s.json")) == "ok");
  const std::string err = outcome(parseBlobTreeScene(sceneText(kMaxBlobTreeDepth), "s.json"));
  CHECK_THAT(err, Catch::StartsWith("s.json: node " + std::to_string(kMaxBlobTreeDepth)));
  CHECK_THAT(err, Catch::Contains("nested 65 nodes deep, more than the 64 allowed"));
  CHECK_THAT(outcome(projectFromJson(projectWithTree(100), "p.animorph")),
             Catch::Contains("p.animorph: actor 'blob': node 64"));
}

TEST_CASE("the editor cannot build a BlobTree deeper than a file may be", "[reliability][blobtree]") {
  auto tree = parseBlobTreeScene(sceneText(kMaxBlobTreeDepth - 1), "s.json");  // frames 0..62, point 63 at level 64
  REQUIRE(tree.ok());
  int next = 1000;
  // A chain frame -> frame -> frame -> frame -> point (5 nodes high).
  auto chain = [&] {
    BlobNode top = makeDefaultNode(NodeType::Frame, next);
    BlobNode* at = &top;
    for (int i = 0; i < 3; ++i) {
      at->children.push_back(makeDefaultNode(NodeType::Frame, next));
      at = &at->children.back();
    }
    at->children.push_back(makeDefaultNode(NodeType::Point, next));
    return top;
  };
  // Under frame 62 (level 63) a single node fits; a frame with a child does not.
  CHECK(addNode(*tree, 62, makeDefaultNode(NodeType::Point, next)).ok());
  Status deeper = addNode(*tree, 62, chain());
  REQUIRE_FALSE(deeper.ok());
  CHECK_THAT(deeper.error(), Catch::Contains("the tree would be 68 nodes deep, more than the 64 allowed"));
  // Moving a subtree where it would end too deep is refused too, and changes nothing.
  BlobNode c = chain();
  const int chainId = c.id;
  REQUIRE(addNode(*tree, 0, std::move(c)).ok());
  const std::string before = blobTreeSceneToString(*tree);
  Status moved = reparentNode(*tree, chainId, 60);
  REQUIRE_FALSE(moved.ok());
  CHECK_THAT(moved.error(), Catch::Contains("cannot move"));
  CHECK(blobTreeSceneToString(*tree) == before);
  // Whatever the editor accepted loads again.
  CHECK(outcome(parseBlobTreeScene(before, "again.json")) == "ok");
}

TEST_CASE("a glTF whose extras nest 15,000 arrays is refused before tinygltf parses it", "[reliability][gltf]") {
  TempDir tmp;
  const std::string ok = triangleGltf(tmp, "shallow.gltf", R"("extras":[[[1]]],)");
  REQUIRE(outcome(importGltf(ok)) == "ok");
  const std::string deep =
      triangleGltf(tmp, "deep.gltf", "\"extras\":" + std::string(15000, '[') + std::string(15000, ']') + ",");
  checkRefusedQuickly(runBounded([&] { return outcome(importGltf(deep)); }, 20),
                      "deep.gltf: nesting deeper than 256 levels at line 1, column 266 (in /extras/0/0/0/0/0/0/0/...");
  // The same JSON as the chunk of a GLB.
  std::ifstream in(deep, std::ios::binary);
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (json.size() % 4) json += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  writeText(tmp.file("deep.glb"), "glTF" + u32(2) + u32(static_cast<uint32_t>(20 + json.size())) +
                                      u32(static_cast<uint32_t>(json.size())) + "JSON" + json);
  checkRefusedQuickly(runBounded([&] { return outcome(importGltf(tmp.file("deep.glb"))); }, 20),
                      "deep.glb: nesting deeper than 256 levels");
}

// ---------------------------------------------------------------------------
// 2. Files that are not regular files

TEST_CASE("/dev/zero, a FIFO and a folder are refused at once, naming the path as given", "[reliability][io]") {
  TempDir tmp;
  const std::string fifo = tmp.file("pipe.glb");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::filesystem::create_directories(tmp.path() / "folder.glb");
  const std::string folder = tmp.file("folder.glb");
  const BoundedRun r = runBounded(
      [&] {
        return outcome(readFile("/dev/zero")) + "\n" + outcome(importGltf(fifo)) + "\n" + outcome(importGltf(folder)) +
               "\n" + outcome(loadProject(fifo)) + "\n" + outcome(loadBlobTreeScene("/dev/zero"));
      },
      10);
  checkRefusedQuickly(r, "/dev/zero: is a character device, not a regular file", 3.0, 50);
  CHECK_THAT(r.output, Catch::Contains(fifo + ": is a FIFO (named pipe), not a regular file"));
  CHECK_THAT(r.output, Catch::Contains(folder + ": is a directory, not a regular file"));
  CHECK(r.output.find("not valid JSON") == std::string::npos);
}

TEST_CASE("a file over the size cap is refused before it is read", "[reliability][io]") {
  TempDir tmp;
  writeText(tmp.file("big.json"), std::string(11, ' '));
  auto whole = readFile(tmp.file("big.json"), 11);
  REQUIRE(whole.ok());
  CHECK(*whole == std::string(11, ' '));
  CHECK(outcome(readFile(tmp.file("big.json"), 10)) ==
        tmp.file("big.json") + ": is 11 bytes, more than the 10 bytes allowed");
}

TEST_CASE("a project asset naming /dev/zero gives the asset's error, not gigabytes read", "[reliability][io]") {
  const BoundedRun r = runBounded(
      [] {
        AssetCache cache;
        const AssetCache::Entry& e = cache.get("/dev/zero");
        return e.character ? std::string("loaded") : e.error;
      },
      10);
  checkRefusedQuickly(r, "/dev/zero: is a character device", 3.0, 50);
}

// ---------------------------------------------------------------------------
// 3. Integers that must not wrap

TEST_CASE("glTF indices beyond 32 bits are errors, not wrapped indices", "[reliability][gltf]") {
  TempDir tmp;
  auto build = [&](const std::string& name, auto&& edit) {
    MiniGltf g;
    int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    for (int i = 0; i < 4; ++i) g.addU16({0, 1, 2}, "SCALAR");  // accessors 1..4: wrapping would find one
    g.addMesh(pos, 1);
    g.json()["nodes"].push_back({{"mesh", 0}});
    edit(g.json());
    return g.write(tmp.path().string(), name);
  };
  REQUIRE(outcome(importGltf(build("fine.gltf", [](nlohmann::json&) {}))) == "ok");
  CHECK(outcome(importGltf(build("indices.gltf", [](nlohmann::json& j) {
          j["meshes"][0]["primitives"][0]["indices"] = 4294967300ULL;
        }))) == tmp.file("indices.gltf") + ": meshes[0].primitives[0].indices: 4294967300 is out of range (0..2147483647)");
  CHECK(outcome(importGltf(build("view.gltf", [](nlohmann::json& j) { j["accessors"][0]["bufferView"] = 4294967295ULL; }))) ==
        tmp.file("view.gltf") + ": accessors[0].bufferView: 4294967295 is out of range (0..2147483647)");
  CHECK(outcome(importGltf(build("attr.gltf", [](nlohmann::json& j) {
          j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 4294967296ULL;
        }))) == tmp.file("attr.gltf") + ": meshes[0].primitives[0].attributes.POSITION: 4294967296 is out of range (0..2147483647)");
  CHECK(outcome(importGltf(build("count.gltf", [](nlohmann::json& j) { j["accessors"][0]["count"] = 1ULL << 40; }))) ==
        tmp.file("count.gltf") + ": accessors[0].count: 1099511627776 is out of range (0..4294967295)");
  CHECK(outcome(importGltf(build("child.gltf", [](nlohmann::json& j) {
          j["nodes"][0]["children"] = {0, 4294967296ULL};
        }))) == tmp.file("child.gltf") + ": nodes[0].children[1]: 4294967296 is out of range (0..2147483647)");
  CHECK(outcome(importGltf(build("sparse.gltf", [](nlohmann::json& j) {
          j["accessors"][0]["sparse"] = {{"count", 4294967295ULL},
                                         {"indices", {{"bufferView", 1}, {"componentType", 5123}}},
                                         {"values", {{"bufferView", 0}}}};
        }))) == tmp.file("sparse.gltf") + ": accessors[0].sparse.count: 4294967295 is out of range (0..2147483647)");
  // An array of the wrong elements names the element instead of contradicting itself.
  CHECK(outcome(importGltf(build("mats.gltf", [](nlohmann::json& j) { j["skins"] = {nlohmann::json::object(), 3}; }))) ==
        tmp.file("mats.gltf") + ": skins[1]: expected an object, found integer");
}

TEST_CASE("project integers are read as 64 bits and range-checked", "[reliability][project]") {
  auto load = [](const std::string& body) {
    return outcome(projectFromJson(R"({"format":"animorph",)" + body + "}", "p.animorph"));
  };
  const std::string actors =
      R"("actors":[{"id":"a","asset":"a.glb"},{"id":"b","asset":"b.glb"}])";
  auto markers = [&](const std::string& m) {
    return load(R"("version":1,)" + actors + R"(,"morph":{"source":"a","target":"b","markers":)" + m + "}");
  };
  REQUIRE(load(R"("version":1)") == "ok");
  REQUIRE(markers(R"({"A":0,"B":10,"C":20,"D":30})") == "ok");
  CHECK_THAT(load(R"("version":4294967297)"), Catch::Contains("version 4294967297 is newer than this Animorph"));
  CHECK_THAT(load(R"("version":18446744073709551615)"), Catch::Contains("p.animorph: version: 18446744073709551615 is out of range"));
  CHECK(load(R"("version":1,"timeline":{"frame_end":4294967296})") ==
        "p.animorph: timeline.frame_end: 4294967296 is out of range (-10000000..10000000)");
  CHECK(load(R"("version":1,"timeline":{"frame_start":-2147483648})") ==
        "p.animorph: timeline.frame_start: -2147483648 is out of range (-10000000..10000000)");
  CHECK(load(R"("version":1,"timeline":{"fps":1e-300})") ==
        "p.animorph: timeline.fps: must be in [0.1, 1000] frames per second");
  CHECK(load(R"("version":1,"actors":[{"id":"a","asset":"a.glb","clip":2147483647}])") ==
        "p.animorph: actors[0].clip: 2147483647 is out of range (0..65535)");
  CHECK(markers(R"({"A":0,"B":4294967296,"C":4294967297,"D":4294967298})") ==
        "p.animorph: morph.markers.B: 4294967296 is out of range (-10000000..10000000)");
  CHECK_THAT(outcome(parseBlobTreeScene(R"({"root":{"id":4294967297,"type":"point","params":{"center":[0,0,0],"radius":1}}})", "s.json")),
             Catch::Contains("s.json: root: \"id\": 4294967297 is out of range"));
}

// ---------------------------------------------------------------------------
// 4. Decoding budget

TEST_CASE("a tiny glTF declaring 2^26 vertices without a bufferView is refused within the budget", "[reliability][gltf]") {
  TempDir tmp;
  const std::string path = tmp.file("tiny.gltf");
  writeText(path, R"({"asset":{"version":"2.0"},"accessors":[{"componentType":5126,"count":67108864,"type":"VEC3"}],)"
                  R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}]})");
  REQUIRE(std::filesystem::file_size(path) < 256);
  checkRefusedQuickly(runBounded([&] { return outcome(importGltf(path)); }, 20),
                      "tiny.gltf: accessor 0: 67108864 elements without a bufferView would decode to 805306368 bytes, "
                      "more than the",
                      2.0, 64);
}

TEST_CASE("animation channels sharing a huge accessor cannot multiply the allocation", "[reliability][gltf]") {
  TempDir tmp;
  const std::string path = tmp.file("channels.gltf");
  nlohmann::json j = {{"asset", {{"version", "2.0"}}},
                      {"nodes", {{{"name", "n"}}}},
                      {"accessors",
                       {{{"componentType", 5126}, {"count", 1000000}, {"type", "SCALAR"}},
                        {{"componentType", 5126}, {"count", 1000000}, {"type", "VEC3"}}}}};
  nlohmann::json channels = nlohmann::json::array();
  for (int i = 0; i < 400; ++i) channels.push_back({{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}});
  j["animations"] = {{{"channels", channels}, {"samplers", {{{"input", 0}, {"output", 1}}}}}};
  writeText(path, j.dump());
  const BoundedRun r = runBounded([&] { return outcome(importGltf(path)); }, 20);
  checkRefusedQuickly(r, "channels.gltf: accessor 0: 1000000 elements without a bufferView would decode to", 3.0, 100);
  CHECK_THAT(r.output, Catch::Contains("decoding budget"));
}

TEST_CASE("an accessor shared by many channels inside the budget is decoded and shared", "[reliability][gltf]") {
  TempDir tmp;
  MiniGltf g;
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  g.addMesh(pos, -1);
  g.json()["nodes"].push_back({{"mesh", 0}});
  int times = g.addFloats({0.0f, 0.5f, 1.0f}, "SCALAR");
  int values = g.addFloats({0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3");
  nlohmann::json channels = nlohmann::json::array();
  for (int i = 0; i < 50; ++i) channels.push_back({{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}});
  g.json()["animations"] = {{{"channels", channels}, {"samplers", {{{"input", times}, {"output", values}}}}}};
  auto c = importGltf(g.write(tmp.path().string(), "shared.gltf"));
  REQUIRE(c.ok());
  REQUIRE(c->clips.size() == 1);
  REQUIRE(c->clips[0].channels.size() == 50);
  for (const auto& ch : c->clips[0].channels) {
    CHECK(ch.timesSec == std::vector<float>{0.0f, 0.5f, 1.0f});
    CHECK(ch.values.back().x == 2.0f);
  }
}

// ---------------------------------------------------------------------------
// 5. Temporary files of atomic saves

namespace {

std::vector<std::string> temporariesOf(const std::filesystem::path& dir, const std::string& name) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("." + name + ".tmp", 0) == 0) out.push_back(f);
  }
  return out;
}

std::string contentsOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("a save removes stale temporaries of the same file, never a locked one or another file's", "[reliability][save]") {
  TempDir tmp;
  const std::string target = tmp.file("p.animorph");
  for (const char* stale : {".p.animorph.tmp123456", ".p.animorph.tmp0123456789abcdef"})
    writeText(tmp.file(stale), "half a save");
  writeText(tmp.file(".q.animorph.tmp123456"), "another project's");
  writeText(tmp.file(".p.animorph.tmp-mine"), "not a temporary name");
  writeText(tmp.file(".p.animorph.tmp777"), "a save in progress");
  int busy = ::open(tmp.file(".p.animorph.tmp777").c_str(), O_RDONLY | O_CLOEXEC);
  REQUIRE(busy >= 0);
  REQUIRE(::flock(busy, LOCK_EX) == 0);
  REQUIRE(writeFileAtomic(target, "new").ok());
  ::close(busy);
  CHECK(contentsOf(target) == "new");
  auto left = temporariesOf(tmp.path(), "p.animorph");
  std::sort(left.begin(), left.end());
  CHECK(left == std::vector<std::string>{".p.animorph.tmp-mine", ".p.animorph.tmp777"});
  CHECK(std::filesystem::exists(tmp.file(".q.animorph.tmp123456")));
  // Once its writer is gone, the next save removes it too.
  REQUIRE(writeFileAtomic(target, "newer").ok());
  CHECK(temporariesOf(tmp.path(), "p.animorph") == std::vector<std::string>{".p.animorph.tmp-mine"});
}

TEST_CASE("saves killed at random points leave the old or the new file, and no temporaries after the next save",
          "[reliability][save]") {
  TempDir tmp;
  const std::string target = tmp.file("k.animorph");
  const std::string a(1 << 20, 'a'), b(1 << 20, 'b');
  REQUIRE(writeFileAtomic(target, a).ok());
  std::mt19937 rng(7);
  for (int round = 0; round < 25; ++round) {
    std::fflush(nullptr);
    pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      for (int i = 0;; ++i) writeFileAtomic(target, i % 2 ? a : b);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(500, 20000)(rng)));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    const std::string now = contentsOf(target);
    CHECK((now == a || now == b));
  }
  REQUIRE(writeFileAtomic(target, "final").ok());
  CHECK(contentsOf(target) == "final");
  CHECK(temporariesOf(tmp.path(), "k.animorph").empty());
}

namespace {

// A child saves values[0] and values[1] alternately to path in a loop and is SIGKILLed after a
// random 0.2-30 ms, `rounds` times; after every kill the file must load as exactly one of the
// two (compared with what each loads as: loading may fill in what saving leaves out). Returns
// {kills after which the file did not, kills that left a named temporary behind}.
template <class T, class Save, class Load>
std::pair<int, int> killSavesAtRandom(const T (&values)[2], const std::string& path, int rounds, std::mt19937& rng,
                                      Save save, Load load) {
  T loaded[2];
  for (int k : {1, 0}) {
    REQUIRE(save(values[k], path).ok());
    auto l = load(path);
    REQUIRE(l);
    loaded[k] = *l;
  }
  REQUIRE_FALSE(loaded[0] == loaded[1]);
  const std::filesystem::path target(path);
  int torn = 0, leftBehind = 0;
  for (int round = 0; round < rounds; ++round) {
    std::fflush(nullptr);
    pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      for (int i = 0;; ++i) (void)save(values[(i + 1) % 2], path);
    }
    std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(200, 30000)(rng)));
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    auto l = load(path);
    if (!l || !(*l == loaded[0] || *l == loaded[1])) ++torn;
    if (!temporariesOf(target.parent_path(), target.filename().string()).empty()) ++leftBehind;
  }
  return {torn, leftBehind};
}

}  // namespace

TEST_CASE("project and scene saves killed at random points load as the old or the new one, no temporaries stay",
          "[reliability][save]") {
  TempDir tmp;
  std::mt19937 rng(21);
  // Projects of ~1 MB (3000 actors): a save takes long enough for kills to land inside it.
  auto bigProject = [](const std::string& tag) {
    Project p;
    p.name = tag;
    for (int i = 0; i < 3000; ++i) {
      Actor a;
      a.id = tag + std::to_string(i);
      a.name = "actor " + a.id;
      a.assetPath = "assets/" + a.id + ".glb";
      a.speed = 1.0 + i * 1e-3;
      p.actors.push_back(a);
    }
    return p;
  };
  const std::string project = tmp.file("big.animorph");
  const Project projects[2] = {bigProject("old"), bigProject("new")};
  const auto [tornProjects, projectLeft] = killSavesAtRandom(
      projects, project, 40, rng, saveProject, [](const std::string& path) { return loadProject(path); });
  CHECK(tornProjects == 0);

  // BlobTree scenes: a wide tree (2000 points under one blend), the same rule.
  auto bigTree = [](float radius) {
    std::vector<BlobNode> points;
    for (int i = 0; i < 2000; ++i)
      points.push_back(test::pointNode(i + 2, glm::vec3(0.001f * i, 0.0f, 0.0f), radius));
    return test::treeOf(test::operatorNode(NodeType::Blend, 1, std::move(points)));
  };
  const std::string scene = tmp.file("big.json");
  const BlobTree trees[2] = {bigTree(0.5f), bigTree(0.25f)};
  const auto [tornScenes, sceneLeft] = killSavesAtRandom(trees, scene, 25, rng, saveBlobTreeScene, loadBlobTreeScene);
  CHECK(tornScenes == 0);

  // Whatever the kills left (a temporary named just before its rename), the next save of the
  // same file removes; a killed save into an unnamed O_TMPFILE leaves nothing at all.
  UNSCOPED_INFO("kills that left a named temporary: " << projectLeft << " of 40 project saves, " << sceneLeft
                                                       << " of 25 scene saves");
  REQUIRE(saveProject(projects[0], project).ok());
  REQUIRE(saveBlobTreeScene(trees[0], scene).ok());
  CHECK(temporariesOf(tmp.path(), "big.animorph").empty());
  CHECK(temporariesOf(tmp.path(), "big.json").empty());
  std::vector<std::string> all;
  for (const auto& e : std::filesystem::directory_iterator(tmp.path())) all.push_back(e.path().filename().string());
  std::sort(all.begin(), all.end());
  CHECK(all == std::vector<std::string>{"big.animorph", "big.json"});
}

// ---------------------------------------------------------------------------
// 6. Deleting an actor the morph uses

TEST_CASE("deleting an actor the morph uses removes the morph in the same undoable command", "[reliability][morph]") {
  Project p;
  for (const char* id : {"src", "dst", "extra"}) {
    Actor a;
    a.id = id;
    a.name = id;
    a.assetPath = std::string(id) + ".glb";
    p.actors.push_back(a);
  }
  p.morph.sourceActorId = "src";
  p.morph.targetActorId = "dst";
  p.morph.markers = {10, 20, 30, 40};
  for (const char* id : {"src", "dst", "extra"}) p.morph.actors.push_back(ActorMorph{id, {}, {0.5f}, {}});
  const Project before = p;

  auto del = deleteActorCommand(p, "src");
  REQUIRE(del);
  del->apply(p);
  CHECK(p.actors.size() == 2);
  CHECK_FALSE(p.morph.enabled());
  CHECK(p.morph.actors.empty());
  // What is shown is what is saved: no morph either way.
  CHECK(projectToJson(p).find("\"morph\"") == std::string::npos);
  del->revert(p);
  CHECK(p == before);
  CHECK(projectToJson(p) == projectToJson(before));

  // An actor outside the source/target pair: only its own entry goes.
  auto delExtra = deleteActorCommand(p, "extra");
  REQUIRE(delExtra);
  delExtra->apply(p);
  CHECK(p.morph.enabled());
  CHECK(p.morph.findActor("extra") == nullptr);
  CHECK(p.morph.findActor("src") != nullptr);
  delExtra->revert(p);
  CHECK(p == before);
  CHECK(deleteActorCommand(p, "nobody") == nullptr);
}

// ---------------------------------------------------------------------------
// Parser errors name the element

TEST_CASE("malformed glTF structure is named by element, not by tinygltf's raw text", "[reliability][gltf]") {
  TempDir tmp;
  const nlohmann::json base = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", 36}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"nodes", {{{"mesh", 0}}}}};
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  // A GLB of `json` with a BIN chunk of binBytes (none when negative); `length` overrides the header's total.
  auto glb = [&](const std::string& name, const nlohmann::json& j, int binBytes, long length = -1) {
    std::string text = j.dump();
    while (text.size() % 4) text += ' ';
    std::string body = u32(static_cast<uint32_t>(text.size())) + "JSON" + text;
    if (binBytes >= 0) body += u32(static_cast<uint32_t>(binBytes)) + std::string("BIN\0", 4) + std::string(binBytes, '\0');
    const auto total = static_cast<uint32_t>(length >= 0 ? length : static_cast<long>(12 + body.size()));
    writeText(tmp.file(name), "glTF" + u32(2) + u32(total) + body);
    return outcome(importGltf(tmp.file(name)));
  };
  auto gltf = [&](const std::string& name, const nlohmann::json& j) {
    writeText(tmp.file(name), j.dump());
    return outcome(importGltf(tmp.file(name)));
  };
  REQUIRE(glb("ok.glb", base, 36) == "ok");
  const std::string length = glb("length.glb", base, 36, 10);
  CHECK_THAT(length, Catch::StartsWith(tmp.file("length.glb") + ": GLB JSON chunk: length "));
  CHECK_THAT(length, Catch::EndsWith(" exceeds the declared length (10 bytes)"));
  CHECK(glb("short.glb", base, 8) ==
        tmp.file("short.glb") + ": buffers[0].byteLength: 36 is more than the GLB's BIN chunk (8 bytes)");
  CHECK(glb("nobin.glb", base, -1) ==
        tmp.file("nobin.glb") + ": buffers[0]: no uri, and only buffer 0 of a GLB can use its BIN chunk (this GLB has none)");
  CHECK(gltf("nouri.gltf", base) ==
        tmp.file("nouri.gltf") + ": buffers[0].uri: missing (a .gltf buffer needs a file name or a data: URI)");
  nlohmann::json j = base;
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA";
  CHECK(gltf("data.gltf", j) == tmp.file("data.gltf") + ": buffers[0].uri: the data: URI holds 3 bytes but byteLength is 36");
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(48, 'A');
  REQUIRE(gltf("fine.gltf", j) == "ok");
  nlohmann::json k = j;
  k["accessors"][0].erase("type");
  CHECK(gltf("notype.gltf", k) == tmp.file("notype.gltf") + ": accessors[0].type: missing (required)");
  k = j;
  k["accessors"][0]["type"] = "VEC5";
  CHECK(gltf("vec5.gltf", k) == tmp.file("vec5.gltf") + ": accessors[0].type: 'VEC5' is not SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
  k = j;
  k["accessors"][0]["componentType"] = 5130;
  CHECK(gltf("double.gltf", k) == tmp.file("double.gltf") + ": accessors[0].componentType: 5130 is not a glTF component type (5120..5126)");
  k = j;
  k["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"path", "translation"}}}}}},
                      {"samplers", {{{"input", 0}}}}}};
  CHECK(gltf("anim.gltf", k) == tmp.file("anim.gltf") + ": animations[0].samplers[0].output: missing (required)");
  // A channel that animates no node (KHR_animation_pointer, as our sequence export writes) is valid
  // glTF that tinygltf cannot read: it is left out with a warning, and the file loads.
  k["animations"][0]["samplers"][0]["output"] = 0;
  k["animations"][0]["channels"][0]["target"] = {{"path", "pointer"},
                                                 {"extensions", {{"KHR_animation_pointer", {{"pointer", "/nodes/0/translation"}}}}}};
  CHECK(gltf("pointer.gltf", k) == "ok");
  std::ofstream(tmp.file("pointer2.gltf")) << k.dump();
  auto loaded = importGltf(tmp.file("pointer2.gltf"));
  REQUIRE(loaded.ok());
  CHECK(loaded->clips.empty());
  bool warned = false;
  for (const auto& w : loaded->report.warnings) warned |= w.find("animate no node (KHR_animation_pointer)") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("accepted but wrong glTF content gives warnings", "[reliability][gltf]") {
  TempDir tmp;
  MiniGltf g;
  int pos = g.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  g.addMesh(pos, -1);
  // A sheared node matrix, a node scaled to zero along x (its rotation is then undefined).
  g.json()["nodes"] = {{{"mesh", 0}, {"matrix", {1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}},
                       {{"matrix", {0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}}};
  int times = g.addFloats({-0.5f, 0.5f, 0.5f}, "SCALAR");
  int values = g.addFloats({0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3");
  g.json()["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}}}},
                             {"samplers", {{{"input", times}, {"output", values}}}}}};
  // A skin whose second inverse bind matrix is singular.
  int ibm = g.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,  //
                         0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1},
                        "MAT4");
  g.json()["skins"] = {{{"joints", {0, 1}}, {"inverseBindMatrices", ibm}}};
  auto c = importGltf(g.write(tmp.path().string(), "odd.gltf"));
  REQUIRE(c.ok());
  const auto& w = c->report.warnings;
  auto has = [&](const std::string& s) { return std::find(w.begin(), w.end(), s) != w.end(); };
  INFO(nlohmann::json(w).dump(1));
  CHECK(has("node 0: matrix is not translation x rotation x scale (it has shear or a projection); the nearest such "
            "transform is used"));
  CHECK(std::none_of(w.begin(), w.end(), [](const std::string& s) { return s.rfind("node 1:", 0) == 0; }));
  CHECK(c->nodes[1].rest.rotation == glm::quat(1, 0, 0, 0));
  CHECK(has("accessor " + std::to_string(times) + ": key times start below zero (-0.500000 s)"));
  CHECK(has("accessor " + std::to_string(times) + ": key time 0.500000 s repeats at key 2"));
  CHECK(has("skin 0: inverse bind matrix 1 (joint node 1) is not invertible; vertices bound to this joint collapse"));
}
