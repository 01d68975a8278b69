#!/usr/bin/python3
"""Probe every `penumbra` subcommand with hostile input and tabulate what happens.

Usage: /usr/bin/python3 scripts/probe.py [--penumbra PATH] [--jobs N] [--quick] [--seed S]

Probe classes (issue 11): file faults, corrupted EXRs, truncated EXRs, huge
data-window claims, garbage option values, odd output paths, signals during
writes, concurrent writers, OpenCL without a driver, OpenCL with a corrupted
cache, mutated scene JSON. Every case runs in a scratch folder of its own with
a time limit; per class the table counts

  tried    cases run
  clean    the expected outcome: bad input refused with exit 2 and exactly one
           line on stderr (or, where the input may still be valid, exit 0; for
           signals, death by that signal)
  crashed  ended by a signal nobody sent (SIGSEGV, SIGABRT...)
  hung     still running at the time limit (then killed)
  wrong    another exit status (0 or 1 on bad input, "internal error", several
           lines on stderr, a shell command run through --out)
  files    files left behind: temporaries (.NAME.penumbra-tmp-*, or an older
           binary's .NAME.tmp-*), an input changed, a device replaced; after
           SIGKILL, what is left once a second run has written to the same
           folders (the promise of docs/robustness.md: the next run sweeps)

A case can count under several columns (crashed and files, say); `clean`
excludes all the others. Only the standard library is used.
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import random
import resource
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import time

TIMEOUT = 20.0


# --------------------------------------------------------------------------- running


class Case:
    """One run of the tool: arguments, environment, and what would be right."""

    def __init__(self, klass, args, expect=("refuse",), env=None, setup=None, inputs=(), timeout=TIMEOUT,
                 send_signal=None, check=None, parallel=1, then=None):
        self.klass = klass
        self.args = args            # list; "{dir}" is replaced by the scratch folder
        self.expect = expect        # subset of {"refuse", "ok", "signal"}
        self.env = env or {}
        self.setup = setup          # function(scratch) run before
        self.inputs = inputs        # files (relative to scratch) that must not change
        self.timeout = timeout
        self.send_signal = send_signal  # (signal number, delay seconds)
        self.check = check          # function(scratch, stderr) -> problem text or ""
        self.parallel = parallel    # concurrent copies of the same command
        self.then = then            # arguments of a second run, after the first, that must exit 0


MEMORY_LIMIT = 8 << 30


def limit_memory():
    """Caps the child's address space: a binary that allocates what a lying
    header claims (14 GB for 60000^2) must fail alone, not push a shared
    machine into its OOM killer. Such a run then counts as a wrong exit."""
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def subst(value, scratch):
    return value.replace("{dir}", scratch) if isinstance(value, str) else value


def digest(path):
    try:
        with open(path, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()
    except OSError:
        return None


def leftovers(scratch):
    found = []
    for root, dirs, files in os.walk(scratch):
        for name in files + dirs:
            if ".tmp-" in name and name.startswith("."):
                found.append(os.path.join(root, name))
    return found


def run_case(binary, base, case, number):
    scratch = tempfile.mkdtemp(prefix="probe-%d-" % number, dir=base)
    shutil.copytree(os.path.join(base, "inputs"), scratch, dirs_exist_ok=True, symlinks=True)
    if case.setup:
        try:
            case.setup(scratch)
        except OSError as e:  # e.g. an old binary's run left nothing to damage
            return {"class": case.klass, "crashed": False, "hung": False, "wrong": True, "files": False,
                    "detail": "probe setup failed: %s" % e, "args": " ".join(case.args)[:150]}
    before = {p: digest(os.path.join(scratch, p)) for p in case.inputs}
    env = dict(os.environ)
    env.setdefault("PENUMBRA_CACHE_DIR", os.path.join(base, "cache"))
    for key, value in case.env.items():
        value = subst(value, scratch)
        if value is None or value == "":
            env.pop(key, None)
        else:
            env[key] = value
    args = [binary] + [subst(a, scratch) for a in case.args]
    result = {"class": case.klass, "crashed": False, "hung": False, "wrong": False, "files": False, "detail": ""}
    procs = []
    try:
        for _ in range(case.parallel):
            procs.append(subprocess.Popen(args, cwd=scratch, env=env, stdin=subprocess.DEVNULL,
                                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True,
                                          preexec_fn=limit_memory))
        if case.send_signal:
            number_, delay = case.send_signal
            time.sleep(delay)
            for p in procs:
                if p.poll() is None:
                    p.send_signal(number_)
        outcomes = []
        for p in procs:
            try:
                out, err = p.communicate(timeout=case.timeout)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                out, err = p.communicate()
                result["hung"] = True
            outcomes.append((p.returncode, err.decode("utf-8", "replace")))
    finally:
        for p in procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
    for code, err in outcomes:
        classify(case, code, err, result)
    if case.then:
        run_second(binary, case, scratch, env, result)
    if leftovers(scratch):
        result["files"] = True
        result["detail"] += " left: " + ", ".join(os.path.basename(p) for p in leftovers(scratch))
    for path, value in before.items():
        if digest(os.path.join(scratch, path)) != value:
            result["files"] = True
            result["detail"] += " changed input " + path
    for node in ("full", "null"):  # private device nodes, made by device_nodes()
        path = os.path.join(scratch, node)
        if os.path.lexists(path) and not stat.S_ISCHR(os.lstat(path).st_mode):
            result["files"] = True
            result["detail"] += " device %s replaced" % node
    if os.path.exists(os.path.join(scratch, "INJECTED")) or os.path.exists(os.path.join(base, "INJECTED")):
        result["wrong"] = True
        result["detail"] += " shell injection"
    if case.check:
        problem = case.check(scratch, "".join(err for _, err in outcomes))
        if problem:
            result["wrong"] = True
            result["detail"] += " " + problem
    result["args"] = " ".join(a if len(a) < 80 else a[:40] + "..." for a in case.args)
    shutil.rmtree(scratch, ignore_errors=True)
    return result


def run_second(binary, case, scratch, env, result):
    """A later run in the same folders (after SIGKILL: the one that must sweep)."""
    try:
        second = subprocess.run([binary] + [subst(a, scratch) for a in case.then], cwd=scratch, env=env,
                                stdin=subprocess.DEVNULL, capture_output=True, timeout=case.timeout,
                                preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        result["hung"] = True
        return
    if second.returncode != 0:
        result["wrong"] = True
        result["detail"] += " second run exit %d: %s" % (second.returncode, second.stderr.decode("utf-8", "replace")[:160])


def classify(case, code, err, result):
    lines = [l for l in err.split("\n") if l.strip()]
    if result["hung"]:
        return
    if code < 0:
        sent = case.send_signal and -code == case.send_signal[0]
        if sent and "signal" in case.expect:
            return
        result["crashed"] = True
        result["detail"] += " signal %d" % -code
        return
    if code in (134, 139):
        result["crashed"] = True
        result["detail"] += " exit %d" % code
        return
    one_line = len(lines) == 1 and not any("internal error" in l or "Traceback" in l for l in lines)
    if code == 2 and one_line and "refuse" in case.expect:
        return
    if code == 0 and "ok" in case.expect and not any("Traceback" in l for l in lines):
        return
    if "signal" in case.expect and code in (0, 2):
        return  # finished (or refused) before the signal arrived
    result["wrong"] = True
    result["detail"] += " exit %d: %s" % (code, (lines[0] if lines else "(nothing on stderr)")[:160])


# --------------------------------------------------------------------------- inputs


def make_inputs(binary, base):
    inputs = os.path.join(base, "inputs")
    os.makedirs(inputs)
    env = dict(os.environ, PENUMBRA_CACHE_DIR=os.path.join(base, "cache"))
    subprocess.run([binary, "example", "--out", inputs, "--map-size", "64"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    subprocess.run([binary, "render-scene", "contact", "--map-size", "32", "--view-size", "16x12", "--samples", "4",
                    "--shadow-map", os.path.join(inputs, "sm.exr"), "--receivers", os.path.join(inputs, "rx.exr"),
                    "--truth", os.path.join(inputs, "gt.exr")], check=True, env=env, stdout=subprocess.DEVNULL)
    # 1 x 16384 receivers and truth: a header that claims 16384^2 then has an
    # offset table of the right length, so only a size check can catch it.
    subprocess.run([binary, "render-scene", "contact", "--map-size", "8", "--view-size", "1x16384", "--samples", "1",
                    "--shadow-map", os.path.join(inputs, "tall_sm.exr"), "--receivers", os.path.join(inputs, "tall_rx.exr"),
                    "--truth", os.path.join(inputs, "tall_gt.exr")], check=True, env=env, stdout=subprocess.DEVNULL)
    subprocess.run([binary, "sdf-bake", "--scene", "contact", "--out", os.path.join(inputs, "grid.pnsdf"),
                    "--voxel", "0.5"], check=True, env=env, stdout=subprocess.DEVNULL)
    with open(os.path.join(inputs, "scene.json"), "w") as f:
        json.dump(SCENE, f)
    return inputs


SCENE = {
    "name": "probe",
    "map_size": 32,
    "light": {"shape": "rectangle", "center": [0, 5, 0], "normal": [0, -1, 0], "size": [1, 1]},
    "light_camera": {"projection": "perspective", "near": 0.5, "far": 10, "fov_degrees": 60},
    "view": {"position": [0, 3, 4], "target": [0, 0, 0], "fov_degrees": 45},
    "primitives": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
                   {"type": "sphere", "center": [0, 1, 0], "radius": 0.5}],
}

# The commands, each with the option that names an input file and a runnable command line.
SHADE = ["shade", "--method", "vsm", "--shadow-map", "sm.exr", "--receivers", "rx.exr", "--out", "out.exr",
         "--backend", "simd"]
BLUR = ["blur", "--in", "gt.exr", "--guide", "sm_as_guide.exr", "--out", "out.exr", "--backend", "simd"]
SDF_SHADE = ["sdf-shade", "--grid", "grid.pnsdf", "--receivers", "rx.exr", "--out", "out.exr", "--k", "8",
             "--light-position", "0,5,0", "--backend", "simd"]
SDF_SCENE = ["sdf-shade", "--scene", "scene.json", "--receivers", "rx.exr", "--out", "out.exr", "--backend", "simd"]
PISMO_SHADE = ["shade", "--method", "pismo", "--scene", "scene.json", "--receivers", "rx.exr", "--out", "out.exr",
               "--light-level", "0", "--map-size", "8", "--rays", "4", "--backend", "simd"]
SDF_BAKE = ["sdf-bake", "--scene", "scene.json", "--out", "out.pnsdf", "--voxel", "0.5"]
DSM_BUILD = ["dsm-build", "--scene", "scene.json", "--out", "out.exr", "--size", "16", "--samples", "4"]
PISMO_BUILD = ["pismo-build", "--scene", "scene.json", "--out", "pismo", "--light-level", "0", "--map-size", "8"]
RENDER = ["render-scene", "scene.json", "--map-size", "32", "--view-size", "16x12", "--samples", "4",
          "--shadow-map", "o_sm.exr", "--receivers", "o_rx.exr", "--truth", "o_gt.exr"]
EXAMPLE = ["example", "--out", "exdir", "--map-size", "32"]
DEMO = ["demo", "--quick", "--scene", "contact", "--method", "vsm", "--view-size", "8x6", "--samples", "1",
        "--map-size", "32", "--backend", "simd", "--out", "demo"]
INFO = ["info"]


def with_value(command, option, value):
    args = list(command)
    if option in args:
        args[args.index(option) + 1] = value
    else:
        args += [option, value]
    return args


def blur_setup(scratch):
    # blur's guide must match the mask's size: the receivers' depth, as Z.
    shutil.copy(os.path.join(scratch, "gt.exr"), os.path.join(scratch, "sm_as_guide.exr"))
    patch_channel_name(os.path.join(scratch, "sm_as_guide.exr"), b"Y", b"Z")


def patch_channel_name(path, old, new):
    data = bytearray(open(path, "rb").read())
    at = data.find(b"channels\0chlist\0")
    name_at = at + len(b"channels\0chlist\0") + 4
    if data[name_at:name_at + len(old) + 1] == old + b"\0":
        data[name_at:name_at + len(old)] = new
    open(path, "wb").write(bytes(data))


FILE_INPUTS = [  # (command, option, inputs that must stay as they were)
    (SHADE, "--shadow-map"), (SHADE, "--receivers"), (BLUR, "--in"), (BLUR, "--guide"),
    (SDF_SHADE, "--grid"), (SDF_SHADE, "--receivers"), (SDF_SCENE, "--scene"), (SDF_BAKE, "--scene"),
    (DSM_BUILD, "--scene"), (PISMO_BUILD, "--scene"),
]


def file_fault_setups():
    def fifo(s):
        os.mkfifo(os.path.join(s, "fault"))

    def directory(s):
        os.mkdir(os.path.join(s, "fault"))

    def empty(s):
        open(os.path.join(s, "fault"), "w").close()

    def text(s):
        open(os.path.join(s, "fault"), "w").write("not this kind of file\n")

    def loop(s):
        os.symlink("fault", os.path.join(s, "fault"))

    def dangling(s):
        os.symlink("nowhere", os.path.join(s, "fault"))

    def unreadable(s):
        open(os.path.join(s, "fault"), "w").write("x")
        os.chmod(os.path.join(s, "fault"), 0)

    def sparse_huge(s):
        with open(os.path.join(s, "fault"), "wb") as f:
            f.truncate(1 << 31)

    return [("missing", None, "fault"), ("fifo", fifo, "fault"), ("directory", directory, "fault"),
            ("empty", empty, "fault"), ("text", text, "fault"), ("symlink loop", loop, "fault"),
            ("dangling symlink", dangling, "fault"), ("unreadable", unreadable, "fault"),
            ("sparse 2 GiB", sparse_huge, "fault"), ("/dev/zero", None, "/dev/zero"),
            ("/dev/null", None, "/dev/null"), ("5000-char name", None, "n" * 5000),
            ("path through a file", None, "sm.exr/x")]


def combine(*setups):
    def run(scratch):
        for s in setups:
            if s:
                s(scratch)
    return run


def setup_for(command):
    return blur_setup if command and command[0] == "blur" else None


# The files each command reads: an output may not replace them.
INPUTS_OF = {"shade": ("sm.exr", "rx.exr"), "blur": ("gt.exr", "sm_as_guide.exr"), "sdf-shade": ("grid.pnsdf", "rx.exr"),
             "sdf-bake": ("scene.json",), "render-scene": ("scene.json",), "dsm-build": ("scene.json",),
             "pismo-build": ("scene.json",)}


def cases_file_faults(quick):
    cases = []
    for command, option in FILE_INPUTS:
        for label, setup, value in file_fault_setups():
            cases.append(Case("file faults", with_value(command, option, value), setup=combine(setup_for(command), setup)))
    for label, setup, value in file_fault_setups():  # the scene argument of render-scene
        args = list(RENDER)
        args[1] = value
        cases.append(Case("file faults", args, setup=setup))
    return cases


# ---- EXR damage


def exr_setup(name, change):
    def run(scratch):
        path = os.path.join(scratch, name)
        data = bytearray(open(path, "rb").read())
        change(data)
        open(path, "wb").write(bytes(data))
    return run


EXR_TARGETS = [(SHADE, "sm.exr"), (SHADE, "rx.exr"), (BLUR, "gt.exr"), (SDF_SHADE, "rx.exr"), (PISMO_SHADE, "rx.exr")]


def cases_corrupt_exr(quick, rng):
    cases = []
    count = 30 if quick else 120
    for command, name in EXR_TARGETS:
        size = os.path.getsize(os.path.join(BASE, "inputs", name))
        for _ in range(count):
            flips = [(rng.randrange(size), rng.randrange(1, 256)) for _ in range(rng.choice([1, 1, 3, 16]))]

            def change(data, flips=flips):
                for at, mask in flips:
                    data[at] ^= mask
            cases.append(Case("corrupted EXR", command, expect=("refuse", "ok"),
                              setup=combine(setup_for(command), exr_setup(name, change)), inputs=(name,)))
    return cases


def cases_truncated_exr(quick, rng):
    cases = []
    count = 15 if quick else 60
    for command, name in EXR_TARGETS:
        size = os.path.getsize(os.path.join(BASE, "inputs", name))
        for keep in sorted({0, 1, 4, 8, size - 1} | {rng.randrange(size) for _ in range(count)}):
            cases.append(Case("truncated EXR", command,
                              setup=combine(setup_for(command), exr_setup(name, lambda d, k=keep: d.__delitem__(slice(k, None)))),
                              inputs=(name,)))
    return cases


def set_window(data, x_min, y_min, x_max, y_max):
    key = b"dataWindow\0box2i\0"
    at = data.find(key)
    struct.pack_into("<4i", data, at + len(key) + 4, x_min, y_min, x_max, y_max)


def cases_huge_window(quick):
    windows = [(0, 0, 59999, 59999), (0, 0, 99999, 99999), (0, 0, 2**31 - 2, 0), (0, 0, 0, 2**31 - 2),
               (-2**31, -2**31, 2**31 - 1, 2**31 - 1), (0, 0, 16383, 16383), (0, 0, 99999, 11), (0, 0, 127, 127),
               (0, 0, 64 * 2 - 1, 63), (0, 0, 63, 64 * 2 - 1), (5, 5, 4, 4), (0, 0, -1, -1), (0, 0, 3, 3)]
    cases = []
    # 16384 lines with a consistent offset table, claimed 16384 (or 60000) wide.
    tall = [(with_value(SHADE, "--receivers", "tall_rx.exr"), "tall_rx.exr"),
            (with_value(BLUR, "--in", "tall_gt.exr"), "tall_gt.exr"),
            (with_value(SDF_SHADE, "--receivers", "tall_rx.exr"), "tall_rx.exr")]
    for command, name in tall:
        for w in [(0, 0, 16383, 16383), (0, 0, 59999, 16383), (0, 0, 1, 16383), (0, 0, 2**31 - 2, 16383)]:
            for extra in ([], ["--max-pixels", "1000000000000"]):
                cases.append(Case("huge data window", command + extra, timeout=60,
                                  setup=combine(setup_for(command), exr_setup(name, lambda d, w=w: set_window(d, *w))),
                                  inputs=(name,)))
    for command, name in EXR_TARGETS:
        for w in windows:
            cases.append(Case("huge data window", command,
                              setup=combine(setup_for(command), exr_setup(name, lambda d, w=w: set_window(d, *w))),
                              inputs=(name,)))
            cases.append(Case("huge data window", command + ["--max-pixels", "1000000000000"],
                              setup=combine(setup_for(command), exr_setup(name, lambda d, w=w: set_window(d, *w))),
                              inputs=(name,)))
    return cases


# ---- options

COMMANDS = []  # the tool's commands, as `penumbra --help` lists them (tool_commands)


def tool_commands(binary):
    """The command names of `penumbra --help`, which the CLI generates from its
    command table (host/cli/main.cpp, commands()): a command line there is two
    spaces and the name; a summary on a line of its own is indented further."""
    text = subprocess.run([binary, "--help"], check=True, capture_output=True, text=True).stdout
    lines = text.split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("usage:")) + 1
    names = []
    for line in lines[start:]:
        if not line.strip():
            break
        if line.startswith("  ") and not line.startswith("   "):
            names.append(line.split()[0])
    if not names:
        raise SystemExit("probe: `%s --help` lists no commands" % binary)
    return names

GARBAGE = ["", "-1", "0", "nan", "inf", "-inf", "1e999", "abc", "99999999999999999999", "1,2", "0x10", " 3",
           "3 ", "--help", "-", "\u00e9", "1" * 5000, "%s%n", "$(touch INJECTED)"]

VALUED = {
    "shade": (SHADE, ["--method", "--radius", "--min-variance", "--bleed", "--light-size", "--precision", "--backend",
                      "--max-pixels"]),
    "blur": (BLUR, ["--radius", "--spatial-sigma", "--depth-sigma", "--depth-threshold", "--difference", "--window",
                    "--backend"]),
    "sdf-shade": (SDF_SHADE, ["--k", "--light-width", "--light-position", "--t-min", "--t-max", "--max-steps",
                              "--hit-epsilon", "--normal-offset", "--estimate"]),
    "shade --method pismo": (PISMO_SHADE, ["--rays", "--light-level", "--map-size", "--layers", "--pismo-maps"]),
    "sdf-bake": (SDF_BAKE, ["--voxel", "--margin"]),
    "dsm-build": (DSM_BUILD, ["--size", "--samples", "--tolerance", "--filter", "--seed"]),
    "pismo-build": (PISMO_BUILD, ["--light-level", "--map-size", "--layers", "--receivers"]),
    "render-scene": (RENDER, ["--map-size", "--view-size", "--samples"]),
    "example": (EXAMPLE, ["--map-size"]),
    "demo": (DEMO, ["--method", "--scene", "--map-size", "--view-size", "--samples", "--frames", "--backend"]),
}


def cases_garbage_options(quick):
    cases = []
    values = GARBAGE[::3] if quick else GARBAGE
    for name, (command, options) in VALUED.items():
        for option in options:
            for value in values:
                cases.append(Case("garbage options", with_value(command, option, value), expect=("refuse", "ok"),
                                  setup=setup_for(command), timeout=60))
        cases.append(Case("garbage options", command + ["--no-such-option"], setup=setup_for(command)))
        cases.append(Case("garbage options", command[:-1], setup=setup_for(command)))  # the last option, no value
    cases.append(Case("garbage options", [], expect=("refuse",)))
    cases.append(Case("garbage options", ["no-such-command"]))
    for name in COMMANDS:
        cases.append(Case("garbage options", [name, "--out", "x", "--help"], expect=("ok",)))
    return cases


# ---- outputs

def device_nodes(scratch):
    os.mknod(os.path.join(scratch, "full"), 0o666 | stat.S_IFCHR, os.makedev(1, 7))
    os.mknod(os.path.join(scratch, "null"), 0o666 | stat.S_IFCHR, os.makedev(1, 3))


def cases_odd_outputs(quick):
    writers = [(SHADE, "--out"), (BLUR, "--out"), (SDF_SHADE, "--out"), (SDF_BAKE, "--out"), (DSM_BUILD, "--out"),
               (RENDER, "--shadow-map"), (RENDER, "--truth")]
    # The device nodes are private copies of /dev/full and /dev/null in the
    # scratch folder: an old binary replaces what it is given, and replacing the
    # machine's own /dev/null breaks every other process (it did, once).
    odd = ["full", "null", ".", "missing/out.exr", "sm.exr", "rx.exr", "scene.json", "grid.pnsdf",
           "/proc/penumbra.exr", "sm.exr/out.exr", "o" * 5000]
    cases = []
    for command, option in writers:
        inputs = INPUTS_OF[command[0]]
        for value in odd:
            # Another command's input is just a regular file here: replacing it is right.
            harmless = value.endswith((".exr", ".json", ".pnsdf")) and "/" not in value and value not in inputs
            if value in ("full", "null") and os.geteuid() != 0:
                continue  # only root can make device nodes
            setup = combine(setup_for(command), device_nodes if value in ("full", "null") else None)
            cases.append(Case("odd output paths", with_value(command, option, value), setup=setup,
                              inputs=inputs, expect=("ok",) if harmless else ("refuse",)))
    inputs = ("sm.exr", "rx.exr", "scene.json")
    for value in ["sm.exr", "/proc/x", "full", "exdir/q'; touch INJECTED; echo '"]:
        cases.append(Case("odd output paths", with_value(EXAMPLE, "--out", value), inputs=inputs,
                          setup=device_nodes if os.geteuid() == 0 else None,
                          expect=("refuse", "ok") if "INJECTED" in value else ("refuse",)))
    for value in ["sm.exr", "/proc/x", "demo/q'; touch INJECTED; echo '", 'demo/$(touch INJECTED)', "demo/`touch INJECTED`"]:
        cases.append(Case("odd output paths", with_value(DEMO, "--out", value), inputs=inputs,
                          expect=("refuse", "ok") if "INJECTED" in value else ("refuse",), timeout=60))
    # Two outputs the same, an output the same as the scene file.
    args = with_value(RENDER, "--truth", "o_sm.exr")
    cases.append(Case("odd output paths", args, inputs=inputs))
    cases.append(Case("odd output paths", with_value(RENDER, "--truth", "scene.json"), inputs=inputs))

    def hardlink(s):
        os.link(os.path.join(s, "sm.exr"), os.path.join(s, "alias.exr"))
    cases.append(Case("odd output paths", with_value(SHADE, "--out", "alias.exr"), setup=hardlink, inputs=inputs))
    # render-scene must not replace SM and RX when GT cannot be written.
    cases.append(Case("odd output paths", with_value(RENDER, "--truth", "missing/gt.exr"),
                      setup=lambda s: [shutil.copy(os.path.join(s, "sm.exr"), os.path.join(s, n)) for n in ("o_sm.exr", "o_rx.exr")],
                      inputs=inputs + ("o_sm.exr", "o_rx.exr")))
    return cases


# ---- signals and concurrency

def cases_signals(quick, rng):
    # Each writes tens of megabytes for about a second here; beside each, a
    # small run writing to the same folders.
    heavy = [(["example", "--out", "exdir", "--map-size", "8192"], ["example", "--out", "exdir", "--map-size", "16"]),
             (["render-scene", "contact", "--map-size", "4096", "--view-size", "320x240", "--samples", "16",
               "--shadow-map", "o_sm.exr", "--receivers", "o_rx.exr", "--truth", "o_gt.exr"],
              ["render-scene", "contact", "--map-size", "16", "--view-size", "8x6", "--samples", "1",
               "--shadow-map", "o_sm.exr", "--receivers", "o_rx.exr", "--truth", "o_gt.exr"]),
             (["sdf-bake", "--scene", "contact", "--out", "out.pnsdf", "--voxel", "0.01"],
              ["sdf-bake", "--scene", "contact", "--out", "out.pnsdf", "--voxel", "1"])]
    cases = []
    count = 4 if quick else 12
    for command, small in heavy:
        for number in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL, signal.SIGHUP):
            # SIGKILL between naming a run's temporaries and renaming them leaves
            # them (docs/robustness.md); the next run in that folder removes them.
            then = small if number == signal.SIGKILL else None
            for _ in range(count):
                cases.append(Case("signals during writes", command, expect=("signal", "ok"),
                                  send_signal=(number, rng.uniform(0.02, 1.2)), timeout=60, then=then))
    return cases


def valid_exr(path):
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x76\x2f\x31\x01"
    except OSError:
        return False


def cases_concurrent(quick):
    cases = []
    for copies in (2, 4, 8):
        for _ in range(2 if quick else 6):
            cases.append(Case("concurrent writers", SHADE, expect=("ok",), parallel=copies, inputs=("sm.exr",),
                              check=lambda s, e: "" if valid_exr(os.path.join(s, "out.exr")) else "out.exr not an EXR"))
            cases.append(Case("concurrent writers", EXAMPLE, expect=("ok",), parallel=copies,
                              check=lambda s, e: "" if valid_exr(os.path.join(s, "exdir/shadow_map.exr")) else "no map"))
    return cases


# ---- OpenCL

OPENCL_SHADE = with_value(SHADE, "--backend", "opencl")


def cases_opencl_no_driver(quick):
    env = {"OCL_ICD_VENDORS": "{dir}/no-vendors", "OCL_ICD_FILENAMES": ""}
    mk = lambda s: os.mkdir(os.path.join(s, "no-vendors"))
    cases = []
    for command in (OPENCL_SHADE, with_value(BLUR, "--backend", "opencl"), with_value(SDF_SHADE, "--backend", "opencl")):
        cases.append(Case("OpenCL without a driver", command, env=env, setup=combine(setup_for(command), mk)))
        for backend in ("auto", "simd"):
            cases.append(Case("OpenCL without a driver", with_value(command, "--backend", backend), env=env,
                              expect=("ok",), setup=combine(setup_for(command), mk)))
    cases.append(Case("OpenCL without a driver", ["info"], env=env, expect=("ok",), setup=mk))
    cases.append(Case("OpenCL without a driver", ["info", "--json"], env=env, expect=("ok",), setup=mk))
    # An unusable cache folder must not pose as a missing driver.
    for cache in ("{dir}/sm.exr", "/proc/penumbra-cache"):
        cases.append(Case("OpenCL without a driver", OPENCL_SHADE, env={"PENUMBRA_CACHE_DIR": cache, "POCL_CACHE_DIR": ""},
                          check=lambda s, e: "" if "PENUMBRA_CACHE_DIR" in e else "the cache folder is not named"))
    return cases


def damage_pocl(kind, rng):
    def run(scratch):
        shutil.copytree(os.path.join(BASE, "warm-cache"), os.path.join(scratch, "cache"))
        pocl = os.path.join(scratch, "cache", "pocl")
        targets = []
        for root, _, files in os.walk(pocl):
            for name in files:
                if (kind.startswith("bc") and name == "program.bc") or (kind.startswith("so") and name.endswith(".so")):
                    targets.append(os.path.join(root, name))
        for path in targets:
            data = bytearray(open(path, "rb").read())
            if kind == "bc-empty":
                data = bytearray()
            elif kind == "bc-half":
                data = data[:len(data) // 2]
            elif kind == "bc-zero":
                data = bytearray(len(data))
            else:
                for i in range(64, len(data), rng.randrange(50, 400)):
                    data[i] ^= 0x5A
            open(path, "wb").write(bytes(data))
    return run


def cases_opencl_corrupt_cache(quick, rng):
    cases = []
    kinds = ["bc-empty", "bc-half", "bc-zero", "so-flip"]
    for kind in kinds:
        for _ in range(1 if quick else 3):
            cases.append(Case("OpenCL with a corrupted cache", OPENCL_SHADE, expect=("ok",),
                              env={"PENUMBRA_CACHE_DIR": "{dir}/cache", "POCL_CACHE_DIR": ""},
                              setup=damage_pocl(kind, rng), timeout=120))
    return cases


# ---- scene JSON

def mutations(rng, count):
    text = json.dumps(SCENE)
    out = []
    paths = []

    def walk(node, path):
        paths.append(path)
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, path + [k])
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, path + [i])
    walk(SCENE, [])
    odd_values = [None, True, "x", -1, 0, 1e308, -1e308, 1e-320, [], {}, [1, 2], "1e999", 2**63, -2**63, 1e999]
    for _ in range(count):
        scene = json.loads(text)
        kind = rng.randrange(4)
        path = rng.choice(paths[1:])
        parent = scene
        for key in path[:-1]:
            parent = parent[key]
        if kind == 0:
            value = rng.choice(odd_values)
            parent[path[-1]] = value
            body = json.dumps(scene).replace("Infinity", "1e999")
        elif kind == 1:
            if isinstance(parent, dict):
                del parent[path[-1]]
            else:
                parent.pop(path[-1])
            body = json.dumps(scene)
        elif kind == 2:
            body = text[:rng.randrange(len(text))]
        else:
            data = bytearray(text.encode())
            for _ in range(rng.randrange(1, 4)):
                data[rng.randrange(len(data))] = rng.randrange(256)
            body = data.decode("latin-1")
        out.append(body)
    out += ["[" * 100000, "{}", "null", "\"text\"", "{\"name\": \"t\", \"unknown\": 1}", "1e999"]
    return out


def cases_scene_json(quick, rng):
    cases = []
    for body in mutations(rng, 40 if quick else 200):
        def write(s, body=body):
            with open(os.path.join(s, "scene.json"), "w", encoding="latin-1", errors="replace") as f:
                f.write(body)
        command = RENDER if rng.random() < 0.5 else SDF_BAKE
        cases.append(Case("mutated scene JSON", command, expect=("refuse", "ok"), setup=write, inputs=("scene.json",),
                          timeout=60))
    return cases


# --------------------------------------------------------------------------- main

CLASSES = ["file faults", "corrupted EXR", "truncated EXR", "huge data window", "garbage options", "odd output paths",
           "signals during writes", "concurrent writers", "OpenCL without a driver", "OpenCL with a corrupted cache",
           "mutated scene JSON"]


def main():
    global BASE
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--penumbra", default=os.path.join(os.path.dirname(__file__), "..", "build", "penumbra"))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--quick", action="store_true", help="a few hundred cases instead of a few thousand")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--details", type=int, default=3, help="failing cases to print per class")
    parser.add_argument("--memory-gb", type=float, default=8, help="address-space limit per run (GiB)")
    options = parser.parse_args()
    global MEMORY_LIMIT
    MEMORY_LIMIT = int(options.memory_gb * (1 << 30))
    binary = os.path.abspath(options.penumbra)
    rng = random.Random(options.seed)
    BASE = tempfile.mkdtemp(prefix="penumbra-probe-")
    start = time.time()
    try:
        COMMANDS[:] = tool_commands(binary)
        untested = [name for name in COMMANDS if name not in VALUED and name != "info"]  # info: flags only
        if untested:
            print("probe: no option cases for the command(s) %s: add them to VALUED" % ", ".join(untested),
                  file=sys.stderr)
        make_inputs(binary, BASE)
        # A warm OpenCL cache for the corrupted-cache cases (copied into each scratch folder).
        cache = os.path.join(BASE, "warm-cache")
        warm_env = dict(os.environ, PENUMBRA_CACHE_DIR=cache)
        warm_env.pop("POCL_CACHE_DIR", None)
        os.makedirs(cache, exist_ok=True)
        subprocess.run([binary] + OPENCL_SHADE, cwd=os.path.join(BASE, "inputs"), env=warm_env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=300)
        for leftover in ("out.exr",):
            if os.path.exists(os.path.join(BASE, "inputs", leftover)):
                os.remove(os.path.join(BASE, "inputs", leftover))
        cases = (cases_file_faults(options.quick) + cases_corrupt_exr(options.quick, rng) +
                 cases_truncated_exr(options.quick, rng) + cases_huge_window(options.quick) +
                 cases_garbage_options(options.quick) + cases_odd_outputs(options.quick) +
                 cases_signals(options.quick, rng) + cases_concurrent(options.quick) +
                 cases_opencl_no_driver(options.quick) + cases_opencl_corrupt_cache(options.quick, rng) +
                 cases_scene_json(options.quick, rng))
        with concurrent.futures.ThreadPoolExecutor(max_workers=options.jobs) as pool:
            results = list(pool.map(lambda nc: run_case(binary, BASE, nc[1], nc[0]), enumerate(cases)))
    finally:
        shutil.rmtree(BASE, ignore_errors=True)
    print_table(results, options, binary, time.time() - start)
    bad = sum(1 for r in results if r["crashed"] or r["hung"] or r["wrong"] or r["files"])
    return 1 if bad else 0


def print_table(results, options, binary, seconds):
    print("penumbra probe: %s, %d cases, %d jobs, %.0f s, %g GiB address space per run%s" % (
        binary, len(results), options.jobs, seconds, options.memory_gb, ", quick" if options.quick else ""))
    print()
    print("| class | tried | refused cleanly | crashed | hung | wrong exit | files left |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    totals = [0] * 6
    for klass in CLASSES:
        rows = [r for r in results if r["class"] == klass]
        counts = [len(rows),
                  sum(1 for r in rows if not (r["crashed"] or r["hung"] or r["wrong"] or r["files"])),
                  sum(r["crashed"] for r in rows), sum(r["hung"] for r in rows), sum(r["wrong"] for r in rows),
                  sum(r["files"] for r in rows)]
        totals = [a + b for a, b in zip(totals, counts)]
        print("| %s | %s |" % (klass, " | ".join(str(c) for c in counts)))
    print("| **all** | %s |" % " | ".join("**%d**" % c for c in totals))
    print()
    for klass in CLASSES:
        shown = 0
        for r in results:
            if r["class"] == klass and (r["crashed"] or r["hung"] or r["wrong"] or r["files"]) and shown < options.details:
                flags = ",".join(k for k in ("crashed", "hung", "wrong", "files") if r[k])
                print("  %s [%s] %s ->%s" % (klass, flags, r["args"][:150], r["detail"][:200]))
                shown += 1


if __name__ == "__main__":
    sys.exit(main())
