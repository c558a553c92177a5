// Benchmark of the host's part of a GPU preview frame on the recording thread (the editor's UI
// thread): GpuPolygonizer::record() building the command buffer for the animorphosis demo's
// programs, with the frame's host half (grid bounds, packing, region lists) computed in the record
// as before, and prepared beforehand on the field compile thread (GpuPolygonizer::prepare,
// PreviewFieldCompiler). Nothing is submitted: the rows time the host alone. Latency, wall, one
// thread, warm (pipelines made by the first record), medians; the baseline is the same run's
// unprepared record.
#include <cstdio>
#include <string>

#include "app/cli/bench/bench.h"
#include "core/animorphosis/compile_generic.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/compile.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/vulkan/command_resources.h"
#include "gpu/vulkan/context.h"

namespace {

using namespace animorph;
using animorph::bench::Row;
namespace g = animorph::gpu;

// Rows for one program at res: the record's host time without and with a prepared frame, and the
// preparation itself (off the recording thread).
void recordRows(g::Context& ctx, g::GpuPolygonizer& poly, VkCommandBuffer cmd, const std::string& tag,
                const FieldProgram& program, int res, std::vector<Row>& rows) {
  const g::GpuField field = g::GpuField::single(program);
  g::GpuPolygonizeSettings s;
  s.resolution = res;
  const uint64_t limit = g::GpuPolygonizer::loopLimit(ctx.properties());
  uint64_t serial = 0;
  std::string error;
  auto recordOnce = [&](const g::GpuPreparedFrame* prepared) {
    vkResetCommandBuffer(cmd, 0);
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    vkBeginCommandBuffer(cmd, &bi);
    Status st = poly.record(cmd, serial++, field, s, prepared);
    vkEndCommandBuffer(cmd);
    if (!st && error.empty()) error = st.error();
  };
  std::shared_ptr<const g::GpuPreparedFrame> prepared;
  const double prepareMs = animorph::bench::medianMs(3, [&] {
    auto p = g::GpuPolygonizer::prepare(field, s, limit);
    if (p) prepared = *p;
    else if (error.empty()) error = p.error();
  });
  const double plainMs = animorph::bench::medianMs(5, [&] { recordOnce(nullptr); });
  const double preparedMs = animorph::bench::medianMs(5, [&] { recordOnce(prepared.get()); });
  if (!error.empty()) {
    rows.push_back({tag + " record failed", 0, "", "", error});
    return;
  }
  const std::string how = "latency, wall, one thread, warm, median; nothing submitted";
  rows.push_back({tag + " record host time, preparing in the record", plainMs, "ms", "",
                  "the baseline: grid bounds, packing and region lists on the recording thread; " + how});
  rows.push_back({tag + " record host time, prepared frame", preparedMs, "ms", "",
                  "upload and commands only (lastStats().preparedInRecord " +
                      std::string(poly.lastStats().preparedInRecord ? "true" : "false") + "); " + how});
  rows.push_back({tag + " prepare (field compile thread)", prepareMs, "ms", "",
                  "GpuPolygonizer::prepare, off the recording thread; " + how});
  rows.push_back({tag + " record host time, prepared / preparing", preparedMs / plainMs, "ratio", "", ""});
}

std::vector<Row> runGpuRecord(const animorph::bench::Options& opt) {
  std::vector<Row> rows;
  bool wanted = opt.gpu;
  for (const auto& f : opt.filters) wanted |= f.find("gpu") != std::string::npos;
  if (!wanted) return {{"skipped", 0, "", "", "run `bench gpu-record` or pass --gpu"}};
  auto ctx = g::Context::create(g::ContextSettings{});
  if (!ctx) return {{"skipped", 0, "", "", "no Vulkan device: " + ctx.error()}};
  auto poly = g::GpuPolygonizer::create(**ctx);
  if (!poly) return {{"skipped", 0, "", "", poly.error()}};
  auto project = makeAnimorphosisDemoProject();
  auto c = project ? projectGenericTree(*project) : Result<GenericTree>(Error{project.error()});
  if (!c) return {{"animorphosis demo: skipped", 0, "", "", c.error()}};
  rows.push_back({"device", 0, "", "", (*ctx)->deviceName()});
  VkDevice dev = (*ctx)->device();
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (Status st = g::createCommandResources(dev, (*ctx)->queueFamily(), 1, &pool, &cmd, nullptr); !st) {
    if (pool) vkDestroyCommandPool(dev, pool, nullptr);
    return {{"skipped", 0, "", "", st.error()}};
  }
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  const FieldProgram ct = compileGeneric(*c, animorphosisTiming(*project), mid);
  const int res = opt.quick ? 48 : 96;
  recordRows(**ctx, **poly, cmd, "demo C(t) at the middle " + std::to_string(res) + "^3", ct, res, rows);
  const FieldProgram dragon = compileFieldProgram(project->actors[1].blobTree, 0.5);
  recordRows(**ctx, **poly, cmd, "demo dragon 128^3", dragon, 128, rows);
  vkDeviceWaitIdle(dev);
  vkDestroyCommandPool(dev, pool, nullptr);
  return rows;
}

}  // namespace

ANIMORPH_BENCH("gpu-record", "Host time of a GPU preview record of the demo's programs, preparing in it or prepared ahead",
               runGpuRecord);
