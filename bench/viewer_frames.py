"""The viewer's frame times, measured by driving `skyspec view` over HTTP (issue 37, targets 1-2).

usage: viewer_frames.py SKYSPEC [--frames N] [--size WxH]

Starts `skyspec view` on a free port with an empty table cache of its own, then
  1. the first frame of the default scene (the tables built: the cold start);
  2. N frames of the same atmosphere with the sun moved by 1 degree each in elevation, exact and
     as previews (a coarse sky-view table), then N exact frames with the sun moved by 1 degree each
     in azimuth and N exact frames of a perspective camera turned by 1 degree each, as the page's
     drag does (the sky-view table's entries shared) (target 1: a new 512 x 256 frame within 50 ms
     at the server, render + encode);
  3. the atmosphere changed (aerosol amount): its first frame, a single-scattering preview while the
     tables are built, then asked again every 0.5 s as the page does until the exact one comes, the
     frames between from the preview's small tables once they are built (the time of the first
     such frame is printed) (target 2: a preview within 200 ms, the exact frame within 2 s); then
     back to a cached atmosphere.
  4. with --interpolated-cache DIR: a second server with render.ms_tables = "interpolated" and the
     table cache DIR, which must hold the grid's tables (bench/dataset_skies.sh leaves them in
     /tmp/skyspec-dataset-bench/cache-interpolated): three changes of the aerosol amount, each its
     first frame and the time until the frame of all orders from blended tables
     (docs/jobs.md, "Tables shared between atmospheres").
Prints each time (median and range of the server's X-Skyspec-Render/Encode-Seconds, and the
client's round trip) and the targets with pass / FAIL.
"""

import argparse
import contextlib
import math
import os
import shutil
import statistics
import subprocess
import tempfile
import time
import urllib.parse
import urllib.request


PNG_BYTES = []  # of every frame


def frame(url, preview=False, **keys):
    """(render s, encode s, round trip s, the X-Skyspec-Preview header) of one frame."""
    query = urllib.parse.urlencode({k: v for k, v in keys.items() if v is not None}) + ("&preview=1" if preview else "")
    start = time.perf_counter()
    with urllib.request.urlopen(url + "api/frame?" + query, timeout=600) as r:
        PNG_BYTES.append(len(r.read()))
        render = float(r.headers["X-Skyspec-Render-Seconds"])
        encode = float(r.headers["X-Skyspec-Encode-Seconds"])
        what = r.headers["X-Skyspec-Preview"]
    return render, encode, time.perf_counter() - start, what


@contextlib.contextmanager
def server(skyspec, cache=None, extra=()):
    """`skyspec view` on a free port (the table cache `cache`, else an empty one of its own): its URL."""
    folder = tempfile.mkdtemp(prefix="skyspec-viewer-bench-")
    env = dict(os.environ, SKYSPEC_CACHE_DIR=cache or os.path.join(folder, "cache"))
    proc = subprocess.Popen([skyspec, "view", "--port", "0", "--out", os.path.join(folder, "exports"), "-q", *extra],
                            stdout=subprocess.PIPE, text=True, env=env)
    try:
        yield proc.stdout.readline().split()[3]
    finally:
        proc.terminate()
        proc.wait(timeout=30)
        shutil.rmtree(folder, ignore_errors=True)


