#!/usr/bin/python3
"""Newton iterations and solve seconds per frame of the arm example, each
frame started from the previous frame or from linear blend skinning
(character.skinned_guess), at a few frame rates (faster motion per frame at
fewer frames per second).

    python3 skinned_guess.py path/to/snh [--fps 10 5] [--cell 0.025] [--repeat 3]

Runs `snh run` on variants of arm.json in a scratch folder and prints one
row per frame rate and start: frames, mean and largest Newton iterations
per frame, CG iterations, and the median over the repeats of the mean
seconds per frame (frame 0, at rest, left out).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("snh")
    parser.add_argument("--fps", type=float, nargs="+", default=[10, 5])
    parser.add_argument("--cell", type=float, default=0.025)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    scene = json.load(open(os.path.join(HERE, "arm.json")))
    work = tempfile.mkdtemp(prefix="snh_skinned_guess_")
    shutil.copy(os.path.join(HERE, "arm.gltf"), work)
    print("cell %g" % args.cell)
    print("fps  start     frames  newton mean  newton max  cg total  s per frame (median of %d)" % args.repeat)
    for fps in args.fps:
        for guess in (False, True):
            s = json.loads(json.dumps(scene))
            s["character"]["fps"] = fps
            s["character"]["cell"] = args.cell
            s["character"]["frames"] = [0, int(round(fps))]  # the whole 1 s clip
            s["character"]["skinned_guess"] = guess
            s["output"] = {}
            path = os.path.join(work, "scene.json")
            json.dump(s, open(path, "w"))
            seconds = []
            for _ in range(args.repeat):
                out = os.path.join(work, "run.json")
                subprocess.run([args.snh, "run", path, "--quiet", "--json", out], check=True,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                frames = json.load(open(out))["frames"][1:]
                seconds.append(sum(f["seconds"] for f in frames) / len(frames))
            newton = [f["newton_iterations"] for f in frames]
            print("%-4g %-9s %-7d %-12.1f %-11d %-9d %.3f" % (
                fps, "skinned" if guess else "previous", len(frames), sum(newton) / len(newton), max(newton),
                sum(f["cg_iterations"] for f in frames), statistics.median(seconds)))
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
