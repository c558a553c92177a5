// The command line of animorph-cli farm slurm / farm assemble (cli/farm.h).
#include <cstdio>
#include <cstdlib>

#include "core/export/frame_files.h"
#include "app/cli/farm/farm.h"

namespace animorph::cli {

std::string parseFarmOptions(const std::vector<std::string>& args, FarmOptions& o) {
  std::string frames;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "-o" || a == "--output" || a == "--frames" || a == "--chunk" || a == "--res" || a == "--jobs" ||
        a == "--name" || a == "--format" || a == "--gltf" || a == "--mp4" || a == "--size" || a == "--chunks" ||
        a == "--partition") {
      if (i + 1 >= args.size()) return a + " needs a value";
      const std::string& v = args[++i];
      if (a == "--frames") frames = v;
      else if (a == "--chunk") o.chunkFrames = std::atoi(v.c_str());
      else if (a == "--res") o.res = std::atoi(v.c_str());
      else if (a == "--jobs") o.jobs = std::atoi(v.c_str());
      else if (a == "--name") o.name = v;
      else if (a == "--format") o.format = v;
      else if (a == "--gltf") o.gltf = v;
      else if (a == "--mp4") o.mp4 = v;
      else if (a == "--size") o.size = v;
      else if (a == "--chunks") o.chunksDir = v;
      else if (a == "--partition") o.partition = v;
      else o.output = v;
    } else if (a == "--burn-in") {
      o.burnIn = true;
    } else if (a == "--keep-inner-shell") {
      o.keepInnerShell = true;
    } else if (a == "--submit") {
      o.submit = true;
    } else if (a == "--gpu") {
      o.gpu = true;
    } else if (a == "--keep-chunks") {
      o.keepChunks = true;
    } else if (!a.empty() && a[0] == '-') {
      return "unknown option " + a;
    } else if (o.project.empty()) {
      o.project = a;
    } else {
      return "only one PROJECT is accepted";
    }
  }
  if (o.project.empty()) return "no PROJECT given";
  char tail = 0;
  if (frames.empty() || std::sscanf(frames.c_str(), "%d:%d%c", &o.first, &o.last, &tail) != 2 || o.first < 0 ||
      o.last < o.first)
    return "--frames: expected A:B with 0 <= A <= B, got '" + frames + "'";
  if (o.chunkFrames < 1) return "--chunk: expected the frames per task, 1 or more";
  if (o.res < 2 || o.res > 1024) return "--res: expected 2..1024";
  if (o.jobs < 1 || o.jobs > 256) return "--jobs: expected 1..256";
  if (!o.name.empty() && framePrefix(o.name) != o.name)
    return "--name: use letters, digits, '.', '-' and '_' only, got '" + o.name + "'";
  if (o.format != "ply" && o.format != "obj" && o.format != "ply,obj" && o.format != "obj,ply" && o.format != "none")
    return "--format: expected ply, obj, ply,obj or none, got '" + o.format + "'";
  int w = 0, h = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192 || w % 2 ||
      h % 2)
    return "--size: expected WxH, even numbers 16..8192, got '" + o.size + "'";
  if (o.partition.find_first_of(" \t\n'\"\\$`") != std::string::npos)
    return "--partition: a Slurm partition name, got '" + o.partition + "'";
  return {};
}

}  // namespace animorph::cli
