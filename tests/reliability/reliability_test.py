#!/usr/bin/env python3
"""Reliability tests of the bhm executable, run as a user (or a crash, or a full disk) would.

usage: reliability_test.py CASE --bhm BHM --shim LIBFAULT.so --work DIR [--seed N]

Cases (each a ctest entry, "reliability: CASE"):
  kill9         kill -9 at random moments, resume until done: the same run as an uninterrupted one
  busy          a second writer of a run directory is refused naming the owner; SIGINT stops the
                first within a second with its checkpoint named; then the second may resume
  stop-time     Ctrl+C in a generation keeps its time in the checkpoint's elapsed time
  enospc        a full disk (or EIO) injected into write(2) for PNG, frames, replay, VXA, checkpoint,
                video, GIF (inside ffmpeg) and screenshot: exit 1, the system's reason, the old
                file untouched, no "wrote"
  unwritable    --resume into a run directory the user cannot write fails before any simulation
  checkpoint    random byte flips in checkpoint.json: always noticed, the previous one used, and
                the resumed run equals the uninterrupted one; no usable checkpoint says what to
                do; a checkpoint replaced by a folder is refused before any simulation
  replay-fuzz   damaged replays (non-finite and huge sizes, flipped bytes, truncation) through
                bhm render --color strain|displacement: exit 0/1/2/3 only
  mutation-fuzz >= 1000 mutated experiment, body, replay, VXA and measured-track files through
                every subcommand (import, mesh and VTK export of mutated replays, calibrate
                included) and, with --python-module, the Python module's entry points: exit
                0/1/2/3 only, no signal, no sanitizer report, no '[json.exception...]' text;
                calibrate refuses in one line and leaves no output, or writes a report that
                parses and a calibrated experiment that validates

Timings are never asserted except the documented bound of the stop (1 s, with margin for load).
"""
import argparse
import concurrent.futures
import json
import math
import os
import random
import shutil
import signal
import struct
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EXPERIMENT = os.path.join(HERE, "tiny-experiment.json")
BODY = os.path.join(HERE, "tiny-body.json")
TIMING = {"wall_s", "elapsed_s", "sim_wall_s", "checksum"}
SANITIZER_MARKS = ("AddressSanitizer", "runtime error:", "LeakSanitizer", "UndefinedBehaviorSanitizer")

failures = []


def fail(message):
    failures.append(message)
    print("FAIL: " + message, file=sys.stderr)


def check(condition, message):
    if not condition:
        fail(message)
    return condition


