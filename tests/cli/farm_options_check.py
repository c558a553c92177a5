#!/usr/bin/env python3
"""animorph-cli farm without a cluster: what --gpu and --keep-chunks put into the job scripts, how
bake --gpu (what a --gpu task runs) refuses on a machine with no Vulkan device, and `farm assemble`
removing the chunks' glTFs once it succeeded unless --keep-chunks is given.

usage: farm_options_check.py CLI PROJECT"""
import os
import shutil
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_checks import fail, run  # noqa: E402

cli, project = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
tmp = tempfile.mkdtemp(prefix="animorph-farm-options-")


def scripts(*extra):
    out = os.path.join(tmp, "plan" + "".join(extra).replace("-", "_"))
    r = run(cli, "farm", "slurm", project, "--frames", "0:5", "--chunk", "3", "--res", "8", "-o", out, "--gltf",
            os.path.join(tmp, "plan.glb"), *extra)
    if r.returncode != 0:
        fail(f"farm slurm {' '.join(extra)}: exit {r.returncode}: {r.stderr}")
    texts = []
    for name in ("demo_bake.sbatch", "demo_assemble.sbatch"):
        with open(os.path.join(out, "slurm", name)) as fh:
            texts.append(fh.read())
    return texts


try:
    # --gpu: each task asks Slurm for a GPU and bakes B->C on it; --keep-chunks reaches the assembly.
    bake, assemble = scripts()
    if "--gres" in bake or " --gpu" in bake or "--keep-inner-shell" in bake or "--keep-chunks" in assemble:
        fail(f"farm slurm without --gpu/--keep-inner-shell/--keep-chunks wrote:\n{bake}\n{assemble}")
    bake, assemble = scripts("--gpu", "--keep-chunks")
    bake_line = [line for line in bake.splitlines() if line.startswith("exec ")]
    if "#SBATCH --gres=gpu:1\n" not in bake or len(bake_line) != 1 or not bake_line[0].endswith(" --gpu"):
        fail(f"farm slurm --gpu: the bake script does not ask for a GPU and bake with it:\n{bake}")
    if "--keep-chunks" not in assemble:
        fail(f"farm slurm --keep-chunks: the assembly script does not keep them:\n{assemble}")
    print("ok: --gpu asks Slurm for one GPU per task (--gres=gpu:1) and runs bake --gpu; --keep-chunks is passed on")
    bake, assemble = scripts("--keep-inner-shell")
    bake_line = [line for line in bake.splitlines() if line.startswith("exec ")]
    if len(bake_line) != 1 or not bake_line[0].endswith(" --keep-inner-shell") or "--keep-inner-shell" in assemble:
        fail(f"farm slurm --keep-inner-shell: the tasks do not bake with it (or the assembly got it):\n{bake}\n{assemble}")
    print("ok: --keep-inner-shell reaches every task's bake")

    # What such a task does on a node without a usable Vulkan device: bake --gpu refuses clearly.
    env = dict(os.environ, VK_ICD_FILENAMES=os.path.join(tmp, "no-driver.json"))
    env.pop("DISPLAY", None)
    r = subprocess.run([cli, "bake", project, "--frames", "60:60", "--res", "8", "--format", "none", "--gltf",
                        os.path.join(tmp, "gpu.glb"), "--gpu"], capture_output=True, text=True, env=env, timeout=120)
    if r.returncode != 1 or "--gpu: no usable Vulkan device" not in r.stderr or os.path.exists(os.path.join(tmp, "gpu.glb")):
        fail(f"bake --gpu without a device: exit {r.returncode}, expected 1 and a message: {r.stderr.strip()!r}")
    print(f"ok: bake --gpu without a device exits 1: {r.stderr.strip().splitlines()[-1]}")
    r = run(cli, "farm", "slurm", os.path.join(os.path.dirname(project), "animorphosis.animorph"), "--frames", "0:5",
            "--chunk", "3", "-o", os.path.join(tmp, "anim"), "--gpu")
    if r.returncode != 2 or "--gpu" not in r.stderr:
        fail(f"farm slurm --gpu of an animorphosis: exit {r.returncode}, expected 2: {r.stderr.strip()!r}")

    # Two chunks baked as the array's tasks would, then assembled twice.
    chunks = os.path.join(tmp, "chunks")
    for first, last in ((0, 2), (3, 5)):
        r = run(cli, "bake", project, "--frames", f"{first}:{last}", "--res", "8", "--format", "none", "--gltf",
                os.path.join(chunks, f"demo_{first:04d}-{last:04d}.glb"))
        if r.returncode != 0:
            fail(f"bake of chunk {first}..{last}: exit {r.returncode}: {r.stderr}")
    want = ["demo_0000-0002.glb", "demo_0003-0005.glb"]
    r = run(cli, "farm", "assemble", project, "--frames", "0:5", "--chunk", "3", "--chunks", chunks, "--gltf",
            os.path.join(tmp, "kept.glb"), "--keep-chunks")
    if r.returncode != 0 or sorted(os.listdir(chunks)) != want or not os.path.exists(os.path.join(tmp, "kept.glb")):
        fail(f"farm assemble --keep-chunks: exit {r.returncode}, chunks left {os.listdir(chunks)}: {r.stderr}")
    r = run(cli, "farm", "assemble", project, "--frames", "0:5", "--chunk", "3", "--chunks", chunks, "--gltf",
            os.path.join(tmp, "assembled.glb"))
    if r.returncode != 0 or os.path.exists(chunks) or not os.path.exists(os.path.join(tmp, "assembled.glb")):
        fail(f"farm assemble: exit {r.returncode}, the chunks should be gone: {r.stdout}{r.stderr}")
    with open(os.path.join(tmp, "kept.glb"), "rb") as a, open(os.path.join(tmp, "assembled.glb"), "rb") as b:
        if a.read() != b.read():
            fail("the glTF assembled with --keep-chunks differs from the one assembled without")
    print(f"ok: {r.stdout.strip().splitlines()[-1]}")
finally:
    shutil.rmtree(tmp, ignore_errors=True)
print("OK")
