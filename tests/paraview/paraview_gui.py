"""Drives the real ParaView GUI (the `paraview` binary, Qt and all) on a private X display, as a
user would see it: the test that the plugin's cloud is drawn in ParaView's own window
(tests/paraview/CMakeLists.txt, paraview.gui.draws_cloud) and the picture of docs/paraview.md
(docs/scripts/make-paraview-image.sh) both run through here.

    paraview_gui.py check WORK_DIR
    paraview_gui.py picture OUTPUT.png WORK_DIR

It starts Xvfb on a free display (-displayfd, so tests running side by side never share one),
gives ParaView a fresh HOME whose settings turn the welcome dialog off (the dialog is modal and
sits over the middle of the render view; ParaView keeps that setting in ParaView5.11.0.ini, not
in ParaView-UserSettings.json), and starts `paraview --script=gui_scene.py`, which loads the
plugin and shows a Cloud Density source as a Cloud Volume. Then it looks at the screen itself
(ImageMagick's `import` of the root window), not at a render ParaView makes for a screenshot:
what is checked is what is on the display.

`check` sets up the scene so that a cloud is easy to tell apart from everything else on screen
(a pure blue background, a yellow cloud) and passes once a cloud-coloured blob fills part of the
middle of the blue render view on several captures in a row and ParaView has printed no error;
it fails when no cloud appears in time, saying what the screen showed and what ParaView reported. `picture` shows the docs'
scene, scrolls the Properties panel to the Cloud Lighting group with xdotool and saves the screen.

Environment: CLOUDVIS_PARAVIEW_PLUGIN (the plugin), PYTHONPATH with ParaView's Python package
(the private prefix, paraview/make-prefix.sh), PARAVIEW (the binary, default `paraview`)."""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import numpy

HERE = os.path.dirname(os.path.abspath(__file__))
SCREEN = (1400, 900)
# The test's scene: ParaView draws the view's background exactly, so the render view is where
# the screen is this blue, and the cloud (yellow, lit by a white sun) is where red and green
# match and stand well above blue. Nothing else in ParaView's window has both.
CHECK_BACKGROUND = (0, 0, 255)
# Long enough for ParaView to start and draw on two busy cores, short enough for ctest.
CHECK_TIMEOUT_S = 50
# Captures one second apart that must all show the cloud.
STEADY_CAPTURES = 5


def fail(message):
    sys.stderr.write("FAIL: %s\n" % message)
    sys.exit(1)


def start_xvfb(work_dir):
    """Xvfb on the first free display; returns (process, ":N")."""
    read_end, write_end = os.pipe()
    log = open(os.path.join(work_dir, "xvfb.log"), "w")
    xvfb = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write_end), "-screen", "0", "%dx%dx24" % SCREEN, "-noreset",
         "-nolisten", "tcp"],
        pass_fds=[write_end], stdout=log, stderr=subprocess.STDOUT)
    os.close(write_end)
    with os.fdopen(read_end) as pipe:
        number = pipe.readline().strip()
    if not number:
        fail("Xvfb did not start (%s)" % os.path.join(work_dir, "xvfb.log"))
    return xvfb, ":" + number


def fresh_home(work_dir):
    """A HOME with no one's ParaView settings but the one that keeps the welcome dialog away."""
    home = os.path.join(work_dir, "home")
    shutil.rmtree(home, ignore_errors=True)
    config = os.path.join(home, ".config", "ParaView")
    os.makedirs(config)
    with open(os.path.join(config, "ParaView5.11.0.ini"), "w") as f:
        f.write("[General]\nGeneralSettings.ShowWelcomeDialog=0\n")
    return home


def start_paraview(work_dir, display, scene):
    """`paraview --script=gui_scene.py` filling the screen; gui_scene.py writes `ready` in
    work_dir once it has shown the cloud."""
    home = fresh_home(work_dir)
    runtime = os.path.join(home, "runtime")
    os.makedirs(runtime, mode=0o700)
    env = dict(os.environ, DISPLAY=display, HOME=home, XDG_RUNTIME_DIR=runtime,
               CLOUDVIS_GUI_SCENE=scene,
               CLOUDVIS_GUI_READY=os.path.join(work_dir, "ready"))
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [env.get("PYTHONPATH"), HERE]))
    log = open(os.path.join(work_dir, "paraview.log"), "w")
    return subprocess.Popen(
        [os.environ.get("PARAVIEW", "paraview"),
         "-qwindowgeometry", "%dx%d+0+0" % SCREEN,
         "--script=" + os.path.join(HERE, "gui_scene.py")],
        env=env, cwd=work_dir, stdout=log, stderr=subprocess.STDOUT)