class Bhm:
    def __init__(self, path, shim, work, python_module=None):
        self.path, self.shim, self.work = path, shim, work
        self.python_module = python_module  # build/python, where the bhm module is (optional)
        self.python = sys.executable
        self.fuzz_cases = 0  # 0: each fuzz case's own count
        self.env = dict(os.environ)
        self.env.setdefault("GALLIUM_DRIVER", "llvmpipe")
        self.env.setdefault("MESA_SHADER_CACHE_DISABLE", "true")
        # LD_PRELOAD before a sanitizer runtime is fine for this shim.
        self.env["ASAN_OPTIONS"] = self.env.get("ASAN_OPTIONS", "") + ":verify_asan_link_order=0"

    def run(self, args, fault=None, timeout=120, prefix=()):
        env = dict(self.env)
        if fault:
            env["LD_PRELOAD"] = self.shim
            env.update({k: str(v) for k, v in fault.items()})
        try:
            p = subprocess.run(list(prefix) + [self.path] + args, env=env, cwd=self.work,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
            return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")
        except subprocess.TimeoutExpired:
            return None, "", "timeout"

    def run_python(self, args, timeout=60):
        """The Python module's entry points on the same files (PYTHON_CASE below)."""
        env = dict(self.env)
        env["PYTHONPATH"] = self.python_module
        try:
            p = subprocess.run([self.python, "-c", PYTHON_CASE] + args, env=env, cwd=self.work,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=timeout)
            return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")
        except subprocess.TimeoutExpired:
            return None, "", "timeout"

    def start(self, args):
        return subprocess.Popen([self.path] + args, env=self.env, cwd=self.work,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if k not in TIMING}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v


def run_files(d):
    """What must equal between two runs: everything but wall-clock times."""
    lines = open(os.path.join(d, "fitness.csv")).read().splitlines()
    wall = lines[0].split(",").index("wall_s")
    csv = [[c for i, c in enumerate(l.split(",")) if i != wall] for l in lines]
    checkpoint = json.load(open(os.path.join(d, "checkpoint.json")))
    champion = json.load(open(os.path.join(d, "champion.json")))
    return csv, strip(checkpoint), strip(champion)


def fresh(work, name):
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    return d


def evolve_args(d, generations, threads=2):
    return ["evolve", EXPERIMENT, "--out", d, "--generations", str(generations), "--threads",
            str(threads)]


# --- cases -------------------------------------------------------------------------------------

def case_kill9(bhm, rng):
    generations = 7
    slow = json.load(open(EXPERIMENT))
    slow["simulation"]["evaluate_s"] = 0.3  # generations of ~0.1-0.3 s: kills land anywhere
    experiment = os.path.join(bhm.work, "slow.json")
    json.dump(slow, open(experiment, "w"))

    def args(d, resume):
        a = ["evolve", experiment, "--out", d, "--generations", str(generations), "--threads", "2"]
        return a + (["--resume"] if resume else [])

    reference = fresh(bhm.work, "reference")
    started = time.monotonic()
    rc, _, err = bhm.run(args(reference, False))
    if not check(rc == 0, "reference run failed: " + err):
        return
    # Kills land anywhere in the run: up to 0.8 s, or half the uninterrupted run where a loaded
    # machine (or a costlier engine) makes its generations slower than the 0.1-0.3 s planned.
    longest_wait = max(0.8, 0.5 * (time.monotonic() - started))
    expected = run_files(reference)
    kills_total = 0
    for trial in range(3):
        d = fresh(bhm.work, "killed-%d" % trial)
        for attempt in range(60):
            resume = any(os.path.exists(os.path.join(d, f))
                         for f in ("checkpoint.json", "checkpoint.prev.json"))
            p = bhm.start(args(d, resume))
            try:
                p.wait(timeout=rng.uniform(0.05, longest_wait))
            except subprocess.TimeoutExpired:
                p.send_signal(signal.SIGKILL)
                p.wait()
                kills_total += 1
                continue
            err = p.stderr.read().decode(errors="replace")
            if not check(p.returncode == 0, "trial %d: exit %s: %s" % (trial, p.returncode, err)):
                break
            check(run_files(d) == expected, "trial %d: resumed run differs from the reference" % trial)
            break
        else:
            fail("trial %d never finished" % trial)
    print("kill9: 3 trials, %d kills, every resumed run equal to the uninterrupted one" % kills_total)


def case_busy(bhm, rng):
    d = fresh(bhm.work, "busy")
    slow = json.load(open(EXPERIMENT))
    slow["simulation"]["evaluate_s"] = 30.0  # simulations of seconds: the stop lands in one
    slow["simulation"]["record_fps"] = 1.0
    experiment = os.path.join(bhm.work, "busy.json")
    json.dump(slow, open(experiment, "w"))
    first = bhm.start(["evolve", experiment, "--out", d, "--threads", "1"])
    lock = os.path.join(d, "run.lock")
    deadline = time.time() + 30
    while not os.path.exists(lock) and time.time() < deadline:
        time.sleep(0.02)
    if not check(os.path.exists(lock), "no run.lock appeared"):
        first.kill()
        return
    time.sleep(0.3)  # inside generation 0's simulations by now
    for second in (["evolve", experiment, "--out", d], ["evolve", experiment, "--out", d, "--resume"]):
        rc, out, err = bhm.run(second)
        check(rc == 1, "second writer %s: exit %s" % (second[-1], rc))
        check("in use by pid %d on host " % first.pid in err,
              "the refusal does not name the owner: " + err)
    asked = time.time()
    first.send_signal(signal.SIGINT)
    first.wait(timeout=60)
    waited = time.time() - asked
    err = first.stderr.read().decode(errors="replace")
    check(first.returncode == 0, "stopped run exit %s" % first.returncode)
    check(waited < 2.0, "SIGINT took %.2f s to stop a run mid-simulation" % waited)
    check("no generation completed, nothing to resume" in err, "stop message: " + err)
    check(not os.path.exists(lock), "run.lock left behind by a clean stop")
    rc, _, err = bhm.run(evolve_args(d, 2))  # the directory is free again (no checkpoint yet)
    check(rc == 0, "a run after the stop was refused: " + err)
    print("busy: second writers refused naming pid %d; SIGINT stopped a 30 s simulation in %.3f s"
          % (first.pid, waited))


def case_stop_time(bhm, rng):
    """Ctrl+C in the middle of a generation keeps its time on the clock (as the studio's Stop
    does): the checkpoint written at the stop holds the elapsed time up to the signal, so a
    resumed run's clock does not go back to the last complete generation."""
    d = fresh(bhm.work, "stop-time")
    slow = json.load(open(EXPERIMENT))
    slow["simulation"]["evaluate_s"] = STOP_TIME_EVALUATE_S  # generations of a few seconds
    slow["simulation"]["record_fps"] = 1.0
    experiment = os.path.join(bhm.work, "stop-time.json")
    json.dump(slow, open(experiment, "w"))
    started = time.time()
    run = bhm.start(["evolve", experiment, "--out", d, "--threads", "1", "--generations", "100"])
    checkpoint = os.path.join(d, "checkpoint.json")
    deadline = time.time() + 120
    while not os.path.exists(checkpoint) and time.time() < deadline:
        time.sleep(0.02)
    if not check(os.path.exists(checkpoint), "no checkpoint after generation 0"):
        run.kill()
        return
    seen = time.time()
    time.sleep(0.05)  # the rename is atomic; the file we read is whole
    first = json.load(open(checkpoint))["payload"]
    # Well inside generation 1, whatever the machine's speed: 40 % of generation 0's time.
    time.sleep(0.4 * (seen - started))
    signalled = time.time()
    run.send_signal(signal.SIGINT)
    run.wait(timeout=60)
    err = run.stderr.read().decode(errors="replace")
    check(run.returncode == 0, "stopped run exit %s: %s" % (run.returncode, err))
    last = json.load(open(checkpoint))["payload"]
    gen_time = seen - started
    print("stop-time: generation 0 took about %.2f s; checkpoint elapsed %.3f s after it, "
          "%.3f s after the stop %.2f s later" % (gen_time, first["elapsed_s"], last["elapsed_s"],
                                                   signalled - seen))
    check(last["generation"] == first["generation"] or last["elapsed_s"] > first["elapsed_s"],
          "the checkpoint went back")
    # The time from the first checkpoint to the signal is on the clock (less a margin for the
    # moments between the checkpoint's writing and our seeing it).
    check(last["elapsed_s"] >= first["elapsed_s"] + 0.8 * (signalled - seen),
          "Ctrl+C lost the stopped generation's time: elapsed %.3f s, was %.3f s %.2f s before "
          "the signal" % (last["elapsed_s"], first["elapsed_s"], signalled - seen))
    check(last["elapsed_s"] <= first["elapsed_s"] + (signalled - seen) + 1.0,
          "elapsed time larger than the wall time: %.3f s" % last["elapsed_s"])


STOP_TIME_EVALUATE_S = 3.0


def expect_enospc(label, result, before, path, reason="No space left on device"):
    rc, out, err = result
    check(rc == 1, "%s: exit %s (expected 1): %s" % (label, rc, err))
    check(reason in err, "%s: the message lacks the reason '%s': %s" % (label, reason, err))
    check("wrote" not in out, "%s: printed 'wrote' after a failed write" % label)
    if before is not None:
        check(open(path, "rb").read() == before, "%s: the old file was changed" % label)
    check(not os.path.exists(path + ".tmp"), "%s: a temporary was left behind" % label)


def case_enospc(bhm, rng):
    w = bhm.work
    png = os.path.join(w, "good.png")
    render = ["render", EXPERIMENT, "--body", BODY, "--size", "64x48", "--samples", "1"]
    rc, _, err = bhm.run(render + ["--out", png])
    if not check(rc == 0, "render failed: " + err):
        return
    good = open(png, "rb").read()
    expect_enospc("render --out", bhm.run(render + ["--out", png], {"BHM_FAULT_FILE": "good.png"}),
                  good, png)
    expect_enospc("render --out (EIO)",
                  bhm.run(render + ["--out", png], {"BHM_FAULT_FILE": "good.png", "BHM_FAULT_ERRNO": 5}),
                  good, png, "Input/output error")

    sim = fresh(w, "sim")
    rc, _, err = bhm.run(["simulate", EXPERIMENT, "--body", BODY, "--out", sim])
    check(rc == 0, "simulate failed: " + err)
    replay = os.path.join(sim, "replay.bin")
    old_replay = open(replay, "rb").read()
    expect_enospc("simulate replay.bin",
                  bhm.run(["simulate", EXPERIMENT, "--body", BODY, "--out", sim],
                          {"BHM_FAULT_FILE": "replay.bin"}), old_replay, replay)
    frames = fresh(w, "frames")
    expect_enospc("render --frames",
                  bhm.run(["render", EXPERIMENT, "--replay", replay, "--frames", "4", "--out-dir",
                           frames, "--size", "64x48", "--samples", "1"],
                          {"BHM_FAULT_FILE": "frame-", "BHM_FAULT_AFTER": 2}), None,
                  os.path.join(frames, "frame-00002.png"))

    vxa = os.path.join(w, "body.vxa")
    rc, _, _ = bhm.run(["export", EXPERIMENT, "--body", BODY, "--vxa", vxa])
    old_vxa = open(vxa, "rb").read()
    expect_enospc("export --vxa", bhm.run(["export", EXPERIMENT, "--body", BODY, "--vxa", vxa],
                                          {"BHM_FAULT_FILE": "body.vxa"}), old_vxa, vxa)

    # A VTK series replaced by a longer one, the disk full at its third frame (issue 26 N4): the
    # old series stays whole, with no new frame 0 beside it and no staging folder.
    vtk = fresh(w, "vtk")
    rc, _, err = bhm.run(["export", EXPERIMENT, "--body", BODY, "--vtk", vtk])
    if check(rc == 0, "export --vtk failed: " + err):
        old_series = {n: open(os.path.join(vtk, n), "rb").read() for n in os.listdir(vtk)}
        result = bhm.run(["export", EXPERIMENT, "--body", BODY, "--replay", replay, "--vtk", vtk],
                         {"BHM_FAULT_FILE": "frame-00002"})
        expect_enospc("export --vtk", result, None, os.path.join(vtk, "frame-00002.vtu"))
        check("the previous series is unchanged" in result[2], "export --vtk: " + result[2])
        now = {n: open(os.path.join(vtk, n), "rb").read() for n in os.listdir(vtk)}
        check(now == old_series, "export --vtk: the old series was changed: %s" % sorted(now))

    run = fresh(w, "run-enospc")
    rc, _, err = bhm.run(evolve_args(run, 2))
    check(rc == 0, "evolve failed: " + err)
    checkpoint = os.path.join(run, "checkpoint.json")
    old_checkpoint = open(checkpoint, "rb").read()
    expect_enospc("evolve checkpoint", bhm.run(evolve_args(run, 4) + ["--resume"],
                                               {"BHM_FAULT_FILE": "checkpoint.json"}),
                  old_checkpoint, checkpoint)
    check(not os.path.exists(os.path.join(run, "run.lock")), "run.lock left after a failure")
    rc, _, err = bhm.run(evolve_args(run, 4) + ["--resume"])  # the disk has room again
    check(rc == 0, "resume after the full disk failed: " + err)
    reference = fresh(w, "run-reference")
    bhm.run(evolve_args(reference, 4))
    check(run_files(run) == run_files(reference), "the run after a full disk differs")

    # ffmpeg fails in the trailer on a full disk but exits 0 (issue 26 N1): the video is verified
    # before it replaces anything; with --video and --gif together neither is replaced.
    videos = ["render", EXPERIMENT, "--replay", replay, "--size", "64x48", "--samples", "1",
              "--video", os.path.join(w, "good.mp4"), "--gif", os.path.join(w, "good.gif")]
    rc, _, err = bhm.run(videos)
    if check(rc == 0, "render --video --gif failed: " + err):
        old = {n: open(os.path.join(w, n), "rb").read() for n in ("good.mp4", "good.gif")}
        for name, after in (("good.mp4", 0), ("good.mp4", 1), ("good.mp4", 3), ("good.gif", 0)):
            label = "render --video --gif, %s full after %d writes" % (name, after)
            rc, out, err = bhm.run(videos, {"BHM_FAULT_FILE": name, "BHM_FAULT_AFTER": after})
            expect_enospc(label, (rc, out, err), old[name], os.path.join(w, name))
            check(name + ": " in err and "the previous file is unchanged" in err,
                  "%s: the message does not name the file: %s" % (label, err))
            for other in old:
                check(open(os.path.join(w, other), "rb").read() == old[other],
                      "%s: %s was replaced" % (label, other))
                check(not os.path.exists(os.path.join(w, other + ".tmp" + other[-4:])),
                      "%s: a temporary video was left behind" % label)

    shot = os.path.join(w, "shot.png")
    shutil.copy(png, shot)
    expect_enospc("studio --screenshot",
                  bhm.run(["studio", "--headless", "--frames", "1", "--size", "160x120",
                           "--screenshot", shot], {"BHM_FAULT_FILE": "shot.png"}, timeout=120),
                  good, shot)
    print("enospc: render, frames, video, GIF, simulate, export, evolve and studio keep the old "
          "file and exit 1")


def run_as_other_user():
    """A prefix that runs a command as 'nobody' when we are root (root writes anywhere)."""
    if os.geteuid() != 0:
        return ()
    setpriv = shutil.which("setpriv")
    return (setpriv, "--reuid=65534", "--regid=65534", "--clear-groups") if setpriv else None


def case_unwritable(bhm, rng):
    prefix = run_as_other_user()
    if prefix is None:
        print("unwritable: skipped (root without setpriv)")
        return
    d = fresh(bhm.work, "readonly")
    rc, _, err = bhm.run(evolve_args(d, 1))
    check(rc == 0, "evolve failed: " + err)
    for root, dirs, files in os.walk(d):
        os.chmod(root, 0o755 if prefix else 0o555)
        for f in files:
            os.chmod(os.path.join(root, f), 0o644 if prefix else 0o444)
    os.chmod(bhm.work, 0o755)
    rc, out, err = bhm.run(evolve_args(d, 5) + ["--resume"], prefix=prefix)
    os.chmod(d, 0o755)
    check(rc == 1, "resume into an unwritable directory: exit %s: %s" % (rc, err))
    check("not writable" in err, "the message does not say why: " + err)
    check("gen " not in err, "it simulated before failing: " + err)
    print("unwritable: refused before any simulation: " + err.strip().splitlines()[-1])


def case_checkpoint(bhm, rng):
    base = fresh(bhm.work, "ck-base")
    rc, _, err = bhm.run(evolve_args(base, 3))
    if not check(rc == 0, "evolve failed: " + err):
        return
    reference = fresh(bhm.work, "ck-reference")
    bhm.run(evolve_args(reference, 5))
    expected = run_files(reference)
    good = open(os.path.join(base, "checkpoint.json"), "rb").read()
    noticed = 0
    for trial in range(24):
        d = fresh(bhm.work, "ck-%d" % trial)
        shutil.copytree(base, d)
        data = bytearray(good)
        at = rng.randrange(len(data))
        data[at] ^= 1 << rng.randrange(8)
        open(os.path.join(d, "checkpoint.json"), "wb").write(bytes(data))
        full = trial < 3  # a few resumed to the end and compared; the rest only loaded
        rc, _, err = bhm.run(evolve_args(d, 5 if full else 3) + ["--resume"])
        check(rc == 0, "flip at byte %d: exit %s: %s" % (at, rc, err))
        if check(os.path.join(d, "checkpoint.json") in err and "checkpoint.prev.json" in err,
                 "flip at byte %d not noticed: %s" % (at, err)):
            noticed += 1
        if full:
            check(run_files(d) == expected, "flip at byte %d: the resumed run differs" % at)
    print("checkpoint: %d/24 single-bit flips noticed, the previous checkpoint used" % noticed)

    # Both checkpoints unusable: the message says what still works (issue 26).
    d = fresh(bhm.work, "ck-none")
    shutil.copytree(base, d)
    for name in ("checkpoint.json", "checkpoint.prev.json"):
        open(os.path.join(d, name), "w").write("{")
    rc, _, err = bhm.run(evolve_args(d, 5) + ["--resume"])
    check(rc == 1, "no usable checkpoint: exit %s: %s" % (rc, err))
    check("a plain start (without --resume)" in err, "no usable checkpoint: " + err)
    check("json.exception" not in err, "a library's tag reached the user: " + err)
    # checkpoint.json replaced by a folder: refused before any simulation, not a generation later.
    d = fresh(bhm.work, "ck-folder")
    shutil.copytree(base, d)
    os.remove(os.path.join(d, "checkpoint.json"))
    os.mkdir(os.path.join(d, "checkpoint.json"))
    rc, _, err = bhm.run(evolve_args(d, 5) + ["--resume"])
    check(rc == 1, "checkpoint folder: exit %s: %s" % (rc, err))
    check("checkpoint.json: is not a regular file" in err, "checkpoint folder: " + err)
    check("gen " not in err, "checkpoint folder: it simulated before failing: " + err)


# --- fuzzing -----------------------------------------------------------------------------------

INTERESTING = [0, -1, 1, 2, 255, 256, 65536, 2147483647, -2147483648, 4294967296, 1e308, -1e308,
               1e-308, 5e-324, 0.5, -0.0, 1e9, "", "x", None, True, [], {}, [1, 2, 3]]


def mutate_json(text, rng):
    """Either a structural change of one value or raw byte damage."""
    if rng.random() < 0.5:
        try:
            doc = json.loads(text)
        except ValueError:
            doc = None
        if doc is not None:
            paths = []

            def walk(v, path):
                paths.append(path)
                if isinstance(v, dict):
                    for k, x in v.items():
                        walk(x, path + [k])
                elif isinstance(v, list):
                    for i, x in enumerate(v):
                        walk(x, path + [i])
            walk(doc, [])
            path = rng.choice(paths[1:] or [[]])
            parent = doc
            for p in path[:-1]:
                parent = parent[p]
            choice = rng.random()
            if not path:
                return json.dumps(rng.choice(INTERESTING))
            if choice < 0.15 and isinstance(parent, dict):
                del parent[path[-1]]
            elif choice < 0.25 and isinstance(parent, list):
                parent.append(parent[path[-1]])
            else:
                value = rng.choice(INTERESTING)
                if isinstance(parent[path[-1]], (int, float)) and not isinstance(parent[path[-1]], bool) \
                        and rng.random() < 0.5:
                    value = parent[path[-1]] * rng.choice([-1, 0, 2, 10, 1e6, 1e-6])
                parent[path[-1]] = value
            text = json.dumps(doc, allow_nan=True)
            if rng.random() < 0.1:
                text = text.replace("1e+308", rng.choice(["NaN", "Infinity", "-Infinity", "1e999"]))
            return text
    return mutate_bytes(text.encode(), rng).decode("latin-1")


def mutate_bytes(data, rng):
    data = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        kind = rng.random()
        if not data:
            data = bytearray(b"\0")
        at = rng.randrange(len(data))
        if kind < 0.4:
            data[at] ^= 1 << rng.randrange(8)
        elif kind < 0.55:
            data[at] = rng.randrange(256)
        elif kind < 0.7:
            del data[at:at + rng.randint(1, 16)]
        elif kind < 0.8:
            data[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 8)))
        elif kind < 0.9:
            del data[at:]
        else:
            chunk = data[at:at + rng.randint(1, 64)]
            data[at:at] = chunk
    return bytes(data)


