#!/usr/bin/env python3
"""animorph-cli farm slurm on a real Slurm cluster: one node on localhost, started by this test.

usage: farm_slurm_check.py CLI PROJECT
  Starts munged, slurmctld and slurmd with a private configuration in a temporary folder (free
  ports; the MUNGE key and socket, Slurm's state, spool, pid and log files all in that folder, so
  the test runs beside others and beside any Slurm of the machine). Then:
  * `farm slurm` without --submit: the two job scripts (absolute paths, this CLI as executable,
    one array task per chunk) and the sbatch commands it prints; bad arguments exit 2; `farm
    assemble` before the chunks exist exits 1 naming the missing chunk;
  * `farm slurm --submit` of PROJECT's frames in 3 chunks with --gltf: waits (bounded) for the
    bake array and the assembly job that depends on it, then compares the assembled glTF with one
    `bake --gltf` of the same frames on this machine: the same frame nodes and, per frame, the
    same vertex and index counts, positions and indices (normals within 1e-6), and the chunks'
    PLY sequence is complete (the run has --keep-chunks: the chunks are still there); `farm
    assemble --mp4` over the same chunks gives a playblast of every frame (ffprobe) and then
    removes the chunks;
  * a farm run whose first chunk cannot write its glTF: the assembly job never starts (it stays
    pending, DependencyNeverSatisfied), no glTF is written, the task's log names the chunk;
  * prints the wall times (farm run against the single bake) and the overhead per chunk.
  Everything it started is stopped at the end, also on failure.
Exit 77 (skipped) when Slurm or MUNGE is not installed (Debian packages slurm-wlm and munge, which
./run.sh test installs).
"""
import ctypes
import getpass
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree for the scripts imported below
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cli_checks import fail, run  # noqa: E402 (the scripts beside this one)
from export_checks import accessor_values, read_glb  # noqa: E402

FRAMES = (0, 144)  # the whole demo: source, collapse, morph, expand, target
CHUNK = 49         # -> 3 chunks: 0..48, 49..97, 98..144
RES = "24"
WAIT_SEC = 240     # for the farm run, start to assembled glTF
DAEMONS = ("munged", "slurmctld", "slurmd")
CLIENTS = ("sbatch", "squeue", "sinfo", "scontrol", "scancel")
TERMINAL_STATES = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "BOOT_FAIL",
                   "DEADLINE", "PREEMPTED"}


def free_ports(n):
    """n distinct TCP ports free on every address now (bound together, then released)."""
    socks = [socket.socket(socket.AF_INET, socket.SOCK_STREAM) for _ in range(n)]
    try:
        for s in socks:
            s.bind(("", 0))
        return [s.getsockname()[1] for s in socks]
    finally:
        for s in socks:
            s.close()


def find_program(name):
    return shutil.which(name) or next((p for p in (f"/usr/sbin/{name}", f"/sbin/{name}") if os.access(p, os.X_OK)), None)


