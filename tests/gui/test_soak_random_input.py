"""Soak test: the real editor on the demo project takes random input (clicks, drags, wheel,
shortcut keys) for a bounded time with Vulkan validation on. It must not crash or stop
answering, must quit with zero validation errors, and its memory (RSS) must stay flat after a
warm-up: growth from the end of the warm-up to the end of the run at most
max(64 MiB, 15 % of the warm RSS).

The run lasts ANIMORPH_SOAK_SECONDS (default 60; longer on demand) with random choices from
ANIMORPH_SOAK_SEED (default 21, so the suite repeats the same input; printed, so any run can be
replayed).
Input stays off the menu bar, and Save As / Open are not pressed: the soak must not write or
open files outside its own copy of the demo.

usage: test_soak_random_input.py EDITOR_BIN DEMO_DIR"""
import os
import random
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_driver as g  # noqa: E402

W, H = 1600, 900
MENU_BAR = 30  # pixels at the top that input avoids
KEYS = ["Left", "Right", "Home", "End", "space", "ctrl+z", "ctrl+shift+z", "ctrl+y", "ctrl+s", "ctrl+d",
        "ctrl+g", "f", "e", "p", "Delete", "Escape", "Tab", "Return", "1", "a", "x", "BackSpace"]


def rss_mib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return 0.0


def random_point(rng):
    return rng.randrange(0, W), rng.randrange(MENU_BAR, H)


def act(ed, rng):
    """One random input event (or gesture); returns its description."""
    kind = rng.choices(["click", "drag", "wheel", "key", "move"], weights=[35, 20, 10, 25, 10])[0]
    x, y = random_point(rng)
    if kind == "click":
        button = rng.choices([1, 3, 2], weights=[80, 15, 5])[0]
        ed.move(x, y)
        g.xdo("click", "--repeat", rng.choice([1, 1, 1, 2]), button)
        return f"click {button} at {x},{y}"
    if kind == "drag":
        x1, y1 = random_point(rng)
        button = rng.choices([1, 3, 2], weights=[70, 20, 10])[0]
        mods = rng.choice([(), (), ("shift",), ("ctrl",)])
        for k in mods:
            g.xdo("keydown", k)
        ed.move(x, y)
        g.xdo("mousedown", button)
        for i in range(1, 7):
            ed.move(x + (x1 - x) * i / 6, y + (y1 - y) * i / 6)
        g.xdo("mouseup", button)
        for k in mods:
            g.xdo("keyup", k)
        return f"drag {button}{'+' + '+'.join(mods) if mods else ''} {x},{y} -> {x1},{y1}"
    if kind == "wheel":
        ed.move(x, y)
        g.xdo("click", "--repeat", rng.randrange(1, 5), rng.choice([4, 5]))
        return f"wheel at {x},{y}"
    if kind == "key":
        k = rng.choice(KEYS)
        g.xdo("key", "--clearmodifiers", k)
        return f"key {k}"
    ed.move(x, y)
    return f"move to {x},{y}"


def quit_editor(ed):
    """Quits through the UI (Escape closes popups; Don't Save answers the unsaved-changes prompt):
    Ctrl+Q, or File > Quit when the shortcut does not get through."""
    def click_key(key):
        rect = ed.ui_map().get("widgets", {}).get(key)
        if rect:
            ed.click((rect[0] + rect[2]) / 2, (rect[1] + rect[3]) / 2, wait=False)
        return bool(rect)

    for attempt in range(4):
        for _ in range(3):
            g.xdo("key", "Escape")
        # A modifier the editor still believes held (its key-up lost among the random input) would
        # turn Ctrl+Q into another shortcut: press and release each once.
        for k in ("shift", "ctrl", "alt"):
            g.xdo("key", k)
        if attempt % 2 == 0:
            g.xdo("key", "--clearmodifiers", "ctrl+q")
        elif click_key("menu/File"):
            time.sleep(0.5)
            click_key("menu/Quit")
        end = time.time() + 10
        while time.time() < end and ed.proc.poll() is None:
            click_key("prompt/dont_save")  # clicked as soon as seen: the editor may be gone before a settled map
            time.sleep(0.3)
        if ed.proc.poll() is not None:
            return ed.proc.returncode
        m = ed.ui_map()
        print(f"soak: still running after quit attempt {attempt + 1}: status {m.get('status')!r}, job "
              f"{m.get('job')!r}", flush=True)
    g.fail("the editor does not quit (Ctrl+Q or File > Quit, Don't Save)")