TRACK_VALUES = ["nan", "inf", "-inf", "abc", "", "1e999", "412", "-0", "1e-320", "0x10", "1,2"]
TRACK_LINES = ["# units: px", "# units: mm", "# scale_m_per_px: -1", "# scale_m_per_px: nan",
               "# time_offset_s: inf", "# time_offset_s: 1e308", "# units: px\n# scale_m_per_px: 0.001",
               "t_s,tip.x", "t_s,knee.x,tip.z", "t_s,tip.w,tip.z", "t_s,voxel:99999.x,tip.z",
               "t_s,voxel:-1.x,tip.z", "t_s,com.x,com.x", ""]


def mutate_track(text, rng):
    """A measured track (docs/track-format.md) with one structural fault or byte damage."""
    if rng.random() < 0.3:
        return mutate_bytes(text.encode(), rng).decode("latin-1")
    lines = text.split("\n")
    data = [i for i, line in enumerate(lines) if line and line[0].isdigit()]
    header = next((i for i, line in enumerate(lines) if line.startswith("t_s")), 0)
    kind = rng.random()
    if kind < 0.3 and data:  # one value
        i = rng.choice(data)
        cells = lines[i].split(",")
        cells[rng.randrange(len(cells))] = rng.choice(TRACK_VALUES)
        lines[i] = ",".join(cells)
    elif kind < 0.45 and len(data) > 1:  # time order: two rows swapped or repeated
        a, b = rng.sample(data, 2)
        lines[a], lines[b] = lines[b], (lines[a] if rng.random() < 0.5 else lines[b])
    elif kind < 0.55:  # too short
        keep = set(data[:rng.randint(0, 2)])
        lines = [line for i, line in enumerate(lines) if i not in data or i in keep]
    elif kind < 0.75:  # a directive or a header
        at = header if rng.random() < 0.5 else 0
        lines[at:at + (1 if lines[at].startswith("t_s") and rng.random() < 0.5 else 0)] = \
            [rng.choice(TRACK_LINES)]
    elif kind < 0.85 and data:  # a column more or less in one row
        i = rng.choice(data)
        lines[i] = lines[i] + ",0" if rng.random() < 0.5 else lines[i].rsplit(",", 1)[0]
    else:  # positions scaled (pixels read as metres, or the whole track made huge)
        factor = rng.choice([1e3, 1e6, 1e300, -1.0, 0.0])
        for i in data:
            cells = lines[i].split(",")
            lines[i] = ",".join([cells[0]] + ["%r" % (float(c) * factor) for c in cells[1:]])
    return "\n".join(lines)


