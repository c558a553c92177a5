#include <catch2/catch.hpp>

#include "core/export/frame_chunks.h"

using namespace animorph;

TEST_CASE("frame chunks: a range split into consecutive chunks covering it once, the last one shorter",
          "[bake][farm]") {
  const std::vector<FrameChunk> c = splitFrames(0, 144, 49);
  REQUIRE(c.size() == 3);
  CHECK((c[0].first == 0 && c[0].last == 48));
  CHECK((c[1].first == 49 && c[1].last == 97));
  CHECK((c[2].first == 98 && c[2].last == 144));
  for (int first : {0, 7, 100})
    for (int last : {first, first + 1, first + 30})
      for (int n : {1, 2, 5, 31, 1000}) {
        const std::vector<FrameChunk> s = splitFrames(first, last, n);
        int next = first;
        for (const FrameChunk& k : s) {
          CHECK(k.first == next);
          CHECK(k.last >= k.first);
          CHECK(k.last - k.first + 1 <= n);
          next = k.last + 1;
        }
        CHECK(next == last + 1);
        CHECK(s.size() == size_t((last - first) / n + 1));
      }
  CHECK(splitFrames(5, 4, 2).empty());
  CHECK(splitFrames(-1, 4, 2).empty());
  CHECK(splitFrames(0, 4, 0).empty());
}

TEST_CASE("frame chunks: the chunk's glTF is named NAME_AAAA-BBBB.glb in its folder", "[bake][farm]") {
  CHECK(chunkGltfName("/farm/chunks", "demo", {49, 97}) == "/farm/chunks/demo_0049-0097.glb");
  CHECK(chunkGltfName("out", "a.b", {10000, 12345}) == "out/a.b_10000-12345.glb");
}
