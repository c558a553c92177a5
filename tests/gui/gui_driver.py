"""Drives the real Animorph editor in an X server (Xvfb in tests) with real
input events (xdotool), finds widgets through the map the editor writes when
ANIMORPH_UI_MAP is set, and judges results from screenshots (ImageMagick) and
the saved project. Used by the tests in this folder."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

SCREEN = "1600x900x24"
# Waits for the editor are this many times longer (3 in a sanitizer build, where the editor is slower;
# tests/gui/CMakeLists.txt sets it).
TIMEOUT_SCALE = float(os.environ.get("ANIMORPH_TEST_TIMEOUT_SCALE", "1"))


def ensure_display(argv):
    """Re-runs this script under xvfb-run when there is no X display."""
    if os.environ.get("DISPLAY"):
        return
    if not shutil.which("xvfb-run"):
        print("SKIP: no DISPLAY and no xvfb-run", flush=True)
        sys.exit(77)
    os.execvp("xvfb-run", ["xvfb-run", "-a", "-s", f"-screen 0 {SCREEN}", sys.executable] + argv)


def demo_copy(demo_dir, prefix):
    """A temporary copy of the demo project and its characters: (work dir, project path, its JSON)."""
    work = tempfile.mkdtemp(prefix=prefix)
    for name in ("demo.animorph", "creature.glb", "gear.glb"):
        shutil.copy(os.path.join(demo_dir, name), work)
    project = os.path.join(work, "demo.animorph")
    with open(project) as f:
        return work, project, json.load(f)


def fail(msg):
    print("FAIL: " + msg, flush=True)
    raise SystemExit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print("ok: " + msg, flush=True)


def xdo(*args):
    subprocess.run(["xdotool", *map(str, args)], check=True)


class Editor:
    def __init__(self, editor_bin, project=None, workdir=None, size="1600x900"):
        self.bin = editor_bin
        self.project = project
        self.workdir = workdir or tempfile.mkdtemp(prefix="animorph-gui-")
        self.size = size
        self.map_path = os.path.join(self.workdir, "uimap.json")
        self.log_path = os.path.join(self.workdir, "editor.log")
        self.proc = None
        self.window = None

    def start(self):
        env = dict(os.environ)
        env["XDG_CONFIG_HOME"] = os.path.join(self.workdir, "config")
        env["HOME"] = self.workdir
        env["ANIMORPH_UI_MAP"] = self.map_path
        env.setdefault("ANIMORPH_VALIDATION", "1")
        env.setdefault("VK_ICD_FILENAMES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json")
        args = [self.bin, "--size", self.size]
        if self.project:
            args.append(self.project)
        self.log = open(self.log_path, "w")
        # A map left by an editor started before in the same folder (a reopen) would pass the wait
        # below at once, and the first input would reach a window not drawn yet.
        if os.path.exists(self.map_path):
            os.remove(self.map_path)
        self.proc = subprocess.Popen(args, env=env, stdout=self.log, stderr=subprocess.STDOUT)
        self.wait_until(lambda m: m.get("frame_count", 0) >= 6, "the editor draws frames", timeout=60)
        out = subprocess.run(["xdotool", "search", "--sync", "--name", "^Animorph"], capture_output=True,
                             text=True, timeout=30 * TIMEOUT_SCALE)
        self.window = out.stdout.split()[0]
        xdo("windowfocus", "--sync", self.window)
        return self

    # --- state -----------------------------------------------------------
    def ui_map(self):
        for _ in range(50):
            try:
                with open(self.map_path) as f:
                    return json.load(f)
            except (FileNotFoundError, json.JSONDecodeError):
                if self.proc and self.proc.poll() is not None:
                    fail(f"editor exited with {self.proc.returncode}; log:\n{self.read_log()}")
                time.sleep(0.1)
        return {}

    def fresh_map(self, frames=3):
        """The map as of at least `frames` frames after now, or of the editor gone idle after a frame
        that took its input after now (it draws on demand: idle, it has processed all input; the
        20 ms are for the X server to deliver input sent just before)."""
        t0 = time.monotonic()
        start = self.ui_map().get("frame_count", 0)
        return self.wait_until(lambda m: m.get("frame_count", 0) >= start + frames
                               or (m.get("idle", False) and m.get("polled_at", 0.0) > t0 + 0.02),
                               "the editor draws after the input")

    def wait_until(self, pred, what, timeout=20):
        end = time.time() + timeout * TIMEOUT_SCALE
        m = {}
        while time.time() < end:
            if self.proc and self.proc.poll() is not None:
                fail(f"editor exited with {self.proc.returncode} while waiting for: {what}; log:\n{self.read_log()}")
            if os.path.exists(self.map_path):
                m = self.ui_map()
                if m and pred(m):
                    return m
            time.sleep(0.05)
        fail(f"timed out waiting for: {what}; last map keys: {sorted(m.get('widgets', {}))[:40]}")

    def widget(self, key, timeout=10):
        """The widget's rectangle once its window has settled: a popup is measured on the frame it
        appears and placed on the next, so take it from a map 3 frames after the first that has
        it, or from the idle editor's."""
        first = self.wait_until(lambda m: key in m.get("widgets", {}), f"widget {key}", timeout)
        seen = first.get("frame_count", 0)
        m = self.wait_until(lambda m: key in m.get("widgets", {}) and
                            (m.get("idle", False) or m.get("frame_count", 0) >= seen + 3), f"widget {key} settled", timeout)
        x0, y0, x1, y1 = m["widgets"][key]
        return (x0, y0, x1, y1)

    def center(self, key):
        x0, y0, x1, y1 = self.widget(key)
        return (int((x0 + x1) / 2), int((y0 + y1) / 2))

    # --- input -----------------------------------------------------------
    def move(self, x, y):
        xdo("mousemove", "--window", self.window, int(x), int(y))

    def click(self, x, y, button=1, wait=True):
        """Clicks at window pixel (x, y); wait=False when the click may end the editor."""
        self.move(x, y)
        time.sleep(0.05)
        xdo("click", button)
        if wait:
            self.fresh_map()

    def click_widget(self, key, button=1, wait=True):
        self.click(*self.center(key), button=button, wait=wait)

    def drag(self, x0, y0, x1, y1, button=1, steps=12, modifiers=()):
        for k in modifiers:
            xdo("keydown", k)
        self.move(x0, y0)
        time.sleep(0.05)
        xdo("mousedown", button)
        self.fresh_map(2)
        for i in range(1, steps + 1):
            self.move(x0 + (x1 - x0) * i / steps, y0 + (y1 - y0) * i / steps)
            time.sleep(0.02)
        self.fresh_map(2)
        xdo("mouseup", button)
        for k in modifiers:
            xdo("keyup", k)
        self.fresh_map()

    def key(self, combo):
        xdo("key", "--clearmodifiers", combo)
        self.fresh_map()

    def type_text(self, text):
        xdo("type", "--delay", 20, text)
        self.fresh_map()

    def set_frame(self, frame):
        """Types frame into the timeline's frame field and checks the editor is there."""
        self.click_widget("timeline/frame")
        self.key("ctrl+a")
        self.type_text(str(frame))
        self.key("Return")
        check(self.fresh_map()["current_frame"] == frame, f"the current frame is {frame}")

    # --- output ----------------------------------------------------------
    def screenshot(self, path):
        self.fresh_map()
        subprocess.run(["import", "-window", "root", path], check=True)
        return path

    def read_log(self):
        try:
            with open(self.log_path) as f:
                return f.read()[-4000:]
        except OSError:
            return ""

    def wait_exit(self, timeout=20):
        try:
            return self.proc.wait(timeout=timeout * TIMEOUT_SCALE)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            fail("editor did not exit")

    def kill(self):
        if self.proc and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()


