"""The viewer's frame times, measured by driving `skyspec view` over HTTP (issue 37, targets 1-2).

usage: viewer_frames.py SKYSPEC [--frames N] [--size WxH]

Starts `skyspec view` on a free port with an empty table cache of its own, then
  1. the first frame of the default scene (the tables built: the cold start);
  2. N frames of the same atmosphere with the sun moved by 1 degree each (target 1: a new
     512 x 256 frame within 50 ms at the server, render + encode);
  3. the atmosphere changed (aerosol amount): its first frame (target 2: a preview within 200 ms,
     the exact frame within 2 s), cold (new tables) and then back to a cached atmosphere.
Prints each time (median and range of the server's X-Skyspec-Render/Encode-Seconds, and the
client's round trip) and the targets with pass / FAIL.
"""

import argparse
import os
import shutil
import statistics
import subprocess
import tempfile
import time
import urllib.parse
import urllib.request


def frame(url, **keys):
    query = urllib.parse.urlencode(keys)
    start = time.perf_counter()
    with urllib.request.urlopen(url + "api/frame?" + query, timeout=600) as r:
        r.read()
        render = float(r.headers["X-Skyspec-Render-Seconds"])
        encode = float(r.headers["X-Skyspec-Encode-Seconds"])
    return render, encode, time.perf_counter() - start


def describe(samples):
    ms = [1000 * s for s in samples]
    return f"median {statistics.median(ms):.0f} ms (range {min(ms):.0f}-{max(ms):.0f}, n = {len(ms)})"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("skyspec")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--size", default="512x256")
    a = ap.parse_args()
    w, h = (int(v) for v in a.size.split("x"))
    folder = tempfile.mkdtemp(prefix="skyspec-viewer-bench-")
    env = dict(os.environ, SKYSPEC_CACHE_DIR=os.path.join(folder, "cache"))
    proc = subprocess.Popen([a.skyspec, "view", "--port", "0", "--out", os.path.join(folder, "exports"), "-q"],
                            stdout=subprocess.PIPE, text=True, env=env)
    try:
        url = proc.stdout.readline().split()[3]
        view = {"camera.type": '"equirectangular"', "camera.width": w, "camera.height": h,
                "camera.min_elevation_deg": 0, "sun.azimuth_deg": 180}
        print(f"skyspec view frames, {w} x {h} equirectangular upper hemisphere, default scene (41 wavelengths, "
              f"6 orders), {os.cpu_count()} cores")
        r, e, t = frame(url, **view, **{"sun.elevation_deg": 10})
        print(f"  first frame, tables built: render {1000 * r:.0f} ms, encode {1000 * e:.0f} ms, round trip {1000 * t:.0f} ms")
        renders, encodes, totals, trips = [], [], [], []
        for k in range(a.frames):
            r, e, t = frame(url, **view, **{"sun.elevation_deg": 11 + k})
            renders.append(r), encodes.append(e), totals.append(r + e), trips.append(t)
        print(f"  sun moved, same atmosphere: render {describe(renders)}; encode {describe(encodes)}; "
              f"round trip {describe(trips)}")
        hazy = {"atmosphere.mie.scattering_per_m": 6e-05}
        r, e, t = frame(url, **view, **hazy, **{"sun.elevation_deg": 10})
        changed = r + e
        print(f"  atmosphere changed (aerosol 21e-6 -> 60e-6 m^-1), new tables: render {1000 * r:.0f} ms, "
              f"encode {1000 * e:.0f} ms")
        r, e, t = frame(url, **view, **{"sun.elevation_deg": 10})
        print(f"  back to the first atmosphere (tables in memory): render {1000 * r:.0f} ms, encode {1000 * e:.0f} ms")
        median = statistics.median(totals)
        print(f"target 1, sun moved: a frame within 50 ms at the server: {1000 * median:.0f} ms: "
              f"{'pass' if median <= 0.05 else 'FAIL'}")
        print(f"target 2, atmosphere changed: the exact frame within 2 s: {changed:.2f} s: "
              f"{'pass' if changed <= 2.0 else 'FAIL'}; a preview within 200 ms: FAIL (no progressive preview: "
              f"the first frame is the exact one)")
    finally:
        proc.terminate()
        proc.wait(timeout=30)
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
