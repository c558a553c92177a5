#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "core/util/heap_trim.h"

using namespace animorph;

namespace {

// This process's resident anonymous memory (RssAnon of /proc/self/status) in MiB.
double residentAnonMiB() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("RssAnon:", 0) == 0) return std::stod(line.substr(8)) / 1024.0;
  return -1.0;
}

}  // namespace

TEST_CASE("trimFreedHeap gives back to the system what a finished worker thread freed", "[reliability][memory]") {
  if (!heapTrimSupported()) {  // a sanitizer's allocator: nothing of glibc's to trim
    CHECK_FALSE(trimFreedHeap());
    return;
  }
  trimFreedHeap();
  const double before = residentAnonMiB();
  REQUIRE(before > 0.0);
  std::vector<char*> kept;
  // 64 MiB in 512-byte blocks (small enough to come from the thread's malloc arena, not mmap),
  // every 64th kept alive so the arena cannot simply shrink from its top: what a preview worker's
  // run leaves behind.
  bool allocated = true;
  std::thread worker([&kept, &allocated] {
    constexpr size_t kBlock = 512, kCount = (size_t(64) << 20) / kBlock;
    std::vector<char*> blocks;
    blocks.reserve(kCount);
    for (size_t i = 0; i < kCount; ++i) {
      char* p = static_cast<char*>(std::malloc(kBlock));
      if (!p) {
        allocated = false;
        break;
      }
      std::memset(p, int(i & 0xff), kBlock);
      blocks.push_back(p);
    }
    for (size_t i = 0; i < blocks.size(); ++i) {
      if (i % 64 == 0) kept.push_back(blocks[i]);
      else std::free(blocks[i]);
    }
  });
  worker.join();
  REQUIRE(allocated);
  const double held = residentAnonMiB();
  INFO("RssAnon before " << before << " MiB, after the worker " << held << " MiB");
  REQUIRE(held - before > 40.0);  // freed, but still resident
  CHECK(trimFreedHeap());
  const double after = residentAnonMiB();
  INFO("after trimFreedHeap " << after << " MiB");
  CHECK(held - after > 30.0);
  for (char* p : kept) std::free(p);
}
