"""Runs a character scene with snh and checks its caches in Blender.

    python3 tests/blender/run_cache_test.py --snh build/snh --blender BLENDER \\
        --scene SCENE.json --workdir DIR [--run-frames N] --check-frames 0,5,10

The scene is copied into DIR with its character file made absolute and its
outputs replaced by DIR/sim.pc2 and DIR/lbs.pc2; `snh run` runs it
(`--frames N` when given) and tests/blender/check_cache.py loads the caches
onto the character in Blender (report: DIR/report.json). A missing Blender
is a failure, not a skip.
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--snh", required=True)
    ap.add_argument("--blender", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--run-frames", type=int, default=0)
    ap.add_argument("--check-frames", required=True)
    args = ap.parse_args()

    blender = args.blender
    if not blender or blender.endswith("NOTFOUND") or not shutil.which(blender):
        print(f"FAIL: Blender not found ({blender!r}). These tests load snh's caches in Blender; "
              "install it (scripts/setup.sh installs Debian's blender) and configure again.", file=sys.stderr)
        return 1

    os.makedirs(args.workdir, exist_ok=True)
    with open(args.scene) as f:
        scene = json.load(f)
    base = os.path.dirname(os.path.abspath(args.scene))
    character = scene["character"]
    character["file"] = os.path.join(base, character["file"])
    sim = os.path.join(args.workdir, "sim.pc2")
    lbs = os.path.join(args.workdir, "lbs.pc2")
    for p in (sim, lbs):
        if os.path.exists(p):
            os.remove(p)
    scene["output"] = {"pc2": sim, "lbs": lbs}
    scene_path = os.path.join(args.workdir, "scene.json")
    with open(scene_path, "w") as f:
        json.dump(scene, f, indent=1)

    checker = os.path.join(HERE, "check_cache.py")
    fps = str(character.get("fps", 30))
    cmd = [args.snh, "run", scene_path]
    if args.run_frames:
        cmd += ["--frames", str(args.run_frames)]
    print("+", " ".join(cmd), flush=True)
    # snh names its surface's vertex count before it solves: when Blender
    # imports no skinned mesh of that count, the caches cannot be loaded
    # onto the character, so fail then rather than after the frames.
    snh = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    counted = False
    for line in snh.stdout:
        print(line, end="", flush=True)
        m = re.search(r"surface of (\d+) vertices", line)
        if m and not counted:
            counted = True
            count_cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", checker, "--",
                         "--file", character["file"], "--points", m.group(1), "--fps", fps,
                         "--out", os.path.join(args.workdir, "points.json")]
            r = subprocess.run(count_cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            if r.returncode != 0:
                snh.kill()
                snh.wait()
                print(r.stdout[-4000:], file=sys.stderr)
                print(f"FAIL: snh's surface has {m.group(1)} vertices and Blender imports no skinned mesh of "
                      f"that many (see {os.path.join(args.workdir, 'points.json')})", file=sys.stderr)
                return 1
    if snh.wait() != 0:
        print(f"FAIL: snh run exited with {snh.returncode}", file=sys.stderr)
        return 1

    report = os.path.join(args.workdir, "report.json")
    cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", checker, "--",
           "--file", character["file"], "--pc2", sim, "--lbs", lbs, "--frames", args.check_frames, "--fps", fps,
           "--out", report]
    print("+", " ".join(cmd), flush=True)
    r = subprocess.run(cmd)
    if r.returncode != 0:
        print(f"FAIL: the Blender check exited with {r.returncode} (report: {report})", file=sys.stderr)
        return 1
    print(f"passed (report: {report})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