def mutate_replay(data, rng):
    """Header doubles (voxel size, settle time) set to non-finite or huge values, or byte damage."""
    data = bytearray(data)
    if rng.random() < 0.5 and len(data) > 40:
        # docs/replay-format.md: magic (8), version, nx, ny, nz (4 each), voxel_size_m, settle_s (8
        # each). Or any float of the frames.
        value = rng.choice([math.inf, -math.inf, math.nan, 1e308, -1e308, 1e-308, 0.0, 1e30])
        if rng.random() < 0.5:
            where, fmt = rng.choice([24, 32]), "<d"
        else:
            where, fmt = rng.randrange(48, len(data) - 8), "<f"
            if math.isfinite(value) and abs(value) > 3e38:
                value = math.copysign(math.inf, value)  # beyond a float: its infinity
        packed = struct.pack(fmt, value)
        data[where:where + len(packed)] = packed
        return bytes(data)
    return mutate_bytes(bytes(data), rng)


# One fuzz case of the Python module: every entry point on the (mutated) files, and on the same
# documents as dicts. A clean refusal is a ValueError or TypeError; anything else (another
# exception, a crash) exits with another status and fails the case.
PYTHON_CASE = r"""
import json, sys
import bhm
exp, body, run_dir = sys.argv[1:4]
def doc(path):
    try:
        return json.load(open(path, encoding="latin-1"))
    except ValueError:
        return None
clean = 0
for call in (lambda: bhm.validate(exp), lambda: bhm.validate(body, exp),
             lambda: bhm.simulate(exp, body, seconds=0.02),
             lambda: bhm.simulate(doc(exp), doc(body), seconds=0.02),
             lambda: bhm.decode(exp, doc(body)), lambda: bhm.load_run(run_dir)):
    try:
        call()
    except (ValueError, TypeError) as e:
        if "json.exception" in str(e):
            print("library tag in: %s" % e, file=sys.stderr)
            sys.exit(3)
        clean += 1
print("%d clean refusals" % clean)
"""


