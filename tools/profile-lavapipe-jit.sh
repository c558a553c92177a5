#!/bin/bash
# Where lavapipe's time goes inside the polygoniser's compute shaders (docs/gpu-polygonizer.md,
# "Profiling the JIT code"). perf samples the JIT code but cannot name it; with ASLR off the JIT
# lands at the same addresses in every run, so this records a profile, runs the same command
# under gdb to dump the JIT mappings once the pipelines exist, disassembles them and prints the
# samples per JIT function and, for the hottest one, per BUCKET bytes with the dominant
# instructions.
#   tools/profile-lavapipe-jit.sh [RES] [BUCKET]    e.g. tools/profile-lavapipe-jit.sh 128 1024
# Needs perf, gdb, objdump (Debian: linux-perf, gdb, binutils) and a built build/app/animorph-cli.
set -euo pipefail
RES=${1:-128}
BUCKET=${2:-1024}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
CLI=$ROOT/build/app/animorph-cli
OUT=$(mktemp -d /tmp/animorph-jitprof.XXXXXX)
export ANIMORPH_BENCH_GPU_NO_DENSE=1 ANIMORPH_BENCH_GPU_RES=$RES
for tool in perf gdb objdump setarch; do
  command -v $tool > /dev/null || { echo "profile-lavapipe-jit: $tool is missing" >&2; exit 1; }
done
setarch "$(uname -m)" -R perf record -q -o "$OUT/perf.data" "$CLI" bench gpu > /dev/null 2>&1
perf script -i "$OUT/perf.data" -F ip,dso 2> /dev/null | awk '$2 ~ /unknown|perf-/ || NF == 1 {print $1}' > "$OUT/ips.txt"
# gdb disables ASLR too; break in the CPU polygoniser, which the bench runs after the GPU one.
gdb -q -batch -ex "set pagination off" -ex "break animorph::polygonize" -ex run -ex "info proc mappings" \
  -ex kill --args "$CLI" bench gpu 2> /dev/null | awk '$5 == "r-xp" && NF == 5 {print $1, $2}' > "$OUT/regions.txt"
args=(-q -batch -ex "set pagination off" -ex "break animorph::polygonize" -ex run)
i=0
while read -r lo hi; do
  args+=(-ex "dump binary memory $OUT/jit$i.bin $lo $hi")
  i=$((i + 1))
done < "$OUT/regions.txt"
gdb "${args[@]}" -ex kill --args "$CLI" bench gpu > /dev/null 2>&1
i=0
while read -r lo hi; do
  objdump -D -b binary -m i386:x86-64 --adjust-vma="$lo" "$OUT/jit$i.bin" >> "$OUT/jit.asm"
  i=$((i + 1))
done < "$OUT/regions.txt"
python3 - "$OUT" "$BUCKET" <<'PY'
import bisect, collections, re, sys
out, bucket = sys.argv[1], int(sys.argv[2])
ips = collections.Counter(int(l, 16) for l in open(out + "/ips.txt") if l.strip())
ins = []
for l in open(out + "/jit.asm"):
    m = re.match(r"\s*([0-9a-f]+):\s+(?:[0-9a-f]{2} )+\s*(.*)", l)
    if m:
        ins.append((int(m.group(1), 16), m.group(2).strip()))
starts, after_ret = [], True
for a, t in ins:
    mn = t.split()[0] if t else ""
    if after_ret and mn not in ("nop", "nopw", "nopl", "int3", "data16", "cs", "xchg", "(bad)", ""):
        starts.append(a)
        after_ret = False
    if mn in ("ret", "retq"):
        after_ret = True
per_fn = collections.Counter()
for ip, n in ips.items():
    i = bisect.bisect_right(starts, ip) - 1
    if i >= 0:
        per_fn[starts[i]] += n
total = sum(per_fn.values())
print("JIT samples: %d (of %d unnamed)" % (total, sum(ips.values())))
sizes = {a: (starts[j + 1] - a if j + 1 < len(starts) else 0) for j, a in enumerate(starts)}
for a, n in per_fn.most_common(8):
    print("  function %#x, %6d bytes: %5d samples, %4.1f %%" % (a, sizes[a], n, 100.0 * n / max(total, 1)))
hot = per_fn.most_common(1)[0][0]
print("hottest function by %d-byte buckets (samples, running share, dominant instructions):" % bucket)
mix, count = collections.defaultdict(collections.Counter), collections.Counter()
for a, t in ins:
    if hot <= a < hot + sizes[hot]:
        k = (a - hot) // bucket
        mix[k][t.split()[0] if t else "?"] += 1
        count[k] += ips.get(a, 0)
run = 0
for k in sorted(mix):
    run += count[k]
    top = " ".join("%s:%d" % x for x in mix[k].most_common(5))
    print("  +%6x %5d %5.1f %% | %s" % (k * bucket, count[k], 100.0 * run / max(per_fn[hot], 1), top))
print("disassembly and samples: " + out)
PY
