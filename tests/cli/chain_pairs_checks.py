"""Chain pairs by hand from the command line: `correspond --pair / --unpair -o` saves
artist pairs that `correspond --json` then marks (the root rule overridden: the
creature's chest takes the gear's hub, its hips go unmatched); names not in the
rigs are refused naming the option, the joint and the chains there are; a pair
in the file that names no chain is a warning, not a failure; `--auto-all -o`
removes the field again.

usage: chain_pairs_checks.py CLI DEMO_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

cli, demo = sys.argv[1], sys.argv[2]
work = tempfile.mkdtemp(prefix="animorph-cli-chain-pairs-")
for f in ("demo.animorph", "creature.glb", "gear.glb"):
    shutil.copy(os.path.join(demo, f), work)


def run(*args, code=0):
    r = subprocess.run([cli, *args], cwd=work, capture_output=True, text=True, timeout=120)
    if r.returncode != code:
        sys.exit(f"FAIL: {' '.join(args)}: exit {r.returncode}, wanted {code}\n{r.stdout}\n{r.stderr}")
    return r


def chains(project):
    j = json.loads(run("correspond", project, "--json").stdout)
    return j, {c["name"]: c for c in j["source_chains"]}


try:
    before, src = chains("demo.animorph")
    assert before["artist_pairs"] == 0 and not any(c["artist"] for c in src.values()), before
    assert src["hips"]["match"] == 0 and src["chest"]["match"] == -1, src  # the root rule: hips <-> hub

    out = run("correspond", "demo.animorph", "--pair", "chest=hub", "--unpair", "neck", "-o", "paired.animorph").stdout
    assert "[artist; automatic: unmatched]" in out, out
    saved = json.load(open(os.path.join(work, "paired.animorph")))["morph"]["chain_pairs"]
    assert saved == [{"source": "chest", "target": "hub"}, {"source": "neck", "target": None}], saved
    after, src = chains("paired.animorph")
    assert after["artist_pairs"] == 2, after
    assert src["chest"]["match"] == 0 and src["chest"]["artist"] and src["chest"]["automatic"] == -1, src["chest"]
    assert src["hips"]["match"] == -1 and not src["hips"]["artist"], src["hips"]  # the artist's pair wins
    assert src["neck"]["match"] == -1 and src["neck"]["artist"], src["neck"]

    bad = run("correspond", "paired.animorph", "--pair", "chst=hub", "-o", "x.animorph", code=2).stderr
    assert "--pair chst=hub: no source chain starts at joint 'chst' (chains: hips," in bad, bad
    assert not os.path.exists(os.path.join(work, "x.animorph")), "nothing saved on a refused edit"
    bad = run("correspond", "paired.animorph", "--pair", "chest=rim", code=2).stderr
    assert "no target chain starts at joint 'rim' (chains: hub)" in bad, bad

    # A stale name in the file: the project still loads, the pair is ignored with a warning.
    p = json.load(open(os.path.join(work, "paired.animorph")))
    p["morph"]["chain_pairs"].append({"source": "tail9", "target": None})
    json.dump(p, open(os.path.join(work, "stale.animorph"), "w"))
    r = run("correspond", "stale.animorph")
    assert "morph.chain_pairs[2].source: no source chain starts at joint 'tail9': pair ignored" in r.stderr, r.stderr

    run("correspond", "paired.animorph", "--auto-all", "-o", "auto.animorph")
    assert "chain_pairs" not in json.load(open(os.path.join(work, "auto.animorph")))["morph"]
    print("ok: chest=hub and neck unmatched saved and marked, bad names refused, stale names warned, --auto-all clears")
finally:
    shutil.rmtree(work, ignore_errors=True)