def find_node(node, nid):
    """The node of id nid in a saved BlobTree (JSON) under node, or None."""
    if node["id"] == nid:
        return node
    for c in node.get("children", []):
        r = find_node(c, nid)
        if r:
            return r
    return None


def region_stats(png, x, y, w, h):
    """Mean and standard deviation (0..1) of the grey levels of a region."""
    out = subprocess.run(["convert", png, "-crop", f"{int(w)}x{int(h)}+{int(x)}+{int(y)}", "+repage",
                          "-colorspace", "Gray", "-format", "%[fx:mean] %[fx:standard_deviation]", "info:"],
                         capture_output=True, text=True, check=True)
    mean, sd = out.stdout.split()
    return float(mean), float(sd)


def pixel(png, x, y):
    """(r, g, b) 0..255 of one pixel."""
    out = subprocess.run(["convert", png, "-crop", f"1x1+{int(x)}+{int(y)}", "-depth", "8", "-format",
                          "%[fx:int(255*r)] %[fx:int(255*g)] %[fx:int(255*b)]", "info:"],
                         capture_output=True, text=True, check=True)
    return tuple(int(v) for v in out.stdout.split())


def scene_region(ui_map):
    """(x, y, w, h) of the viewport below its overlay line (camera scheme, frame number, preview
    button: text that changes with the frame): there only the 3D scene is drawn, so pixels that
    differ there are the scene's, not the frame number's."""
    vx, vy, vw, vh = ui_map["viewport"]
    top = vy + 30
    button = ui_map.get("widgets", {}).get("viewport/preview_button")
    if button:
        top = max(top, button[3] + 4)
    return vx, top, vw, vy + vh - top



