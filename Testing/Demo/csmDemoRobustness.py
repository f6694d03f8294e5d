# SPDX-License-Identifier: BSD-3-Clause
"""csm-demo against damaged and hostile input.

    python3 csmDemoRobustness.py <csm-demo> <temp dir> <case> [osmesa|glx]

Each broken case writes its file into <temp dir>, runs csm-demo on it with a timeout and
checks: exit status 2 (not a crash signal, not a timeout), exactly one line on stderr, starting
with "csm-demo: error:" and naming what is wrong. The "tiny" case checks a model of half-size
1e-6 is drawn; "keys_technique" presses the window's keys offscreen (VTK's shadow pass and
back) and checks VTK reports nothing. The last argument says how csm-demo renders --offscreen: "osmesa" (built with
the OSMesa window: no X display needed, only the interactive window needs one) or "glx" (the
default: every run needs a display). Prints "FAIL: ..." and exits 1 on failure.
"""
import os
import struct
import subprocess
import sys
import zlib

demo, tmp, case = sys.argv[1], sys.argv[2], sys.argv[3]
osmesa = len(sys.argv) > 4 and sys.argv[4] == "osmesa"
NO_DISPLAY = {k: v for k, v in os.environ.items() if k != "DISPLAY"}
os.makedirs(tmp, exist_ok=True)
TIMEOUT = 60


def path(name):
    return os.path.join(tmp, name)


