// animorph-cli farm slurm: a bake as a Slurm job array (one task per chunk of frames) plus an
// assembly job that runs after every task succeeded (cli/farm.h, docs/farm.md).
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/export/frame_chunks.h"
#include "core/export/frame_files.h"
#include "app/cli/cli_command.h"
#include "app/cli/farm/farm.h"
#include "core/project/project_io.h"
#include "core/util/result.h"

namespace animorph::cli {

namespace {

namespace fs = std::filesystem;

// 'text' for bash: single quotes, a single quote written as '\''.
std::string shellQuote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string absolutePath(const std::string& path) { return fs::weakly_canonical(fs::absolute(path)).string(); }

// What every script starts with: the interpreter, what wrote it, the job's name, log and partition.
std::string scriptHead(const std::string& what, const std::string& jobName, const std::string& log,
                       const std::string& partition) {
  std::string s = "#!/bin/bash\n# Written by animorph-cli farm slurm: " + what + "\n";
  s += "#SBATCH --job-name=" + jobName + "\n#SBATCH --output=" + log + "\n";
  if (!partition.empty()) s += "#SBATCH --partition=" + partition + "\n";
  return s;
}

// The job array: task i bakes chunk i into DIR (the frame sequence) and its own glTF (chunkDir).
std::string bakeScript(const FarmOptions& o, const std::string& exe, const std::string& project,
                       const std::string& out, const std::string& name, const std::vector<FrameChunk>& chunks,
                       const std::string& chunkDir) {
  std::string s = scriptHead("frames " + std::to_string(o.first) + ".." + std::to_string(o.last) + " of " + project +
                                 " in " + std::to_string(chunks.size()) + " chunks, one array task per chunk",
                             "animorph-bake-" + name, out + "/logs/bake_%A_%a.log", o.partition);
  s += "#SBATCH --array=0-" + std::to_string(chunks.size() - 1) + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(o.jobs) + "\n#SBATCH --ntasks=1\n";
  // --gpu: every task on a node with a GPU (a generic resource the cluster's gres.conf declares);
  // bake --gpu refuses to run without a usable device rather than fall back to the CPU.
  if (o.gpu) s += "#SBATCH --gres=gpu:1\n";
  s += "set -eu\n";
  std::string first = "FIRST=(", last = "LAST=(", glb = "GLB=(";
  for (size_t i = 0; i < chunks.size(); ++i) {
    const char* sep = i ? " " : "";
    first += sep + std::to_string(chunks[i].first);
    last += sep + std::to_string(chunks[i].last);
    glb += sep + shellQuote(chunkGltfName(chunkDir, name, chunks[i]));
  }
  s += first + ")\n" + last + ")\n";
  if (!chunkDir.empty()) s += glb + ")\n";
  s += "i=${SLURM_ARRAY_TASK_ID:?submit this script with sbatch: it is a job array}\n";
  s += "exec " + shellQuote(exe) + " bake " + shellQuote(project) + " --frames \"${FIRST[i]}:${LAST[i]}\" --res " +
       std::to_string(o.res) + " --jobs " + std::to_string(o.jobs) + " --name " + name + " --format " + o.format;
  if (o.format != "none") s += " -o " + shellQuote(out);
  if (!chunkDir.empty()) s += " --gltf \"${GLB[i]}\"";
  if (o.gpu) s += " --gpu";
  if (o.keepInnerShell) s += " --keep-inner-shell";
  return s + "\n";
}

// The assembly job: the chunks' glTFs joined into --gltf and/or rendered into --mp4.
std::string assembleScript(const FarmOptions& o, const std::string& exe, const std::string& project,
                           const std::string& out, const std::string& name, const std::string& chunkDir) {
  std::string s = scriptHead("joins the chunks of " + project + " (run after the bake array succeeded)",
                             "animorph-assemble-" + name, out + "/logs/assemble_%j.log", o.partition);
  s += "#SBATCH --ntasks=1\nset -eu\n";
  s += "exec " + shellQuote(exe) + " farm assemble " + shellQuote(project) + " --frames " + std::to_string(o.first) +
       ":" + std::to_string(o.last) + " --chunk " + std::to_string(o.chunkFrames) + " --name " + name +
       " --chunks " + shellQuote(chunkDir);
  if (!o.gltf.empty()) s += " --gltf " + shellQuote(absolutePath(o.gltf));
  if (!o.mp4.empty()) s += " --mp4 " + shellQuote(absolutePath(o.mp4)) + " --size " + o.size;
  if (o.burnIn) s += " --burn-in";
  if (o.keepChunks) s += " --keep-chunks";
  return s + "\n";
}

Status writeScript(const std::string& path, const std::string& text) {
  {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!(f << text) || !f.flush()) return Error{path + ": cannot write the job script"};
  }
  std::error_code ec;
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add,
                  ec);
  return {};
}

