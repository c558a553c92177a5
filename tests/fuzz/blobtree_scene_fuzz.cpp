// libFuzzer target: parseBlobTreeScene on a scene file's text. A scene that loads must
// compile into a field program at any time, evaluate to numbers, and save and load again
// as the same tree.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/field/field_program.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace animorph;
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto tree = parseBlobTreeScene(text, "fuzz.json");
  if (!fuzz::loaded(tree, "fuzz.json")) return 0;
  FieldEvaluator evaluator;
  for (double t : {-1.0, 0.0, 0.5, 2.0}) {
    FieldProgram program = compileFieldProgram(*tree, t);
    for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.5f, -0.25f, 1.0f), glm::vec3(3.0f, 2.0f, -4.0f)}) {
      glm::vec3 gradient;
      const float f = evaluator.evaluatePoint(program, p, &gradient);
      fuzz::require(!std::isnan(f), "the field is a number");
    }
  }
  auto again = parseBlobTreeScene(blobTreeSceneToString(*tree), "saved.json");
  fuzz::require(bool(again), "a loaded scene saves to a file that loads", again ? "" : again.error());
  fuzz::require(*again == *tree, "a loaded scene reloads unchanged from its saved form");
  return 0;
}