def write(name, data):
    with open(path(name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())
    return path(name)


def binary_ply(points, faces):
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\n"
              "property float y\nproperty float z\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (len(points), len(faces)))
    body = b"".join(struct.pack("<3f", *p) for p in points)
    body += b"".join(struct.pack("<B3i", 3, *f) for f in faces)
    return header.encode() + body


def run(args, env=None):
    try:
        p = subprocess.run([demo] + args, capture_output=True, timeout=TIMEOUT, env=env)
    except subprocess.TimeoutExpired:
        return None, "", ""
    return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")


def expect_error(args, words, env=None):
    rc, out, err = run(args, env)
    lines = [l for l in err.splitlines() if l.strip()]
    if rc is None:
        return "timed out after %d s" % TIMEOUT
    if rc < 0 or rc >= 128:
        return "killed by signal (status %d); stderr: %s" % (rc, err[:300])
    if rc == 0:
        return "exit status 0; stdout: %s" % out[:300]
    if len(lines) != 1 or not lines[0].startswith("csm-demo: error: "):
        return "expected one error line, got %d: %s" % (len(lines), err[:300])
    for w in words:
        if w not in lines[0]:
            return "the message does not say '%s': %s" % (w, lines[0])
    print("ok: status %d: %s" % (rc, lines[0]))
    return None


def read_png(file):
    """8-bit RGB(A) PNG (what vtkPNGWriter writes) -> rows of pixel tuples."""
    data = open(file, "rb").read()
    pos, idat, width, height, channels = 8, b"", 0, 0, 3
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", chunk[:10])
            channels = {2: 3, 6: 4}[colour]
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + length
    raw, stride, rows, prev = zlib.decompress(idat), width * channels, [], bytearray(width * channels)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b, c = prev[i], prev[i - channels] if i >= channels else 0
            if kind == 1: line[i] = (line[i] + a) & 255
            elif kind == 2: line[i] = (line[i] + b) & 255
            elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        prev = line
    return rows


def drawn_fraction(out):
    background = (191, 209, 229)  # the demo's background (0.75, 0.82, 0.9)
    pixels = [p for row in read_png(out) for p in row]
    drawn = sum(1 for p in pixels if max(abs(x - y) for x, y in zip(p, background)) > 12)
    return drawn, len(pixels)


def binary_stl(triangles):
    body = b"".join(struct.pack("<12fH", 0, 0, 1, i, 0, 0, i + 1, 0, 0, i, 1, 0, 0)
                    for i in range(triangles))
    return b"binary".ljust(80, b"\0") + struct.pack("<I", triangles) + body


def stl_too_long():
    # 20 GB of zeros, sparse (no blocks written): a header of 0 triangles and far too many bytes.
    f = path("too-long.stl")
    with open(f, "wb") as out:
        out.truncate(20 << 30)
    try:
        return expect_error(["--scene", f, "--offscreen", "--out", path("x.png")],
                            ["too long", "84 bytes (84 + 50 * 0) was expected", "21474836480"])
    finally:
        os.remove(f)


def fifo():
    f = path("pipe.stl")
    if not os.path.exists(f):
        os.mkfifo(f)
    return expect_error(["--scene", f, "--offscreen", "--out", path("x.png")],
                        ["pipe.stl", "named pipe", "not a regular file"])


def out_unwritable():
    # Found before the scene is built, not after a render.
    bad = os.path.join(tmp, "no-such-folder", "x.png")
    problem = expect_error(["--offscreen", "--out", bad], ["--out", "no-such-folder", "does not exist"])
    if problem:
        return problem
    _, out, _ = run(["--offscreen", "--out", bad])
    if out.strip():
        return "it did work before refusing the path: %s" % out[:300]
    return expect_error(["--offscreen", "--out", tmp], ["is a directory"])


def triangles_help():
    # One limit: the one --help states is the one the check applies.
    import re
    _, out, _ = run(["--help"])
    _, _, err = run(["--triangles", "1e9"])
    said = re.search(r"--triangles N .*?1000\.\.(\d+)", out)
    checked = re.search(r"--triangles must be in \[1000, (\d+)\]", err)
    if not said or not checked:
        return "no limit in --help or in the refusal: %s / %s" % (out[:200], err[:200])
    if said.group(1) != checked.group(1):
        return "--help says up to %s, the check allows %s" % (said.group(1), checked.group(1))
    print("ok: --triangles up to %s in --help and in the check" % said.group(1))
    return None


def keys_technique():
    # The window's keys, offscreen: p (partition; the interactor style must not also pick and
    # add an outline VTK's pass cannot shade), t to VTK's pass, none, ours again. Dropped pass
    # chains release their resources: VTK says nothing on stderr.
    if not osmesa:
        return "only for a build with the OSMesa window (csm-demo renders through GLX here)"
    out = path("keys.png")
    rc, stdout, err = run(["--offscreen", "--out", out, "--size", "200x150", "--triangles", "20000",
                           "--keys", "pttt"], env=NO_DISPLAY)
    if rc != 0:
        return "--keys pttt: status %s: %s" % (rc, err[:500])
    if err.strip():
        return "--keys pttt: VTK reported: %s" % err[:800]
    if "key t: technique vtk" not in stdout or "key t: technique csm" not in stdout:
        return "--keys pttt did not switch technique: %s" % stdout[:300]
    print("ok: --keys pttt: csm, vtk, none, csm with nothing on stderr")
    return None


def tiny():
    # A tetrahedron of half-size 5e-7 on the demo's ground slab: it was drawn blank.
    s = 1e-6
    f = write("tiny.obj", "v 0 0 0\nv %g 0 0\nv 0 %g 0\nv 0 0 %g\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"
              % (s, s, s))
    for technique in ("none", "csm"):
        out = path("tiny-%s.png" % technique)
        rc, _, err = run(["--scene", f, "--offscreen", "--out", out, "--size", "160x120",
                          "--technique", technique])
        if rc != 0:
            return "tiny model, --technique %s: status %s: %s" % (technique, rc, err[:300])
        drawn, total = drawn_fraction(out)
        if drawn < 0.2 * total:
            return "tiny model, --technique %s: only %d of %d pixels drawn" % (technique, drawn, total)
        print("ok: tiny model, --technique %s: %d of %d pixels drawn" % (technique, drawn, total))
    return None


def offscreen_no_display():
    # Built with the OSMesa window, --offscreen renders with no X display at all.
    if not osmesa:
        return "only for a build with the OSMesa window (csm-demo renders through GLX here)"
    out = path("no-display.png")
    rc, stdout, err = run(["--offscreen", "--out", out, "--size", "200x150", "--triangles", "20000"],
                          env=NO_DISPLAY)
    if rc != 0:
        return "--offscreen without DISPLAY: status %s: %s" % (rc, err[:300])
    drawn, total = drawn_fraction(out)
    if drawn < 0.2 * total:
        return "--offscreen without DISPLAY: only %d of %d pixels drawn" % (drawn, total)
    print("ok: --offscreen without DISPLAY: %d of %d pixels drawn" % (drawn, total))
    # The first image's own time is reported (the large-model measure of Results.md).
    first = [line for line in stdout.splitlines() if line.startswith("first_frame_ms: ")]
    if len(first) != 1 or not float(first[0].split()[1]) > 0.0:
        return "--offscreen: no single positive first_frame_ms line in: %s" % stdout[:300]
    print("ok: %s" % first[0])
    return None


tri = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
def symlink_loop():
    # Two links naming each other: the system's reason, not "no such file".
    for a, b in (("loop-a.ply", "loop-b.ply"), ("loop-b.ply", "loop-a.ply")):
        if os.path.lexists(path(a)):
            os.remove(path(a))
        os.symlink(path(b), path(a))
    return expect_error(["--scene", path("loop-a.ply"), "--offscreen", "--out", path("x.png")],
                        ["Too many levels of symbolic links"])


def light_huge():
    # A direction of huge components is a direction (its length would overflow): it renders.
    rc, out, err = run(["--offscreen", "--light", "1e308,1e308,0", "--out", path("x.png")],
                       NO_DISPLAY if osmesa else None)
    if rc != 0:
        return "exit status %s: %s" % (rc, err[:300])
    print("ok: rendered with --light 1e308,1e308,0")
    return None


cases = {
    "obj_bad_index": lambda: expect_error(
        ["--scene", write("bad-index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999\n"), "--offscreen",
         "--out", path("x.png")], ["bad-index.obj", "point", "3 points"]),
    "vtk_bad_index": lambda: expect_error(
        ["--scene", write("bad-index.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n"
                          "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 99999\n"),
         "--offscreen", "--out", path("x.png")], ["point 99999", "3 points"]),
    "ply_binary_cut": lambda: expect_error(
        ["--scene", write("cut.ply", binary_ply([(i, i % 7, i % 3) for i in range(1000)],
                                                [(i, i + 1, i + 2) for i in range(998)])[:14000]),
         "--offscreen", "--out", path("x.png")], ["cut.ply"]),
    "gltf_no_bin": lambda: expect_error(
        ["--scene", write("no-bin.gltf", '{"asset":{"version":"2.0"},"buffers":[{"uri":"no-bin.bin",'
                          '"byteLength":36}],"meshes":[]}'), "--offscreen", "--out", path("x.png")],
        ["no-bin.bin", "does not exist"]),
    "gltf_bad_json": lambda: expect_error(
        ["--scene", write("bad.gltf", '{"asset": {"version": "2.0"}, "meshes": [ {'), "--offscreen",
         "--out", path("x.png")], ["JSON"]),
    "vtk_huge_points": lambda: expect_error(
        ["--scene", write("huge.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\n"
                          "POINTS 2000000000 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 1 4\n3 0 1 2\n"),
         "--offscreen", "--out", path("x.png")], ["2000000000 points"]),
    "ply_ascii_huge": lambda: expect_error(
        ["--scene", write("huge.ply", "ply\nformat ascii 1.0\nelement vertex 2000000000\n"
                          "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                          "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                          "3 0 1 2\n"), "--offscreen", "--out", path("x.png")], ["2000000000 vertex"]),
    "stl_truncated": lambda: expect_error(
        ["--scene", write("half.stl", binary_stl(100)[:84 + 50 * 50 + 17]), "--offscreen",
         "--out", path("x.png")], ["half.stl", "truncated", "100 triangles", "5084 bytes",
                                   "has 2601", "50 whole triangles"]),
    "stl_too_long": stl_too_long,
    "fifo": fifo,
    "out_unwritable": out_unwritable,
    "triangles_help": triangles_help,
    "keys_technique": keys_technique,
    # CSM_HEADLESS=x turned the OSMesa window off: --offscreen then needs a display too.
    "headless_x_offscreen": lambda: expect_error(
        ["--offscreen", "--out", path("x.png")], ["CSM_HEADLESS=x", "OSMesa window off"],
        env=dict(NO_DISPLAY, CSM_HEADLESS="x")),
    "stl_random": lambda: expect_error(
        ["--scene", write("random.stl", bytes((i * 7919 + 13) * 104729 % 251 for i in range(3000))),
         "--offscreen", "--out", path("x.png")], ["random.stl", "triangles"]),
    "ply_nan_points": lambda: expect_error(
        ["--scene", write("nan.ply", binary_ply(tri + [(float("nan"), 1, 0)], [(0, 1, 2), (0, 1, 3)])),
         "--offscreen", "--out", path("x.png")], ["not finite"]),
    "directory": lambda: expect_error(["--scene", tmp, "--offscreen", "--out", path("x.png")],
                                      ["is a directory"]),
    "symlink_loop": symlink_loop,
    "light_huge": light_huge,
    "range_message": lambda: expect_error(["--darkness", "2"], ["--darkness must be in [0, 1] (see --help)"]),
    "triangles_cap": lambda: expect_error(["--triangles", "5e7"], ["--triangles must be in [1000, "]),
    # The interactive window needs a display; so does --offscreen without the OSMesa window.
    "no_display": lambda: expect_error(
        ["--out", path("x.png")] if osmesa else ["--offscreen", "--out", path("x.png")],
        ["DISPLAY", "xvfb-run -a"] + (["--offscreen", "OSMesa"] if osmesa else []), env=NO_DISPLAY),
    "offscreen_no_display": offscreen_no_display,
    "tiny": tiny,
}
problem = cases[case]()
if problem is None and case in ("range_message",):
    _, _, err = run(["--darkness", "2"])
    if err.count("(see --help)") != 1:
        problem = "'(see --help)' printed %d times: %s" % (err.count("(see --help)"), err)
if problem:
    print("FAIL: %s: %s" % (case, problem))
    sys.exit(1)