g.ensure_display(sys.argv)
seconds = float(os.environ.get("ANIMORPH_SOAK_SECONDS", "60"))
seed = int(os.environ.get("ANIMORPH_SOAK_SEED", "21"))
print(f"soak: {seconds:.0f} s of random input, seed {seed} (ANIMORPH_SOAK_SEED replays it)", flush=True)
rng = random.Random(seed)
work, project, _ = g.demo_copy(sys.argv[2], "animorph-gui-soak-")
ed = g.Editor(sys.argv[1], project, workdir=work).start()
try:
    frames0 = ed.ui_map().get("frame_count", 0)
    start = time.monotonic()
    warmup = min(20.0, seconds / 3)
    samples = []  # (seconds since start, RSS MiB)
    actions, last_sample, recent = 0, 0.0, []
    while time.monotonic() - start < seconds:
        recent = (recent + [act(ed, rng)])[-8:]
        actions += 1
        time.sleep(rng.uniform(0.01, 0.08))
        if ed.proc.poll() is not None:
            g.fail(f"the editor exited ({ed.proc.returncode}) during the soak; last input: {recent}; "
                   f"log:\n{ed.read_log()}")
        now = time.monotonic() - start
        if now - last_sample >= 1.0:
            samples.append((now, rss_mib(ed.proc.pid)))
            last_sample = now
            # The editor answers: a frame drawn, or idle after taking the input (30 s for a busy one).
            ed.wait_until(lambda m: True, "the editor's UI map", timeout=30)
    elapsed = time.monotonic() - start
    frames = ed.ui_map().get("frame_count", 0) - frames0
    g.check(frames > actions // 4, f"{actions} random inputs in {elapsed:.0f} s without a crash; the editor drew "
                                   f"{frames} frames meanwhile")
    # The editor still answers input: it draws a fresh frame after the soak.
    before = ed.ui_map().get("frame_count", 0)
    ed.move(W // 2, H // 2)
    ed.move(W // 2 + 10, H // 2 + 10)
    ed.wait_until(lambda m: m.get("frame_count", 0) > before or m.get("idle", False), "a frame after the soak", 60)

    warm = [r for t, r in samples if warmup - 5 <= t <= warmup + 5] or [samples[0][1]]
    tail = [r for t, r in samples if t >= elapsed - 10] or [samples[-1][1]]
    warm_rss, end_rss = sorted(warm)[len(warm) // 2], sorted(tail)[len(tail) // 2]
    allowed = max(64.0, 0.15 * warm_rss)
    print("soak: RSS MiB over time: " + ", ".join(f"{t:.0f}s {r:.0f}" for t, r in samples[::5]), flush=True)
    g.check(end_rss - warm_rss <= allowed,
            f"memory is flat after the warm-up: RSS {warm_rss:.0f} MiB at {warmup:.0f} s, {end_rss:.0f} MiB at the "
            f"end (growth {end_rss - warm_rss:+.0f} MiB, at most {allowed:.0f} allowed); peak "
            f"{max(r for _, r in samples):.0f} MiB")
    rc = quit_editor(ed)
    log = ed.read_log()
    g.check(rc == 0 and "Vulkan validation error" not in log,
            f"the editor quits cleanly with zero Vulkan validation errors (exit {rc})")
finally:
    ed.kill()