def hue_counts(png, region):
    """(green, orange, clay, saturated) pixel counts of a region (x, y, w, h) of a screenshot:
    saturated = max - min channel > 40; of those, green: g the largest channel by 25; orange
    (the gear's bronze, warm scales): r > g > b, r - b > 60; clay: the implicit surfaces' default
    blue-grey (b > r + 25, b > g)."""
    x, y, w, h = (int(v) for v in region)
    raw = subprocess.run(["convert", png, "-crop", f"{w}x{h}+{x}+{y}", "+repage", "-depth", "8", "rgb:-"],
                         capture_output=True, check=True).stdout
    green = orange = clay = saturated = 0
    for i in range(0, len(raw) - 2, 3):
        r, gg, b = raw[i], raw[i + 1], raw[i + 2]
        if max(r, gg, b) - min(r, gg, b) <= 40:
            continue
        saturated += 1
        if gg > r + 25 and gg > b + 25:
            green += 1
        elif r > gg > b and r - b > 60:
            orange += 1
        elif b > r + 25 and b > gg:
            clay += 1
    return green, orange, clay, saturated

def differing_pixels(png_a, png_b, x, y, w, h, fuzz="3%"):
    """Number of pixels of a region that differ between two screenshots."""
    crop = f"{int(w)}x{int(h)}+{int(x)}+{int(y)}"
    out = subprocess.run(["compare", "-metric", "AE", "-fuzz", fuzz, f"{png_a}[{crop}]", f"{png_b}[{crop}]",
                          "null:"], capture_output=True, text=True)
    return int(float(out.stderr.split()[0]))