def check_calibrate_output(result, out, inputs, label):
    """bhm calibrate: a refusal leaves nothing in the output folder (every file is written
    atomically, and none before the fit is done) and says why in one line ("bhm calibrate: ...")
    or one line per problem naming the file ("FILE:field: ..."); a success writes a report that
    parses and a calibrated experiment."""
    rc, _, err = result
    if rc is None:
        return
    written = sorted(os.listdir(out)) if os.path.isdir(out) else []
    if rc == 0:
        for name in ("report.json", "calibrated-experiment.json"):
            try:
                json.load(open(os.path.join(out, name)))
            except (OSError, ValueError) as e:
                fail("%s: exit 0 but %s is unreadable: %s" % (label, name, e))
        return
    if written:
        fail("%s: exit %d but it wrote %s" % (label, rc, written))
    lines = [line for line in err.splitlines() if line.strip()]
    if rc != 1:
        return
    if not lines:
        fail("%s: exit 1 with no message" % label)
    elif lines[0].startswith("bhm calibrate: "):
        if len(lines) > 1:
            fail("%s: the refusal is not one line: %s" % (label, err[-500:]))
    elif not all(any(line.startswith(path) for path in inputs) for line in lines):
        fail("%s: a problem line names no input file: %s" % (label, err[-500:]))