class Cluster:
    """A one-node Slurm cluster on localhost in folder `tmp`; stop() ends everything start() began."""

    def __init__(self, tmp):
        self.tmp = tmp
        self.procs = []  # (name, Popen)
        self.conf = os.path.join(tmp, "slurm.conf")
        # The daemons, the jobs and what they start inherit this: how stop() finds leftovers.
        self.env = dict(os.environ, SLURM_CONF=self.conf, ANIMORPH_SLURM_TEST=tmp)

    def slurm(self, *args, check=True, timeout=30):
        r = subprocess.run(list(args), capture_output=True, text=True, env=self.env, timeout=timeout, cwd=self.tmp)
        if check and r.returncode != 0:
            self.fail(f"{' '.join(args)}: exit {r.returncode}: {r.stderr.strip()}")
        return r

    def logs(self):
        out = []
        for name in sorted(os.listdir(self.tmp)):
            if name.endswith((".log", ".out")):
                with open(os.path.join(self.tmp, name), errors="replace") as fh:
                    out.append(f"--- {name} (last lines)\n" + "".join(fh.readlines()[-15:]))
        return "\n".join(out)

    def fail(self, msg):
        fail(f"{msg}\n{self.logs()}")

    def spawn(self, name, *args):
        log = open(os.path.join(self.tmp, f"{name}.out"), "w")
        self.procs.append((name, subprocess.Popen(list(args), stdout=log, stderr=subprocess.STDOUT, env=self.env,
                                                  cwd=self.tmp)))

    def start(self):
        t = self.tmp
        os.chmod(t, 0o755)  # munged wants every directory above its socket searchable by all
        for d in ("state", "spool"):
            os.mkdir(os.path.join(t, d))
        key = os.path.join(t, "munge.key")
        with open(key, "wb") as fh:
            fh.write(os.urandom(1024))
        os.chmod(key, 0o400)
        sock = os.path.join(t, "munge.sock")
        self.spawn("munged", find_program("munged"), "--foreground", f"--key-file={key}", f"--socket={sock}",
                   f"--pid-file={t}/munged.pid", f"--log-file={t}/munged.log", f"--seed-file={t}/munged.seed")
        for _ in range(100):
            if os.path.exists(sock):
                break
            self.check_running()
            time.sleep(0.1)
        else:
            self.fail("munged did not create its socket in 10 s")

        # The node as slurmd sees this machine (CPUs, sockets, cores, memory), named localhost.
        hw = subprocess.run([find_program("slurmd"), "-C"], capture_output=True, text=True).stdout
        fields = dict(re.findall(r"(\w+)=(\S+)", hw.splitlines()[0] if hw else ""))
        node = " ".join(f"{k}={fields[k]}" for k in ("CPUs", "Boards", "SocketsPerBoard", "CoresPerSocket",
                                                     "ThreadsPerCore", "RealMemory") if k in fields)
        user = getpass.getuser()
        ctld_port, slurmd_port = free_ports(2)
        with open(self.conf, "w") as fh:
            fh.write(f"""# A private one-node cluster for animorph's farm test.
ClusterName=animorphtest
SlurmctldHost=localhost
SlurmUser={user}
SlurmdUser={user}
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={sock}
StateSaveLocation={t}/state
SlurmdSpoolDir={t}/spool
SlurmctldPidFile={t}/slurmctld.pid
SlurmdPidFile={t}/slurmd.pid
SlurmctldLogFile={t}/slurmctld.log
SlurmdLogFile={t}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
NodeName=localhost {node} State=UNKNOWN
PartitionName=animorph Nodes=localhost Default=YES MaxTime=INFINITE State=UP
""")
        self.spawn("slurmctld", find_program("slurmctld"), "-D", "-f", self.conf)
        self.spawn("slurmd", find_program("slurmd"), "-D", "-N", "localhost", "-f", self.conf)
        deadline = time.monotonic() + 60
        state = ""
        while time.monotonic() < deadline:
            self.check_running()
            state = self.slurm("sinfo", "-h", "-o", "%T", check=False).stdout.strip()
            if state == "idle":
                return
            time.sleep(0.3)
        self.fail(f"the node is not idle after 60 s (sinfo: {state!r})")

    def check_running(self):
        for name, p in self.procs:
            if p.poll() is not None:
                self.fail(f"{name} exited with status {p.returncode}")

    def job(self, job_id):
        """(JobState, Reason) of a job."""
        out = self.slurm("scontrol", "show", "job", "-o", job_id).stdout
        state = re.search(r"JobState=(\S+)", out)
        reason = re.search(r"Reason=(\S+)", out)
        return (state.group(1) if state else "?", reason.group(1) if reason else "")

    def stop(self):
        if os.path.exists(self.conf) and any(p.poll() is None for n, p in self.procs if n == "slurmctld"):
            ids = self.slurm("squeue", "-h", "-o", "%A", check=False).stdout.split()
            if ids:
                self.slurm("scancel", *ids, check=False)
                for _ in range(50):
                    if not self.slurm("squeue", "-h", check=False).stdout.strip():
                        break
                    time.sleep(0.1)
        for name, p in reversed(self.procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        # Job steps (slurmstepd and what it ran) that outlived slurmd: by the marker in their environment.
        marker = f"ANIMORPH_SLURM_TEST={self.tmp}".encode()
        for pid in filter(str.isdigit, os.listdir("/proc")):
            if int(pid) == os.getpid():
                continue
            try:
                with open(f"/proc/{pid}/environ", "rb") as fh:
                    if marker in fh.read().split(b"\0"):
                        os.kill(int(pid), signal.SIGKILL)
            except OSError:
                pass
        # Reap what the daemons left to this process (the subreaper, see main): at most 5 s.
        for _ in range(50):
            try:
                if os.waitpid(-1, os.WNOHANG) == (0, 0):
                    time.sleep(0.1)
            except ChildProcessError:
                break


def frame_meshes(path):
    """{frame node name: (positions, normals, indices)} of an animated glTF written by bake."""
    doc, binary = read_glb(path)
    meshes = {}
    for node in doc["nodes"]:
        if not re.fullmatch(r"demo_\d{4}", node.get("name", "")):
            continue
        if "mesh" not in node:
            meshes[node["name"]] = ([], [], [])
            continue
        prim = doc["meshes"][node["mesh"]]["primitives"][0]
        meshes[node["name"]] = (accessor_values(doc, binary, prim["attributes"]["POSITION"]),
                                accessor_values(doc, binary, prim["attributes"]["NORMAL"]),
                                [i[0] for i in accessor_values(doc, binary, prim["indices"])])
    return meshes


def check_plan(cli, project, tmp):
    """farm slurm without --submit: the scripts and the printed commands."""
    out = os.path.join(tmp, "plan")
    r = run(cli, "farm", "slurm", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--chunk", str(CHUNK), "--res",
            RES, "-o", out, "--gltf", os.path.join(tmp, "plan.glb"))
    if r.returncode != 0:
        fail(f"farm slurm (no --submit): exit {r.returncode}: {r.stderr}")
    bake_sh = os.path.join(out, "slurm", "demo_bake.sbatch")
    assemble_sh = os.path.join(out, "slurm", "demo_assemble.sbatch")
    if "submit with:" not in r.stdout or f"sbatch --parsable '{bake_sh}'" not in r.stdout or \
            f"--dependency=afterok:${{jid%%;*}} '{assemble_sh}'" not in r.stdout:
        fail(f"farm slurm printed:\n{r.stdout}")
    exe = os.path.realpath(cli)
    with open(bake_sh) as fh:
        bake = fh.read()
    with open(assemble_sh) as fh:
        assemble = fh.read()
    for text, what in ((bake, "#SBATCH --array=0-2"), (bake, "FIRST=(0 49 98)"), (bake, "LAST=(48 97 144)"),
                       (bake, f"exec '{exe}' bake '{os.path.realpath(project)}'"),
                       (bake, f"'{out}/chunks/demo_0049-0097.glb'"), (bake, f"#SBATCH --output={out}/logs/"),
                       (assemble, f"exec '{exe}' farm assemble '{os.path.realpath(project)}' --frames 0:144 --chunk 49"),
                       (assemble, f"--gltf '{os.path.join(tmp, 'plan.glb')}'")):
        if what not in text:
            fail(f"{what!r} is not in the job script:\n{text}")
    # The assembly before the chunks exist: exit 1 naming the first chunk's file.
    r = run(cli, "farm", "assemble", project, "--frames", "0:144", "--chunk", str(CHUNK), "--chunks",
            os.path.join(out, "chunks"), "--gltf", os.path.join(tmp, "plan.glb"))
    if r.returncode != 1 or os.path.join(out, "chunks", "demo_0000-0048.glb") not in r.stderr or \
            os.path.exists(os.path.join(tmp, "plan.glb")):
        fail(f"farm assemble without chunks: exit {r.returncode}: {r.stderr.strip()}")
    for bad in (["--chunk", "0"], ["--frames", "9:3"], ["--format", "stl"], ["--name", "a b"]):
        args = {"--chunk": "5", "--frames": "0:9", **dict(zip(bad[::2], bad[1::2]))}
        r = run(cli, "farm", "slurm", project, "--res", RES, "-o", os.path.join(tmp, "bad"),
                *[x for kv in args.items() for x in kv])
        if r.returncode != 2 or "farm" not in r.stderr:
            fail(f"farm slurm {bad}: exit {r.returncode}, expected 2 ({r.stderr.strip()})")


def check_farm_run(cli, project, tmp, cluster):
    out = os.path.join(tmp, "farm")
    farm_glb = os.path.join(tmp, "farm.glb")
    t0 = time.monotonic()
    r = subprocess.run([cli, "farm", "slurm", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--chunk", str(CHUNK),
                        "--res", RES, "-o", out, "--gltf", farm_glb, "--submit", "--keep-chunks"],
                       capture_output=True, text=True, env=cluster.env, timeout=60)
    if r.returncode != 0:
        cluster.fail(f"farm slurm --submit: exit {r.returncode}: {r.stdout}{r.stderr}")
    bake_job = re.search(r"submitted bake job (\d+) \(3 array tasks\)", r.stdout)
    assemble_job = re.search(r"submitted assemble job (\d+) \(after job (\d+) succeeded\)", r.stdout)
    if not bake_job or not assemble_job or assemble_job.group(2) != bake_job.group(1):
        cluster.fail(f"farm slurm --submit printed:\n{r.stdout}")
    state, reason = "?", ""
    while time.monotonic() - t0 < WAIT_SEC:
        cluster.check_running()
        state, reason = cluster.job(assemble_job.group(1))
        if state in TERMINAL_STATES or reason == "DependencyNeverSatisfied":
            break
        time.sleep(0.1)
    farm_sec = time.monotonic() - t0
    logs = os.path.join(out, "logs")
    if state != "COMPLETED":
        job_logs = ""
        for name in sorted(os.listdir(logs)) if os.path.isdir(logs) else []:
            with open(os.path.join(logs, name), errors="replace") as fh:
                job_logs += f"--- {name}\n{fh.read()[-2000:]}"
        cluster.fail(f"the assembly job {assemble_job.group(1)} is {state} ({reason}) after {farm_sec:.0f} s\n{job_logs}")
    task_secs = []
    for name in sorted(os.listdir(logs)):
        with open(os.path.join(logs, name)) as fh:
            m = re.search(r"baked frames (\d+)\.\.(\d+) .* in ([0-9.]+) s", fh.read())
        if m:
            task_secs.append((int(m.group(1)), int(m.group(2)), float(m.group(3))))
    if sorted(t[:2] for t in task_secs) != [(0, 48), (49, 97), (98, 144)]:
        fail(f"the task logs in {logs} report the chunks {sorted(t[:2] for t in task_secs)}")
    chunk_files = sorted(os.listdir(os.path.join(out, "chunks")))
    if chunk_files != ["demo_0000-0048.glb", "demo_0049-0097.glb", "demo_0098-0144.glb"]:
        fail(f"--keep-chunks: the assembly job left {chunk_files} in {out}/chunks")
    plys = sorted(f for f in os.listdir(out) if f.endswith(".ply"))
    if plys != [f"demo_{f:04d}.ply" for f in range(FRAMES[0], FRAMES[1] + 1)]:
        fail(f"the chunks wrote {len(plys)} PLY frames into {out}, expected {FRAMES[1] - FRAMES[0] + 1}")
    return farm_glb, farm_sec, task_secs


def check_failed_chunk(cli, project, tmp, cluster):
    """A chunk whose task fails: the assembly never runs (afterok), no glTF is written."""
    out = os.path.join(tmp, "failing")
    os.makedirs(os.path.join(out, "chunks", "demo_0000-0002.glb"))  # a folder where task 0 writes its file
    glb = os.path.join(tmp, "failing.glb")
    r = subprocess.run([cli, "farm", "slurm", project, "--frames", "0:5", "--chunk", "3", "--res", "8", "-o", out,
                        "--format", "none", "--gltf", glb, "--submit"], capture_output=True, text=True,
                       env=cluster.env, timeout=60)
    assemble_job = re.search(r"submitted assemble job (\d+)", r.stdout)
    if r.returncode != 0 or not assemble_job:
        cluster.fail(f"farm slurm --submit: exit {r.returncode}: {r.stdout}{r.stderr}")
    t0 = time.monotonic()
    state, reason = "?", ""
    while time.monotonic() - t0 < 60 and reason != "DependencyNeverSatisfied" and state not in TERMINAL_STATES:
        time.sleep(0.2)
        state, reason = cluster.job(assemble_job.group(1))
    if (state, reason) != ("PENDING", "DependencyNeverSatisfied") or os.path.exists(glb):
        cluster.fail(f"after a failed chunk the assembly job is {state} ({reason}); glTF written: {os.path.exists(glb)}")
    cluster.slurm("scancel", assemble_job.group(1))
    logs = os.path.join(out, "logs")
    task0 = [n for n in os.listdir(logs) if n.endswith("_0.log")]
    with open(os.path.join(logs, task0[0])) as fh:
        if "demo_0000-0002.glb" not in fh.read():
            fail(f"the failed task's log {task0[0]} does not name the chunk it could not write")
    print(f"a failed chunk: the assembly job stays pending (DependencyNeverSatisfied) after {time.monotonic() - t0:.1f} s")


def check_mp4(cli, project, tmp):
    """farm assemble --mp4 over the farm run's chunks: one playblast of the whole range (ffprobe)."""
    mp4 = os.path.join(tmp, "farm.mp4")
    r = run(cli, "farm", "assemble", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--chunk", str(CHUNK),
            "--chunks", os.path.join(tmp, "farm", "chunks"), "--mp4", mp4, "--size", "320x180")
    if r.returncode == 2 and "without the GPU library" in r.stderr:
        print("farm assemble --mp4 not checked: this animorph-cli has no GPU library")
        return
    if r.returncode != 0:
        fail(f"farm assemble --mp4: exit {r.returncode}: {r.stderr}")
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=nb_read_frames,width,height", "-of", "csv=p=0", mp4], capture_output=True, text=True)
    if probe.stdout.strip() != f"320,180,{FRAMES[1] - FRAMES[0] + 1}":
        fail(f"farm assemble --mp4: ffprobe says {probe.stdout.strip()!r} {probe.stderr.strip()}")
    if os.path.exists(os.path.join(tmp, "farm", "chunks")):
        fail("farm assemble without --keep-chunks left the chunks' glTFs behind")


def compare(farm_glb, single_glb):
    farm, single = frame_meshes(farm_glb), frame_meshes(single_glb)
    if sorted(farm) != sorted(single) or len(single) != FRAMES[1] - FRAMES[0] + 1:
        fail(f"frame nodes: farm {len(farm)}, single bake {len(single)}")
    for name in sorted(single):
        (fp, fn, fi), (sp, sn, si) = farm[name], single[name]
        if (len(fp), len(fi)) != (len(sp), len(si)):
            fail(f"{name}: farm {len(fp)} vertices {len(fi)} indices, single bake {len(sp)}, {len(si)}")
        if fp != sp or fi != si:
            fail(f"{name}: positions or indices differ between the farm and the single bake")
        if any(abs(a - b) > 1e-6 for u, v in zip(fn, sn) for a, b in zip(u, v)):
            fail(f"{name}: normals differ by more than 1e-6")
    with open(farm_glb, "rb") as a, open(single_glb, "rb") as b:
        same_bytes = a.read() == b.read()
    verts = sum(len(m[0]) for m in single.values())
    print(f"assembled glTF = single bake: {len(single)} frames, {verts} vertices in all"
          f"{' (the same bytes)' if same_bytes else ''}")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    cli, project = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    missing = [p for p in DAEMONS + CLIENTS if not find_program(p)]
    if missing:
        print(f"SKIPPED: Slurm/MUNGE not installed (missing {', '.join(missing)}); install the Debian packages "
              "slurm-wlm and munge (./run.sh test does)")
        sys.exit(77)
    # Processes the daemons detach (slurmstepd) become children of this one, not of init, so that
    # they are reaped here at the end (PR_SET_CHILD_SUBREAPER).
    ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0)
    # ctest's timeout and Ctrl+C end the test through the finally below.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("stopped by SIGTERM"))
    tmp = tempfile.mkdtemp(prefix="animorph-slurm-")
    cluster = Cluster(tmp)
    try:
        check_plan(cli, project, tmp)
        t0 = time.monotonic()
        cluster.start()
        print(f"cluster up in {time.monotonic() - t0:.1f} s ({tmp})")
        farm_glb, farm_sec, task_secs = check_farm_run(cli, project, tmp, cluster)
        single_glb = os.path.join(tmp, "single.glb")
        t0 = time.monotonic()
        r = run(cli, "bake", project, "--frames", f"{FRAMES[0]}:{FRAMES[1]}", "--res", RES, "--format", "none",
                "--gltf", single_glb)
        single_sec = time.monotonic() - t0
        if r.returncode != 0:
            fail(f"bake --gltf: exit {r.returncode}: {r.stderr}")
        compare(farm_glb, single_glb)
        check_mp4(cli, project, tmp)
        check_failed_chunk(cli, project, tmp, cluster)
        chunks = len(task_secs)
        print(f"farm run: {farm_sec:.2f} s wall from submit to the assembled glTF ({chunks} chunk tasks + assembly; "
              f"the tasks baked for {', '.join(f'{t[2]:.2f}' for t in task_secs)} s)")
        print(f"single bake: {single_sec:.2f} s wall; overhead per chunk {(farm_sec - single_sec) / chunks:.2f} s "
              "(scheduling, process start, loading the project, reading the chunks back; noisy on a shared machine)")
    finally:
        cluster.stop()
        shutil.rmtree(tmp, ignore_errors=True)
    print("OK")


if __name__ == "__main__":
    main()