def capture(display, path):
    """The whole screen into `path` (any format ImageMagick writes: .ppm, .png)."""
    subprocess.run(["import", "-display", display, "-window", "root", "-depth", "8", path],
                   check=True,
                   capture_output=True)


def read_ppm(path):
    """A binary PPM (P6, 8 bits) as a height x width x 3 int array, top row first."""
    with open(path, "rb") as f:
        data = f.read()
    fields = data.split(maxsplit=4)
    if fields[0] != b"P6" or fields[3] != b"255":
        fail("%s is not an 8-bit binary PPM" % path)
    width, height = int(fields[1]), int(fields[2])
    pixels = numpy.frombuffer(fields[4], dtype=numpy.uint8, count=width * height * 3)
    return pixels.reshape(height, width, 3).astype(numpy.int32)


def find_cloud(screen):
    """Where the test's cloud is on the screen: (view box, cloud pixel count, cloud centroid),
    or a reason it is not there."""
    background = numpy.all(screen == CHECK_BACKGROUND, axis=2)
    rows = numpy.flatnonzero(background.any(axis=1))
    columns = numpy.flatnonzero(background.any(axis=0))
    if rows.size == 0 or background.sum() < 10000:
        return "no render view (no area of the view's blue background) on the screen"
    top, bottom, left, right = rows[0], rows[-1] + 1, columns[0], columns[-1] + 1
    view = screen[top:bottom, left:right]
    r, g, b = view[..., 0], view[..., 1], view[..., 2]
    cloud = (numpy.abs(r - g) <= 12) & (r - b >= 40)
    area = cloud.size
    if cloud.sum() < 0.005 * area:
        return "no cloud in the render view (%d x %d at %d,%d): %d cloud pixels" % (
            right - left, bottom - top, left, top, cloud.sum())
    ys, xs = numpy.nonzero(cloud)
    centre = (xs.mean() / cloud.shape[1], ys.mean() / cloud.shape[0])
    if not (0.25 < centre[0] < 0.75 and 0.25 < centre[1] < 0.75):
        return "the cloud's pixels are not around the middle of the view (centre at %.2f, %.2f " \
               "of its width and height)" % centre
    return (left, top, right - left, bottom - top), int(cloud.sum()), centre


def wait_for_ready(work_dir, paraview, timeout):
    """Waits for gui_scene.py's `ready` file. A script that raises leaves the GUI running, so
    its traceback in ParaView's output ends the wait too."""
    ready = os.path.join(work_dir, "ready")
    log = os.path.join(work_dir, "paraview.log")
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        if os.path.exists(ready):
            return True
        if paraview.poll() is not None:
            fail("paraview exited with %d before showing the cloud (%s)" % (
                paraview.returncode, log))
        with open(log, errors="replace") as f:
            output = f.read()
        if "Traceback (most recent call last)" in output:
            fail("gui_scene.py failed in paraview:\n" + output)
        time.sleep(0.5)
    return False