def classify(result, label, sanitizer_seen):
    rc, out, err = result
    if rc is None:
        return "timeout"
    if "[json.exception." in err:
        fail("%s: a library's message reached the user: %s" % (label, err[-300:]))
        return "bad"
    if rc not in (0, 1, 2, 3):
        fail("%s: exit status %s (a signal or an unexpected code): %s" % (label, rc, err[-500:]))
        return "bad"
    for mark in SANITIZER_MARKS:
        if mark in err:
            fail("%s: sanitizer report: %s" % (label, err[-800:]))
            return "bad"
    return "ok"


def prepare_seeds(bhm):
    seeds = os.path.join(bhm.work, "seeds")
    os.makedirs(seeds, exist_ok=True)
    sim = os.path.join(seeds, "sim")
    rc, _, err = bhm.run(["simulate", EXPERIMENT, "--body", BODY, "--out", sim])
    if rc != 0:
        raise SystemExit("cannot make the seed replay: " + err)
    vxa = os.path.join(seeds, "body.vxa")
    bhm.run(["export", EXPERIMENT, "--body", BODY, "--vxa", vxa])
    # A measured track of the tiny body: its tip and centre of mass simulated at 5 ms steps.
    times = os.path.join(seeds, "times.csv")
    open(times, "w").write("t_s,tip.x,tip.z,com.z\n" +
                           "".join("%.3f,0,0,0\n" % (0.005 * k) for k in range(9)))
    rc, _, err = bhm.run(["calibrate", EXPERIMENT, "--body", BODY, "--track", times,
                          "--simulate-only", "--out", os.path.join(seeds, "track")])
    if rc != 0:
        raise SystemExit("cannot make the seed track: " + err)
    return {"experiment": open(EXPERIMENT).read(), "body": open(BODY).read(),
            "replay": open(os.path.join(sim, "replay.bin"), "rb").read(),
            "vxa": open(vxa, "rb").read(),
            "track": open(os.path.join(seeds, "track", "simulated.csv")).read()}


