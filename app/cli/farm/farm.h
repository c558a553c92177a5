#pragma once
// animorph-cli farm: a long bake split by frame range over a render farm's tasks (Slurm), and the
// assembly step that joins the chunks. See docs/farm.md.
#include <string>
#include <vector>

namespace animorph::cli {

// The options of `farm slurm` and `farm assemble` (each uses the ones its usage names).
struct FarmOptions {
  std::string project;
  int first = 0, last = 0;  // --frames A:B
  int chunkFrames = 0;      // --chunk N: frames per task
  int res = 48;             // --res R
  int jobs = 1;             // --jobs J: frames baked in parallel by each task (its CPUs)
  std::string output;       // -o DIR: the frames (and chunks/, slurm/, logs/)
  std::string format = "ply";
  std::string name;         // --name NAME (default: the project's name, as bake's prefix)
  std::string gltf, mp4, size = "1280x720";
  bool burnIn = false;
  bool keepInnerShell = false;  // --keep-inner-shell (slurm): each task bakes with it (both shells kept)
  std::string chunksDir;    // --chunks DIR (assemble): where the chunks' glTFs are
  std::string partition;    // --partition P (slurm)
  bool submit = false;      // --submit (slurm)
  bool gpu = false;         // --gpu (slurm): each task bakes B->C on the GPU, asking Slurm for one (--gres=gpu:1)
  bool keepChunks = false;  // --keep-chunks: assemble leaves the chunks' glTFs (removed once it succeeded)
};

// Parses args (after "slurm"/"assemble"); "" or the message of a usage error (exit status 2).
std::string parseFarmOptions(const std::vector<std::string>& args, FarmOptions& o);

int runFarmSlurm(const FarmOptions& o);
int runFarmAssemble(const FarmOptions& o);

}  // namespace animorph::cli