# --- drag and drop from a "file manager" (XDND, the X drag-and-drop protocol) ---------------------
# xdotool cannot drop files, so this is a minimal XDND source over libX11 (ctypes): it offers
# text/uri-list, sends Enter / Position / Drop to the target window and answers the target's
# request for the data, as a file manager does.
def drop_files(target_window, paths, x, y, timeout=10.0):
    import ctypes
    import ctypes.util
    from urllib.parse import quote

    x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XInternAtom.restype = ctypes.c_ulong
    x11.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
    x11.XDefaultRootWindow.restype = ctypes.c_ulong
    x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
    x11.XCreateSimpleWindow.restype = ctypes.c_ulong
    x11.XCreateSimpleWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong] + [ctypes.c_int] * 4 + [ctypes.c_uint,
                                                                                               ctypes.c_ulong,
                                                                                               ctypes.c_ulong]
    x11.XSetSelectionOwner.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong]
    x11.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long, ctypes.c_void_p]
    x11.XChangeProperty.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_int,
                                    ctypes.c_int, ctypes.c_char_p, ctypes.c_int]
    x11.XPending.argtypes = [ctypes.c_void_p]
    x11.XNextEvent.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
    x11.XFlush.argtypes = [ctypes.c_void_p]
    x11.XDestroyWindow.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]

    class ClientMessage(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                    ("display", ctypes.c_void_p), ("window", ctypes.c_ulong), ("message_type", ctypes.c_ulong),
                    ("format", ctypes.c_int), ("l", ctypes.c_long * 5)]

    class SelectionRequest(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                    ("display", ctypes.c_void_p), ("owner", ctypes.c_ulong), ("requestor", ctypes.c_ulong),
                    ("selection", ctypes.c_ulong), ("target", ctypes.c_ulong), ("property", ctypes.c_ulong),
                    ("time", ctypes.c_ulong)]

    class SelectionNotify(ctypes.Structure):
        _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                    ("display", ctypes.c_void_p), ("requestor", ctypes.c_ulong), ("selection", ctypes.c_ulong),
                    ("target", ctypes.c_ulong), ("property", ctypes.c_ulong), ("time", ctypes.c_ulong)]

    class XEvent(ctypes.Union):
        _fields_ = [("type", ctypes.c_int), ("client", ClientMessage), ("request", SelectionRequest),
                    ("notify", SelectionNotify), ("pad", ctypes.c_long * 24)]

    CLIENT_MESSAGE, SELECTION_REQUEST, SELECTION_NOTIFY = 33, 30, 31
    dpy = x11.XOpenDisplay(None)
    if not dpy:
        fail("drop_files: cannot open the display")
    atom = lambda name: x11.XInternAtom(dpy, name.encode(), 0)  # noqa: E731
    enter, position, status, drop, finished = (atom("Xdnd" + n) for n in ("Enter", "Position", "Status", "Drop",
                                                                           "Finished"))
    selection, uri_list, copy = atom("XdndSelection"), atom("text/uri-list"), atom("XdndActionCopy")
    target = int(target_window)
    source = x11.XCreateSimpleWindow(dpy, x11.XDefaultRootWindow(dpy), 0, 0, 1, 1, 0, 0, 0)
    x11.XSetSelectionOwner(dpy, selection, source, 0)
    data = "".join("file://" + quote(os.path.abspath(p)) + "\r\n" for p in paths).encode()

    def send(message_type, l1=0, l2=0, l3=0, l4=0):
        ev = XEvent()
        ev.client.type = CLIENT_MESSAGE
        ev.client.window = target
        ev.client.message_type = message_type
        ev.client.format = 32
        ev.client.l[:] = [source, l1, l2, l3, l4]
        x11.XSendEvent(dpy, target, 0, 0, ctypes.byref(ev))
        x11.XFlush(dpy)

    def wait_for(message_type):
        end = time.time() + timeout
        ev = XEvent()
        while time.time() < end:
            while x11.XPending(dpy):
                x11.XNextEvent(dpy, ctypes.byref(ev))
                if ev.type == CLIENT_MESSAGE and ev.client.message_type == message_type:
                    return ev.client
                if ev.type == SELECTION_REQUEST:  # the target asks for the files: put them on its window
                    r = ev.request
                    x11.XChangeProperty(dpy, r.requestor, r.property, r.target, 8, 0, data, len(data))
                    reply = XEvent()
                    reply.notify.type = SELECTION_NOTIFY
                    reply.notify.requestor, reply.notify.selection = r.requestor, r.selection
                    reply.notify.target, reply.notify.property, reply.notify.time = r.target, r.property, r.time
                    x11.XSendEvent(dpy, r.requestor, 0, 0, ctypes.byref(reply))
                    x11.XFlush(dpy)
            time.sleep(0.01)
        fail(f"drop_files: no {message_type} from the editor within {timeout} s")

    try:
        send(enter, 5 << 24, uri_list)
        send(position, 0, (int(x) << 16) | int(y), 0, copy)
        st = wait_for(status)
        check(st.l[1] & 1, "the editor accepts the dragged files (XdndStatus)")
        send(drop, 0, 0)
        wait_for(finished)
    finally:
        x11.XDestroyWindow(dpy, source)
        x11.XCloseDisplay(dpy)
