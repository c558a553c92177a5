#pragma once
// What a fuzz target asserts beyond "no crash, no sanitizer report": a property that
// must hold for every input the loaders accept. A broken one aborts with the reason,
// so libFuzzer keeps the input as a crash.
#include <cstdio>
#include <cstdlib>
#include <string>

namespace animorph::fuzz {

inline void require(bool ok, const char* what, const std::string& detail = {}) {
  if (ok) return;
  std::fprintf(stderr, "fuzz property broken: %s%s%s\n", what, detail.empty() ? "" : ": ", detail.c_str());
  std::abort();
}

// True when a loader's result holds a value; a refusal must name the input as given first.
template <class R>
bool loaded(const R& result, const std::string& name) {
  if (!result) require(result.error().rfind(name, 0) == 0, "an error starts with the input's name", result.error());
  return bool(result);
}

}  // namespace animorph::fuzz