def fuzz(bhm, rng, cases, plan, label):
    cases = bhm.fuzz_cases or cases  # --cases: a longer campaign than ctest's
    seeds = prepare_seeds(bhm)
    jobs = []
    for i in range(cases):
        kind = plan(i, rng)
        d = os.path.join(bhm.work, "case-%04d" % i)
        os.makedirs(d, exist_ok=True)
        exp, body, replay, vxa = EXPERIMENT, BODY, os.path.join(d, "r.bin"), os.path.join(d, "b.vxa")
        case_rng = random.Random(rng.getrandbits(64))
        track = os.path.join(d, "t.csv")
        if kind in ("validate", "simulate", "evolve", "export", "render-body", "python",
                    "calibrate"):
            if case_rng.random() < 0.6:
                exp = os.path.join(d, "e.json")
                open(exp, "w", encoding="latin-1").write(mutate_json(seeds["experiment"], case_rng))
            if kind != "evolve" and (exp == EXPERIMENT or case_rng.random() < 0.4):
                body = os.path.join(d, "b.json")
                open(body, "w", encoding="latin-1").write(mutate_json(seeds["body"], case_rng))
        if kind in ("render-replay", "export-replay", "export-vtk"):
            open(replay, "wb").write(mutate_replay(seeds["replay"], case_rng))
        if kind == "import":
            open(vxa, "wb").write(mutate_bytes(seeds["vxa"], case_rng))
        if kind == "calibrate":
            # Mostly the track is at fault; the experiment and body above sometimes are.
            mutated = exp != EXPERIMENT or body != BODY
            text = seeds["track"] if mutated and case_rng.random() < 0.5 else \
                mutate_track(seeds["track"], case_rng)
            open(track, "w", encoding="latin-1").write(text)
        out = os.path.join(d, "out")
        args = {
            "validate": ["validate", exp, body],
            "simulate": ["simulate", exp, "--body", body, "--seconds", "0.02", "--out", out],
            "evolve": ["evolve", exp, "--out", out, "--generations", "1", "--threads", "1"],
            "export": ["export", exp, "--body", body, "--vxa", out + ".vxa", "--body-out",
                       out + ".json", "--mesh", out + ".stl"],
            "export-replay": ["export", EXPERIMENT, "--body", BODY, "--replay", replay, "--mesh",
                              out + ".obj"],
            "export-vtk": ["export", EXPERIMENT, "--body", BODY, "--replay", replay, "--vtk",
                           out + "-vtk", "--mesh", out + ".stl"],
            "python": [exp, body, d],
            "calibrate": ["calibrate", exp, "--body", body, "--track", track, "--fit",
                          case_rng.choice(["E", "amplitude,phase_lag", "E:active,global_damping"]),
                          "--max-simulations", "4", "--threads", "1", "--out", out],
            "import": ["import", vxa, "--experiment-out", out + "-e.json", "--body-out",
                       out + "-b.json"],
            "render-body": ["render", exp, "--body", body, "--out", out + ".png", "--size", "48x36",
                            "--samples", "1"],
            "render-replay": ["render", EXPERIMENT, "--replay", replay, "--out", out + ".png",
                              "--size", "48x36", "--samples", "1", "--color",
                              case_rng.choice(["strain", "displacement", "material"])],
        }[kind]
        jobs.append((i, kind, args))

    counts = {}
    started = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        futures = {pool.submit(bhm.run_python if kind == "python" else bhm.run, args, timeout=60):
                   (i, kind, args) for i, kind, args in jobs}
        for future in concurrent.futures.as_completed(futures):
            i, kind, args = futures[future]
            case_label = "case %d (%s: bhm %s)" % (i, kind, " ".join(args))
            verdict = classify(future.result(), case_label, True)
            if kind == "calibrate" and verdict == "ok":
                check_calibrate_output(future.result(),
                                       os.path.join(bhm.work, "case-%04d" % i, "out"),
                                       [args[1], args[3], args[5]], case_label)
                verdict = "exit %s" % future.result()[0]
            counts.setdefault(kind, {}).setdefault(verdict, 0)
            counts[kind][verdict] += 1
            shutil.rmtree(os.path.join(bhm.work, "case-%04d" % i), ignore_errors=True)
    timeouts = sum(c.get("timeout", 0) for c in counts.values())
    check(timeouts <= cases // 50, "%d cases ran past 60 s" % timeouts)
    print("%s: %d cases in %.1f s: %s" % (label, cases, time.time() - started,
                                          json.dumps(counts, sort_keys=True)))


def case_replay_fuzz(bhm, rng):
    fuzz(bhm, rng, 60, lambda i, r: "render-replay", "replay-fuzz")


def case_mutation_fuzz(bhm, rng):
    # Weighted by cost: the GL renders and evolutions take longest.
    kinds = ["validate"] * 30 + ["simulate"] * 22 + ["export"] * 14 + ["import"] * 10 + \
            ["export-replay"] * 8 + ["export-vtk"] * 6 + ["evolve"] * 8 + ["render-body"] * 4 + \
            ["render-replay"] * 4 + ["calibrate"] * 12 + \
            (["python"] * 6 if bhm.python_module else [])
    fuzz(bhm, rng, 1000, lambda i, r: r.choice(kinds), "mutation-fuzz")


CASES = {"kill9": case_kill9, "busy": case_busy, "stop-time": case_stop_time, "enospc": case_enospc,
         "unwritable": case_unwritable, "checkpoint": case_checkpoint,
         "replay-fuzz": case_replay_fuzz, "mutation-fuzz": case_mutation_fuzz}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", choices=sorted(CASES))
    parser.add_argument("--bhm", required=True)
    parser.add_argument("--shim", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--cases", type=int, default=0,
                        help="fuzz cases to run (default: the case's own count, as ctest runs it)")
    parser.add_argument("--python-module", help="folder of the bhm Python module (fuzzed too)")
    parser.add_argument("--python", default=sys.executable,
                        help="the interpreter the module was built for (default: this one)")
    a = parser.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    bhm = Bhm(os.path.abspath(a.bhm), os.path.abspath(a.shim), os.path.abspath(a.work),
              os.path.abspath(a.python_module) if a.python_module else None)
    bhm.python = a.python
    bhm.fuzz_cases = a.cases
    CASES[a.case](bhm, random.Random(a.seed))
    if failures:
        print("%d failure(s)" % len(failures), file=sys.stderr)
        return 1
    shutil.rmtree(a.work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