// Runs `sbatch --parsable ARGS SCRIPT` and returns the job id it prints ("ID" or "ID;CLUSTER").
Result<std::string> sbatch(const std::string& args, const std::string& script) {
  const std::string cmd = "sbatch --parsable " + args + shellQuote(script);
  std::fflush(stdout);  // what was printed so far comes before sbatch's messages
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return Error{"cannot run sbatch"};
  std::string out;
  char buf[256];
  while (size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = pclose(p);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    return Error{"sbatch not found: Slurm's client commands must be on PATH (Debian package slurm-client)"};
  if (status != 0) return Error{"sbatch " + script + " failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")"};
  const std::string id = out.substr(0, out.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    return Error{"sbatch " + script + ": expected a job id, got '" + out + "'"};
  return id;
}

}  // namespace

int runFarmSlurm(const FarmOptions& o) {
  if (o.output.empty()) return fail("farm", "slurm: -o DIR is needed (the frames, chunks, job scripts and logs)", 2);
  if (o.format == "none" && o.gltf.empty() && o.mp4.empty())
    return fail("farm", "slurm: nothing to bake: --format none and neither --gltf nor --mp4", 2);
  auto p = loadProject(o.project);
  if (!p) return fail("farm", p.error());
  if (o.gpu && !p->morph.enabled())
    return fail("farm", "slurm: --gpu: " + o.project + " has no morph (an animorphosis is baked on the CPU)", 2);
  std::error_code ec;
  const fs::path exePath = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return fail("farm", "cannot find the path of this animorph-cli: " + ec.message());
  const std::string exe = exePath.string(), project = absolutePath(o.project), out = absolutePath(o.output);
  if (out.find_first_of(" \t\n%") != std::string::npos)
    return fail("farm", "slurm: " + out + ": the output folder's path may not hold spaces or '%' (#SBATCH lines)", 2);
  const std::string name = o.name.empty() ? framePrefix(p->name) : o.name;
  const bool assemble = !o.gltf.empty() || !o.mp4.empty();
  const std::string chunkDir = assemble ? out + "/chunks" : std::string();
  for (const char* sub : {"slurm", "logs", "chunks"}) {
    if (!assemble && std::string(sub) == "chunks") continue;
    fs::create_directories(fs::path(out) / sub, ec);
    if (ec) return fail("farm", out + "/" + sub + ": cannot create directory: " + ec.message());
  }
  const std::vector<FrameChunk> chunks = splitFrames(o.first, o.last, o.chunkFrames);
  const std::string bakePath = out + "/slurm/" + name + "_bake.sbatch";
  const std::string assemblePath = out + "/slurm/" + name + "_assemble.sbatch";
  if (Status st = writeScript(bakePath, bakeScript(o, exe, project, out, name, chunks, chunkDir)); !st)
    return fail("farm", st.error());
  if (assemble)
    if (Status st = writeScript(assemblePath, assembleScript(o, exe, project, out, name, chunkDir)); !st)
      return fail("farm", st.error());
  std::printf("wrote %s: %zu array tasks of up to %d frames (", bakePath.c_str(), chunks.size(), o.chunkFrames);
  for (size_t i = 0; i < chunks.size(); ++i) std::printf("%s%d..%d", i ? ", " : "", chunks[i].first, chunks[i].last);
  std::printf(")\n");
  if (assemble) std::printf("wrote %s: joins the chunks after every task succeeded\n", assemblePath.c_str());
  if (!o.submit) {
    std::printf("submit with:\n");
    if (assemble)
      std::printf("  jid=$(sbatch --parsable %s) && sbatch --dependency=afterok:${jid%%%%;*} %s\n",
                  shellQuote(bakePath).c_str(), shellQuote(assemblePath).c_str());
    else
      std::printf("  sbatch %s\n", shellQuote(bakePath).c_str());
    return 0;
  }
  auto bakeJob = sbatch("", bakePath);
  if (!bakeJob) return fail("farm", "slurm: " + bakeJob.error());
  std::printf("submitted bake job %s (%zu array tasks)\n", bakeJob->c_str(), chunks.size());
  if (assemble) {
    auto assembleJob = sbatch("--dependency=afterok:" + *bakeJob + " ", assemblePath);
    if (!assembleJob) return fail("farm", "slurm: " + assembleJob.error() + " (the bake job " + *bakeJob + " was submitted)");
    std::printf("submitted assemble job %s (after job %s succeeded)\n", assembleJob->c_str(), bakeJob->c_str());
  }
  return 0;
}

}  // namespace animorph::cli
