#!/usr/bin/env python3
"""Headless viewer test: starts its own Xvfb, plays a scripted interaction in `bounce view`
(move, flashlight, technique switch, moving an object, panel) and checks the screenshots: none blank, each
differing from the one before where the action should change the picture, in the direction it
should (a flashlight adds light, dropping indirect light removes some), and the round trip back
to the first technique looking like where it started. Also checks the viewer's errors: a bad
script line and a missing display give a clear message and a non-zero exit."""
import argparse
import os
import shutil
import subprocess
import sys
import statistics
import struct
import tempfile
import zlib

W, H = 320, 200


def fail(message):
    print(f"headless_view: FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def start_xvfb():
    xvfb = shutil.which("Xvfb")
    if not xvfb:
        fail("Xvfb not found (scripts/setup.sh installs the xvfb package)")
    read_fd, write_fd = os.pipe()
    # -displayfd: Xvfb picks a free display number and writes it to the pipe once it is ready.
    proc = subprocess.Popen(
        [xvfb, "-displayfd", str(write_fd), "-screen", "0", "1024x768x24", "-nolisten", "tcp"],
        pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_fd)
    with os.fdopen(read_fd) as pipe:
        number = pipe.readline().strip()
    if not number:
        proc.kill()
        fail("Xvfb did not start")
    return proc, ":" + number


def read_png_rgb8(path):
    """Decodes an 8-bit RGB, non-interlaced PNG (what bounce writes) to (width, height, bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail(f"{path} is not a PNG file")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if (depth, colour, interlace) != (8, 2, 0):
                fail(f"{path}: not 8-bit RGB non-interlaced")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * 3
    out = bytearray(stride * height)
    prev = bytearray(stride)
    for y in range(height):
        filt = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b = prev[i]
            c = prev[i - 3] if i >= 3 else 0
            if filt == 1:
                line[i] = (line[i] + a) & 255
            elif filt == 2:
                line[i] = (line[i] + b) & 255
            elif filt == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif filt == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return width, height, bytes(out)


class Shot:
    def __init__(self, path):
        if not os.path.exists(path):
            fail(f"{path} was not written")
        w, h, self.pixels = read_png_rgb8(path)
        if (w, h) != (W, H):
            fail(f"{path}: size {w}x{h}, expected {W}x{H}")

    def mean(self):
        return sum(self.pixels) / (255.0 * len(self.pixels))

    def std(self):
        return statistics.pstdev(self.pixels[::7]) / 255.0


def check_not_blank(name, image):
    if image.std() < 0.02 or image.mean() < 0.02:
        fail(f"{name} looks blank (mean {image.mean():.3f}, std {image.std():.3f})")


def mean_abs_diff(a, b):
    return sum(abs(x - y) for x, y in zip(a.pixels, b.pixels)) / (255.0 * len(a.pixels))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bounce", required=True)
    parser.add_argument("--source", required=True, help="the repository (for scenes/)")
    args = parser.parse_args()
    out = tempfile.mkdtemp(prefix="bounce-view-")
    xvfb, display = start_xvfb()
    try:
        env = dict(os.environ, DISPLAY=display)
        script = os.path.join(out, "actions.txt")
        shot = lambda name: os.path.join(out, name + ".png")
        with open(script, "w") as f:
            f.write(f"""# scripted interaction
ui off
wait 6
screenshot {shot('start')}
move 0 0 0.2        # walk towards the box
turn 8 -3
wait 6
screenshot {shot('moved')}
flashlight on
wait 6
screenshot {shot('flashlight')}
technique direct    # direct light only: indirect light disappears
wait 6
screenshot {shot('direct')}
technique tiled
flashlight off
wait 6
screenshot {shot('back')}
object 6 -0.1 0 0   # slide the short block's front face towards the red wall
wait 3
screenshot {shot('object')}
ui on
wait 1
screenshot {shot('panel')}
""")
        run = subprocess.run(
            [args.bounce, "view", "--script", script, "-W", str(W), "-H", str(H),
             "--target-ms", "0", "--frames", "500"],
            env=env, capture_output=True, text=True, timeout=240)
        if run.returncode != 0:
            fail(f"bounce view exited with {run.returncode}: {run.stderr.strip()}")
        images = {n: Shot(shot(n)) for n in
                  ("start", "moved", "flashlight", "direct", "back", "object", "panel")}
        for name, image in images.items():
            check_not_blank(name, image)
        # Each action changes the picture.
        for a, b in (("start", "moved"), ("moved", "flashlight"), ("flashlight", "direct"),
                     ("direct", "back"), ("back", "object"), ("object", "panel")):
            d = mean_abs_diff(images[a], images[b])
            if d < 0.005:
                fail(f"{a} and {b} are nearly identical (mean difference {d:.4f})")
        # ... in the direction it should.
        if not images["flashlight"].mean() > images["moved"].mean() + 0.005:
            fail("the flashlight did not brighten the view")
        if not images["direct"].mean() < images["flashlight"].mean() - 0.005:
            fail("switching to direct light only did not darken the view")
        # Back to tiled without the flashlight: the same view as 'moved', up to noise.
        if mean_abs_diff(images["back"], images["moved"]) > 0.03:
            fail("after switching back, the view differs from before the flashlight")
        print("headless_view: screenshots " + ", ".join(
            f"{n} mean {i.mean():.3f}" for n, i in images.items()))

        # A dynamic scene: the animation moves the cube and the light between frames, and the
        # camera path moves the view.
        dyn_script = os.path.join(out, "dynamic.txt")
        with open(dyn_script, "w") as f:
            f.write(f"""ui off
wait 2
screenshot {shot('anim_a')}
wait 20
screenshot {shot('anim_b')}
play off
path on
time 2
wait 2
screenshot {shot('path')}
""")
        scene = os.path.join(args.source, "scenes", "dynamic-cornell.bounce.json")
        run = subprocess.run(
            [args.bounce, "view", scene, "--script", dyn_script, "-W", str(W), "-H", str(H),
             "--target-ms", "0"], env=env, capture_output=True, text=True, timeout=240)
        if run.returncode != 0:
            fail(f"bounce view {scene} exited with {run.returncode}: {run.stderr.strip()}")
        dyn = {n: Shot(shot(n)) for n in ("anim_a", "anim_b", "path")}
        for name, image in dyn.items():
            check_not_blank(name, image)
        for a, b in (("anim_a", "anim_b"), ("anim_b", "path")):
            d = mean_abs_diff(dyn[a], dyn[b])
            if d < 0.005:
                fail(f"{a} and {b} are nearly identical (mean difference {d:.4f})")

        # An environment light: turning its map (bright on one side) about +y and raising its
        # strength from the script change the view; the unlit cube alone gets the default sky.
        with open(os.path.join(out, "cube.obj"), "w") as f:
            f.write("v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                    "v 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\n"
                    "f 1 5 8 4\nf 2 3 7 6\n")
        # A flat Radiance file, 4 x 2 texels: bright on the map's left half, dim on its right.
        with open(os.path.join(out, "sky.hdr"), "wb") as f:
            f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n")
            for _ in range(2):
                f.write(bytes([128, 128, 128, 131]) * 2 + bytes([128, 128, 128, 127]) * 2)
        env_scene = os.path.join(out, "sky.bounce.json")
        with open(env_scene, "w") as f:
            f.write('{"models": [{"file": "cube.obj"}], "lights": [{"type": "environment", '
                    '"map": "sky.hdr", "intensity": 0.5}], '
                    '"camera": {"position": [0, 2, -5], "look_at": [0, 0, 0]}}')
        env_script = os.path.join(out, "environment.txt")
        with open(env_script, "w") as f:
            f.write(f"""ui off
wait 2
screenshot {shot('sky_a')}
light 0 rotation 180
wait 2
screenshot {shot('sky_turned')}
light 0 color 1 1 1
wait 2
screenshot {shot('sky_bright')}
""")
        run = subprocess.run(
            [args.bounce, "view", env_scene, "--script", env_script, "-W", str(W), "-H", str(H),
             "--target-ms", "0"], env=env, capture_output=True, text=True, timeout=240)
        if run.returncode != 0:
            fail(f"bounce view {env_scene} exited with {run.returncode}: {run.stderr.strip()}")
        sky = {n: Shot(shot(n)) for n in ("sky_a", "sky_turned", "sky_bright")}
        for name, image in sky.items():
            check_not_blank(name, image)
        d = mean_abs_diff(sky["sky_a"], sky["sky_turned"])
        if d < 0.005:
            fail(f"turning the environment changed nothing (mean difference {d:.4f})")
        if not sky["sky_bright"].mean() > sky["sky_turned"].mean() + 0.005:
            fail("raising the environment's strength did not brighten the view")

        # Speed in motion, quality at rest: with an unreachable frame-time target (1 ms) the
        # internal resolution falls to its floor (1/4) while the camera turns, and returns to
        # the window's size once it stops.
        for name, rest_frames, size in (("turning", 0, f"{W // 4}x{H // 4}"),
                                        ("stopped", 3, f"{W}x{H}")):
            path = os.path.join(out, name + ".txt")
            with open(path, "w") as f:
                f.write("turn 1 0\nwait 1\n" * 12 + (f"wait {rest_frames}\n" if rest_frames else ""))
            run = subprocess.run(
                [args.bounce, "view", "--script", path, "-W", str(W), "-H", str(H),
                 "--target-ms", "1"], env=env, capture_output=True, text=True, timeout=120)
            if run.returncode != 0 or f"at {size}" not in run.stdout:
                fail(f"{name}: expected the last frame at {size}: {run.stdout.strip()} "
                     f"{run.stderr.strip()}")

        # Errors: a bad script line names the file and line; no display is a clear error.
        bad = os.path.join(out, "bad.txt")
        with open(bad, "w") as f:
            f.write("wait 1\njump 3\n")
        run = subprocess.run([args.bounce, "view", "--script", bad], env=env,
                             capture_output=True, text=True, timeout=60)
        if run.returncode == 0 or f"{bad}:2" not in run.stderr or "jump" not in run.stderr:
            fail(f"a bad script gave exit {run.returncode} and message: {run.stderr.strip()}")
        no_display = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        run = subprocess.run([args.bounce, "view", "--frames", "1"], env=no_display,
                             capture_output=True, text=True, timeout=60)
        if run.returncode == 0 or "display" not in run.stderr:
            fail(f"without a display: exit {run.returncode}, message: {run.stderr.strip()}")
    finally:
        xvfb.terminate()
        xvfb.wait(timeout=10)
    shutil.rmtree(out, ignore_errors=True)
    print("headless_view: ok")


if __name__ == "__main__":
    main()
