# Blender's camera against pleinair's: the test points Blender projected at some frames
# (blender_scene.py) and those `pleinair camera` projected at the same frames must land within
# a pixel of each other. Exit code 1 otherwise, with the points that missed.
#   match_camera.py POINTS.json CAMERA.jsonl
import json
import sys

blender = json.load(open(sys.argv[1]))
pleinair = {}
for line in open(sys.argv[2]):
    j = json.loads(line)
    pleinair[j["frame"]] = j
worst, misses = 0.0, []
for frame, seen in blender["frames"].items():
    ours = pleinair[int(frame)]["points"]
    for i, (b, p) in enumerate(zip(seen, ours)):
        d = ((b[0] - p[0]) ** 2 + (b[1] - p[1]) ** 2) ** 0.5
        worst = max(worst, d)
        if d > 1.0:
            misses.append(f"frame {frame} point {i}: Blender {b[:2]}, pleinair {p[:2]}")
print(f"  {sum(len(v) for v in blender['frames'].values())} projections at "
      f"{len(blender['frames'])} frames; the farthest apart {worst:.4f} px")
for m in misses:
    print("  FAIL " + m)
sys.exit(1 if misses else 0)