def describe(samples):
    ms = [1000 * s for s in samples]
    return f"median {statistics.median(ms):.0f} ms (range {min(ms):.0f}-{max(ms):.0f}, n = {len(ms)})"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("skyspec")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--size", default="512x256")
    ap.add_argument("--interpolated-cache", help="a table cache holding the grid's tables (step 4)")
    a = ap.parse_args()
    w, h = (int(v) for v in a.size.split("x"))
    with server(a.skyspec) as url:
        view = {"camera.type": '"equirectangular"', "camera.width": w, "camera.height": h,
                "camera.min_elevation_deg": 0, "sun.azimuth_deg": 180}
        print(f"skyspec view frames, {w} x {h} equirectangular upper hemisphere, default scene (41 wavelengths, "
              f"6 orders), {os.cpu_count()} cores")
        def until_exact(keys):
            """The first frame of an atmosphere, then asked again every 0.5 s as the page does until the
            exact one comes: (first frame's render + encode, its preview header, seconds to the exact one,
            seconds to the first frame from the preview's small tables or None)."""
            start = time.perf_counter()
            r, e, _, what = frame(url, **keys)
            first, first_what, small = r + e, what, None
            while what:
                if small is None and what.startswith("small scattering tables"):
                    small = time.perf_counter() - start
                time.sleep(0.5)
                _, _, _, what = frame(url, **keys)
            return first, first_what, time.perf_counter() - start, small

        def small_tables(small):
            return "no frame of them" if small is None else f"the first frame of them {small:.1f} s after the request"

        first, what, exact_after, small = until_exact({**view, "sun.elevation_deg": 10})
        print(f"  default atmosphere, empty cache: first frame {1000 * first:.0f} ms ({what or 'exact'}); the preview's "
              f"small tables: {small_tables(small)}; the exact frame {exact_after:.1f} s after the first request "
              f"(the tables' build)")
        results = {}
        for preview in (False, True):
            renders, encodes, totals, trips = [], [], [], []
            for k in range(a.frames):
                r, e, t, what = frame(url, preview, **view, **{"sun.elevation_deg": 11 + k + (0.5 if preview else 0)})
                assert what == ("coarse sky-view table" if preview else ""), what
                renders.append(r), encodes.append(e), totals.append(r + e), trips.append(t)
            results[preview] = statistics.median(totals)
            print(f"  sun moved in elevation, same atmosphere, {'preview (coarse sky-view table)' if preview else 'exact'}: "
                  f"render {describe(renders)}; encode {describe(encodes)}; round trip {describe(trips)}")
        renders, encodes, totals, trips = [], [], [], []
        for k in range(a.frames):
            r, e, t, what = frame(url, **{**view, "sun.elevation_deg": 20, "sun.azimuth_deg": 181 + k})
            assert what == "", what
            renders.append(r), encodes.append(e), totals.append(r + e), trips.append(t)
        results["azimuth"] = statistics.median(totals)
        print(f"  sun moved in azimuth, same atmosphere, exact (the sky-view table's entries shared): "
              f"render {describe(renders)}; encode {describe(encodes)}; round trip {describe(trips)}")
        renders, encodes, totals, trips = [], [], [], []
        for k in range(a.frames + 1):  # the first marches the table (a new camera type's image)
            yaw = math.radians(170 + k)
            look = [1000 * math.sin(yaw) * math.cos(math.radians(10)), 1000 * math.cos(yaw) * math.cos(math.radians(10)),
                    1 + 1000 * math.sin(math.radians(10))]
            r, e, t, what = frame(url, **{**view, "camera.type": '"perspective"', "sun.elevation_deg": 20,
                                          "sun.azimuth_deg": 190, "camera.min_elevation_deg": None,
                                          "camera.look_at_m": "[" + ", ".join(f"{v:.3f}" for v in look) + "]"})
            assert what == "", what
            if k > 0:
                renders.append(r), encodes.append(e), totals.append(r + e), trips.append(t)
        results["turn"] = statistics.median(totals)
        print(f"  perspective camera turned, same sun, exact (the sky-view table's entries shared): "
              f"render {describe(renders)}; encode {describe(encodes)}; round trip {describe(trips)}")
        hazy = {"atmosphere.mie.scattering_per_m": 6e-05}
        first_preview, what, exact_after, small = until_exact({**view, **hazy, "sun.elevation_deg": 10})
        print(f"  atmosphere changed (aerosol 21e-6 -> 60e-6 m^-1): first frame {1000 * first_preview:.0f} ms "
              f"({what or 'exact'}); the preview's small tables: {small_tables(small)}; the exact frame "
              f"{exact_after:.1f} s after the change")
        r, e, t, _ = frame(url, **view, **{"sun.elevation_deg": 10})
        print(f"  back to the first atmosphere (its tables in memory): render {1000 * r:.0f} ms, encode {1000 * e:.0f} ms")
        print(f"  frames' PNGs: median {statistics.median(PNG_BYTES) / 1000:.1f} kB (range "
              f"{min(PNG_BYTES) / 1000:.1f}-{max(PNG_BYTES) / 1000:.1f}, n = {len(PNG_BYTES)})")
        print(f"target 1, sun moved: a frame within 50 ms at the server: in elevation exact "
              f"{1000 * results[False]:.0f} ms, preview {1000 * results[True]:.0f} ms: "
              f"{'pass' if results[True] <= 0.05 else 'FAIL'}; in azimuth exact {1000 * results['azimuth']:.0f} ms: "
              f"{'pass' if results['azimuth'] <= 0.05 else 'FAIL'}; camera turned exact {1000 * results['turn']:.0f} ms: "
              f"{'pass' if results['turn'] <= 0.05 else 'FAIL'}")
        print(f"target 2, atmosphere changed: a preview within 200 ms: {1000 * first_preview:.0f} ms: "
              f"{'pass' if first_preview <= 0.2 else 'FAIL'}; the exact frame within 2 s: {exact_after:.1f} s: "
              f"{'pass' if exact_after <= 2.0 else 'FAIL'}")
    if a.interpolated_cache:
        interpolated(a, w, h)


def interpolated(a, w, h):
    """Step 4: atmosphere changes with interpolated tables and the grid's tables cached."""
    with server(a.skyspec, a.interpolated_cache, ("--set", 'render.ms_tables="interpolated"')) as url:
        view = {"camera.type": '"equirectangular"', "camera.width": w, "camera.height": h,
                "camera.min_elevation_deg": 0, "sun.azimuth_deg": 180, "sun.elevation_deg": 10}
        print(f"interpolated tables (render.ms_tables), the grid's tables in {a.interpolated_cache}:")
        firsts, fulls = [], []
        for beta in (None, 3.3e-5, 6e-5, 9e-5):
            keys = dict(view) if beta is None else {**view, "atmosphere.mie.scattering_per_m": beta}
            start = time.perf_counter()
            r, e, t, what = frame(url, **keys)
            first = r + e
            while what:
                time.sleep(0.5)
                _, _, _, what = frame(url, **keys)
            full = time.perf_counter() - start
            print(f"  aerosol {beta or 'of the scene'}: first frame {1000 * first:.0f} ms at the server (round trip "
                  f"{1000 * t:.0f} ms), the frame of all orders {full:.1f} s after the request")
            if beta is not None:
                firsts.append(first)
                fulls.append(full)
        print(f"target 2 with interpolated tables: a preview within 200 ms: {1000 * max(firsts):.0f} ms at most: "
              f"{'pass' if max(firsts) <= 0.2 else 'FAIL'}; all orders within 2 s: {max(fulls):.1f} s at most: "
              f"{'pass' if max(fulls) <= 2.0 else 'FAIL'}")


if __name__ == "__main__":
    main()