def check(work_dir, display, paraview):
    """Passes once the cloud is on STEADY_CAPTURES screens in a row; fails after
    CHECK_TIMEOUT_S, leaving the last screen as screen.png in work_dir."""
    start = time.monotonic()
    if not wait_for_ready(work_dir, paraview, CHECK_TIMEOUT_S):
        fail("paraview did not run its script within %d s (%s)" % (
            CHECK_TIMEOUT_S, os.path.join(work_dir, "paraview.log")))
    shot = os.path.join(work_dir, "screen.ppm")
    found = "nothing captured"
    seen = 0
    while time.monotonic() - start < CHECK_TIMEOUT_S:
        capture(display, shot)
        found = find_cloud(read_ppm(shot))
        seen = 0 if isinstance(found, str) else seen + 1
        # Seen on several screens in a row: the window settles (its final size, a dialog that
        # opens after the script) in the first seconds.
        if seen == STEADY_CAPTURES:
            errors = paraview_errors(work_dir)
            if errors:
                fail("the cloud is drawn, but ParaView reported errors (its Output Messages "
                     "window):\n" + errors)
            box, count, centre = found
            print("the cloud covers %d pixels of the %d x %d render view at %d,%d "
                  "(centre at %.2f, %.2f), %.0f s after paraview started" % (
                      count, box[2], box[3], box[0], box[1], centre[0], centre[1],
                      time.monotonic() - start))
            return
        time.sleep(1.0)
    capture(display, os.path.join(work_dir, "screen.png"))
    fail("%s after %d s; the screen is in %s\n%s" % (
        found, CHECK_TIMEOUT_S, os.path.join(work_dir, "screen.png"), paraview_errors(work_dir)))


def paraview_errors(work_dir):
    """The errors ParaView printed (VTK's, such as the mapper's refusals, which the GUI also
    shows in its Output Messages window), one a line."""
    with open(os.path.join(work_dir, "paraview.log"), errors="replace") as f:
        # Without loguru's colour codes.
        return "".join(re.sub(r"\x1b\[[0-9;]*m", "", line) for line in f if "ERR|" in line)


def xdotool(display, *args):
    subprocess.run(["xdotool", *args], env=dict(os.environ, DISPLAY=display), check=True)


def drag(display, start, end):
    """A left-button drag, in steps, as Qt's splitters follow a moving mouse."""
    xdotool(display, "mousemove", "--sync", str(start[0]), str(start[1]))
    time.sleep(0.3)
    xdotool(display, "mousedown", "1")
    time.sleep(0.3)
    steps = 5
    for step in range(1, steps + 1):
        x = start[0] + (end[0] - start[0]) * step // steps
        y = start[1] + (end[1] - start[1]) * step // steps
        xdotool(display, "mousemove", "--sync", str(x), str(y))
        time.sleep(0.1)
    xdotool(display, "mouseup", "1")
    time.sleep(0.5)


def picture(work_dir, display, paraview, output):
    """The docs' picture: the left docks made wider and the Properties panel taller (ParaView
    5.11's default layout of a 1400 x 900 window: the docks' splitters at x 295 and y 400), the
    panel scrolled so that the representation and its Cloud Lighting group show together, then
    the screen once the view has settled."""
    if not wait_for_ready(work_dir, paraview, 120):
        fail("paraview did not run its script within 120 s")
    time.sleep(5)  # the window reaching its final size and the view drawn at it
    drag(display, (295, 600), (440, 600))
    drag(display, (150, 400), (150, 250))
    xdotool(display, "mousemove", "200", "700")
    for _ in range(int(os.environ.get("CLOUDVIS_GUI_SCROLL", "1"))):
        xdotool(display, "click", "5")
    xdotool(display, "mousemove", "1399", "899")  # no hover highlight in the picture
    time.sleep(5)  # the view redrawn at its new size, its frames accumulated
    capture(display, output)
    print("wrote %s" % output)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "check":
        mode, output, work_dir = "check", None, sys.argv[2]
    elif len(sys.argv) == 4 and sys.argv[1] == "picture":
        mode, output, work_dir = "picture", os.path.abspath(sys.argv[2]), sys.argv[3]
    else:
        fail("usage: paraview_gui.py check WORK_DIR | picture OUTPUT.png WORK_DIR")
    work_dir = os.path.abspath(work_dir)
    os.makedirs(work_dir, exist_ok=True)
    for stale in ("ready", "screen.ppm", "screen.png"):
        if os.path.exists(os.path.join(work_dir, stale)):
            os.remove(os.path.join(work_dir, stale))
    xvfb, display = start_xvfb(work_dir)
    paraview = None
    try:
        paraview = start_paraview(work_dir, display, mode)
        if mode == "check":
            check(work_dir, display, paraview)
        else:
            picture(work_dir, display, paraview, output)
    finally:
        for process in (paraview, xvfb):
            if process and process.poll() is None:
                process.send_signal(signal.SIGTERM)
                try:
                    process.wait(10)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait()


if __name__ == "__main__":
    main()
