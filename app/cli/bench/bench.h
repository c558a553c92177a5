#pragma once
// Benchmarks for `animorph-cli bench`: each bench_*.cpp registers one with
// ANIMORPH_BENCH. A benchmark measures its own baseline in the same run and
// prints rows of figures; it never fails on timing.
#include <string>
#include <vector>

namespace animorph::bench {

struct Row {
  std::string name;    // what was measured
  double value = 0.0;  // the figure
  std::string unit;    // "ms", "ratio", "tris", ...
  std::string target;  // the target, e.g. "<= 25 ms", or empty
  std::string note;    // anything else (baseline, sizes)
};

struct Options {
  bool quick = false;        // smaller sizes (used by tests)
  bool gpu = false;          // include GPU figures
  std::vector<std::string> filters;  // only benchmarks whose name contains one of these
};

using BenchFn = std::vector<Row> (*)(const Options&);

struct BenchInfo {
  const char* name;
  const char* summary;
  BenchFn run;
};

std::vector<BenchInfo>& benchRegistry();

struct BenchRegistrar {
  explicit BenchRegistrar(BenchInfo info) { benchRegistry().push_back(info); }
};

// Median wall time of fn in milliseconds over repeats runs (after one warm-up).
template <class Fn>
double medianMs(int repeats, Fn&& fn);

}  // namespace animorph::bench

#include <algorithm>
#include <chrono>

template <class Fn>
double animorph::bench::medianMs(int repeats, Fn&& fn) {
  fn();
  std::vector<double> t;
  for (int i = 0; i < std::max(1, repeats); ++i) {
    auto a = std::chrono::steady_clock::now();
    fn();
    auto b = std::chrono::steady_clock::now();
    t.push_back(std::chrono::duration<double, std::milli>(b - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

#define ANIMORPH_BENCH_CONCAT2(a, b) a##b
#define ANIMORPH_BENCH_CONCAT(a, b) ANIMORPH_BENCH_CONCAT2(a, b)
#define ANIMORPH_BENCH(...) \
  static ::animorph::bench::BenchRegistrar ANIMORPH_BENCH_CONCAT(animorphBenchRegistrar_, __LINE__)({__VA_ARGS__})
