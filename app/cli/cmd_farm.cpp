// animorph-cli farm slurm|assemble: a long bake split by frame range over a render farm (cli/farm.h).
#include "app/cli/cli_command.h"
#include "app/cli/farm/farm.h"

namespace {

using namespace animorph::cli;

int runFarm(const std::vector<std::string>& args) {
  if (args.empty() || (args[0] != "slurm" && args[0] != "assemble"))
    return fail("farm", "expected 'farm slurm ...' or 'farm assemble ...' (see animorph-cli farm --help)", 2);
  FarmOptions o;
  if (std::string e = parseFarmOptions(std::vector<std::string>(args.begin() + 1, args.end()), o); !e.empty())
    return fail("farm", args[0] + ": " + e, 2);
  if (args[0] == "slurm" && !o.chunksDir.empty())
    return fail("farm", "slurm: --chunks is an option of farm assemble (slurm puts the chunks into DIR/chunks)", 2);
  if (args[0] == "assemble" && (o.submit || !o.partition.empty() || !o.output.empty() || o.keepInnerShell))
    return fail("farm", "assemble: -o, --partition, --keep-inner-shell and --submit are options of farm slurm", 2);
  return args[0] == "slurm" ? runFarmSlurm(o) : runFarmAssemble(o);
}

}  // namespace

ANIMORPH_CLI_COMMAND("farm", "split a bake by frame range over a render farm (Slurm job array + assembly job)",
                     "usage: animorph-cli farm slurm PROJECT.animorph --frames A:B --chunk N --res R -o DIR\n"
                     "                          [--format ply|obj|ply,obj|none] [--name NAME] [--gltf FILE.glb]\n"
                     "                          [--mp4 FILE.mp4 [--size WxH] [--burn-in]] [--jobs J]\n"
                     "                          [--partition P] [--gpu] [--keep-inner-shell] [--keep-chunks]\n"
                     "                          [--submit]\n"
                     "       animorph-cli farm assemble PROJECT.animorph --frames A:B --chunk N --chunks DIR\n"
                     "                          [--name NAME] [--gltf FILE.glb] [--mp4 FILE.mp4 [--size WxH] [--burn-in]]\n"
                     "                          [--keep-chunks]\n"
                     "  farm slurm writes two Slurm batch scripts into DIR/slurm/ (absolute paths; the\n"
                     "  executable is this animorph-cli):\n"
                     "    NAME_bake.sbatch      a job array, one task per chunk of N frames: task i runs\n"
                     "                          `animorph-cli bake` on its frames with --res R --jobs J\n"
                     "                          (--cpus-per-task J), writing the frame sequence (--format,\n"
                     "                          default ply) into DIR and, when --gltf or --mp4 is given,\n"
                     "                          its chunk as an animated glTF DIR/chunks/NAME_AAAA-BBBB.glb\n"
                     "    NAME_assemble.sbatch  (with --gltf or --mp4) `farm assemble`: joins the chunks\n"
                     "                          into the glTF of the whole range and/or renders the mp4\n"
                     "  --gpu: every task asks Slurm for one GPU (#SBATCH --gres=gpu:1) and runs bake\n"
                     "  --gpu (B->C on the GPU polygoniser; a task whose node has no usable device fails\n"
                     "  with a message rather than bake on the CPU). A morph only.\n"
                     "  --keep-inner-shell: every task runs bake --keep-inner-shell (collapse and\n"
                     "  expansion frames keep the stand-in core as a second shell; by default they are\n"
                     "  written as their visible surface, as bake writes them).\n"
                     "  Logs go to DIR/logs/. Without --submit it prints the sbatch commands; with\n"
                     "  --submit it runs sbatch (the bake array, then the assembly with\n"
                     "  --dependency=afterok on the array) and prints both job ids.\n"
                     "  farm assemble reads the chunks' glTFs (DIR/NAME_AAAA-BBBB.glb for the chunks of\n"
                     "  A:B by N), checks that each holds exactly its frames, and writes --gltf (the same\n"
                     "  meshes as one `bake --gltf` of A:B) and/or --mp4 (as bake --mp4). Once everything\n"
                     "  is written it removes the chunks' glTFs (and DIR when that leaves it empty);\n"
                     "  --keep-chunks keeps them (farm slurm --keep-chunks passes it on).\n"
                     "  Exit status: 0 on success, 1 when the project, a chunk or sbatch fails, 2 on bad\n"
                     "  arguments.\n",
                     runFarm);
