// libFuzzer target: projectFromJson on a project file's text. A project that loads must
// save and load again as the same project (what the editor saves it can open).
#include <cstdint>
#include <string>

#include "core/project/project_io.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace animorph;
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto p = projectFromJson(text, "fuzz.animorph");
  if (!fuzz::loaded(p, "fuzz.animorph")) return 0;
  const std::string saved = projectToJson(*p);
  auto again = projectFromJson(saved, "saved.animorph");
  fuzz::require(bool(again), "a loaded project saves to a file that loads", again ? "" : again.error());
  fuzz::require(*again == *p, "a loaded project reloads unchanged from its saved form");
  return 0;
}
