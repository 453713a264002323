#!/usr/bin/python3
"""Prints the benchmark table of bench/run_benchmarks.sh from its working folder.

Relative error per pixel: the largest |L - L_ref| / L_ref over the pixel's channels (all spectral
channels S0.*; for the baseline its R, G, B = 680, 550, 440 nm), over the pixels whose reference
radiance (largest channel) exceeds 1e-6 of the image's largest. The baseline (512 x 512, pixel
x = 2 (i + 0.5) / (W - 1) - 1) is compared with skyspec's seed preset rendered at 511 x 511 with
reference settings, whose pixel x = 2 (i + 0.5) / 511 - 1 is the same direction for i < 511.
Case 4 is the upper hemisphere only (camera.min_elevation_deg = 0): the whole image is compared.
The "tables / image / files" column is skyspec's own split of its wall time, from the line
"rendered ... (tables T s, image I s, completing the files F s)" of its log: set-up and tables;
metering and the image's rows (with the EXR's bands written meanwhile); the EXR's offset table,
fsync and rename (medians over the runs). Wall times: the median of the runs and their range; the
ratio to the baseline divides the medians. Cases compared with each other ran interleaved (run i
of each before run i + 1 of any); the paired ratios below divide run i of one by run i of the
other, so that the VM's drifts in speed cancel.
"""
import re
import sys
from pathlib import Path

import numpy as np
import OpenImageIO as oiio


def read_exr(path):
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise SystemExit(f"bench_stats.py: cannot read {path}: {oiio.geterror()}")
    spec = inp.spec()
    px = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    names = list(spec.channelnames)
    idx = [k for k, n in enumerate(names) if n.startswith("S0.")]
    wl = [float(names[k][3:-2].replace(",", ".")) for k in idx]
    return np.asarray(px)[:, :, idx].astype(np.float64), wl


def read_pfm(path):
    data = Path(path).read_bytes()
    head = data.split(b"\n", 3)
    w, h = map(int, head[1].split())
    return np.frombuffer(head[3], dtype="<f4", count=w * h * 3).reshape(h, w, 3).astype(np.float64)


def rel_error(img, ref):
    peak = ref.max(axis=-1)
    mask = peak > 1e-6 * peak.max()
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(img - ref) / np.abs(ref)
    rel = np.where(ref > 0, rel, np.where(img == ref, 0.0, np.inf)).max(axis=-1)[mask]
    return np.percentile(rel, 50), np.percentile(rel, 99)


STAGES = re.compile(r"\(tables ([0-9.]+) s, image ([0-9.]+) s, completing the files ([0-9.]+) s\)")


def stage_runs(out, name):
    """skyspec's own split of each run's time: (tables, image, files) per run, from NAME.stages."""
    path = out / f"{name}.stages"
    text = path.read_text() if path.exists() else ""
    return [tuple(float(v) for v in m.groups()) for m in STAGES.finditer(text)]


def stages_of(out, name):
    """The median of each stage over the runs (None for the baseline)."""
    runs = stage_runs(out, name)
    return None if not runs else tuple(float(np.median([r[k] for r in runs])) for k in range(3))


def runs_of(out, name):
    """Wall times (s) of a case's runs and its largest peak RSS (MB)."""
    runs = [line.split() for line in (out / f"{name}.time").read_text().splitlines() if line.strip()]
    return [float(r[0]) for r in runs], max(int(r[1]) for r in runs) / 1024.0


def time_of(out, name):
    walls, rss = runs_of(out, name)
    return float(np.median(walls)), rss


def wall_cell(out, name):
    """The median wall time, and the range when the case ran more than once."""
    walls, _ = runs_of(out, name)
    median = float(np.median(walls))
    if len(walls) == 1:
        return f"{median:.3f}"
    return f"{median:.3f} ({min(walls):.3f}-{max(walls):.3f}, {len(walls)} runs)"


def paired(out, a, b, stage=False):
    """Median and range of run i of a over run i of b: wall times, or tables + image (stage=True)."""
    if stage:
        x = [t + i for t, i, _ in stage_runs(out, a)]
        y = [t + i for t, i, _ in stage_runs(out, b)]
    else:
        x, y = runs_of(out, a)[0], runs_of(out, b)[0]
    r = [p / q for p, q in zip(x, y) if q > 0]
    return None if not r else (float(np.median(r)), min(r), max(r), len(r))


def paired_lines(out, base):
    def text(v):
        return "-" if v is None else f"{v[0]:.2f}x ({v[1]:.2f}-{v[2]:.2f}, {v[3]} pairs)"
    lines = []
    for sun in ("30", "10", "2"):
        if sun in base and (out / f"c2n-{sun}.time").exists():
            line = (f"baseline / case 2 (RGB-fast, uncompressed), sun {sun}, per interleaved pair: "
                    f"{text(paired(out, f'base-{sun}', f'c2n-{sun}'))}; PIZ: {text(paired(out, f'base-{sun}', f'c2-{sun}'))}")
            if (out / f"c2ln-{sun}.time").exists():
                line += f"; --quality lean, uncompressed: {text(paired(out, f'base-{sun}', f'c2ln-{sun}'))}"
            lines.append(line)
    for one, two, what in (("c3-1t", "c3-2t", "case 1 (PIZ)"), ("c3n-1t", "c3n-2t", "case 1 uncompressed"),
                           ("c4n1-10", "c4n-10", "case 4 uncompressed")):
        if (out / f"{one}.time").exists() and (out / f"{two}.time").exists():
            lines.append(f"speed-up from 1 to 2 threads, {what}, per interleaved pair: wall {text(paired(out, one, two))}; "
                         f"tables + image (skyspec's own split) {text(paired(out, one, two, stage=True))}")
    if (out / "c3-1t.time").exists() and (out / "c3x-1t.time").exists():
        v = paired(out, "c3-1t", "c3x-1t")
        if v is not None:
            lines.append("what two cores give two independent renders: 2 x (case 1 on 1 thread) / (two of them at once), "
                         f"per interleaved pair: {text((2 * v[0], 2 * v[1], 2 * v[2], v[3]))}")
    return lines


def codec_lines(out):
    """OpenEXR's lossless codecs on case 5's pixels (codecs.tsv from bench/exr_codecs.cpp)."""
    path = out / "codecs.tsv"
    if not path.exists():
        return []
    rows = [line.split("\t") for line in path.read_text().splitlines() if line.strip()]
    piz = {int(t): int(b) for c, t, _, _, b in rows if c == "piz"}
    lines = ["OpenEXR's lossless codecs on case 5's panorama at 1024 x 512 x 81 wavelengths (bench/exr_codecs.cpp, "
             "fastest of 2 writes to /dev/shm; \"-core\": OpenEXRCore, line blocks compressed on the threads and "
             "written in order, as skyspec writes; the others: the C++ library's OutputFile):", "",
             "| codec | threads | seconds | MB/s of floats | file (MB) | size / PIZ's |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for codec, threads, sec, raw, size in rows:
        t, sec, raw, size = int(threads), float(sec), float(raw), int(size)
        lines.append(f"| {codec} | {t} | {sec:.3f} | {raw / sec / 1e6:.0f} | {size / 1e6:.1f} | {size / piz[t]:.2f} |")
    # The fastest lossless codec whose file is at most 1.25 x PIZ's (issue 21's bound), on 2 threads,
    # and what its rate would mean for case 5's full-size file (8192 x 4096 x 84 channels of floats).
    ok = [(float(raw) / float(sec), codec) for codec, t, sec, raw, size in rows
          if int(t) == 2 and codec != "none" and int(size) <= 1.25 * piz[2]]
    if ok:
        rate, codec = max(ok)
        full = 8192 * 4096 * 84 * 4
        lines += ["", f"fastest lossless codec within 1.25 x PIZ's size on 2 threads: {codec}, {rate / 1e6:.0f} MB/s of floats; "
                  f"case 5's {full / 1e9:.1f} GB of floats at that rate: {full / rate:.1f} s (the sample's rate; "
                  "target 6 below times the codec on the file's own pixels)"]
    return lines


def mark(ok):
    """A target's verdict: pass, FAIL, or - where this run cannot tell (ok is None)."""
    return "-" if ok is None else ("pass" if ok else "FAIL")


def target_lines(out, base, table_p99):
    """Issue 21's six targets, each with its figure from this run and a pass / FAIL mark."""
    def exists(*names):
        return all((out / f"{n}.time").exists() for n in names)
    lines = ["Issue 21's targets, from this run:"]
    if exists("c5-10"):
        wall, rss = time_of(out, "c5-10")
        lines.append(f"1. 8192 x 4096 x 81 spectral EXR, lossless (PIZ): {wall:.1f} s (at most 15 s: {mark(wall <= 15)}), "
                     f"peak RSS {rss:.0f} MB (at most 1024 MB: {mark(rss <= 1024)}); 16384 x 8192 not run "
                     "(a 43 GB file, several minutes)")
    def pairs_over_suns(a, b, case):
        """Run i of a over run i of b at every sun the case ran at ("{}" in a and b is the sun)."""
        suns = [s for s in ("30", "10", "2") if s in base and exists(f"{case}-{s}")]
        r = []
        for sun in suns:
            r += [p / q for p, q in zip(runs_of(out, a.format(sun))[0], runs_of(out, b.format(sun))[0])]
        return suns, r
    suns, ratios = pairs_over_suns("c1-{}", "base-{}", "c1")
    if ratios:
        p99 = max(table_p99.get(f"c1-{s}", 1.0) for s in suns)
        lines.append(f"2. case 1 (41 wl, 512 fisheye, default PIZ file) / baseline, per interleaved pair: "
                     f"{min(ratios):.2f}-{max(ratios):.2f} (at most 0.5 in every pair: {mark(max(ratios) <= 0.5)}); "
                     f"p99 error {p99:.1e} (at most 5e-3: {mark(p99 <= 5e-3)}); the file is PIZ's (size 1.00 x)")
    if exists("c6-cold"):
        wall, _ = time_of(out, "c6-cold")
        lines.append(f"3. default scene, first render with no cached tables (256 x 256): {wall:.2f} s "
                     f"(at most 2 s: {mark(wall <= 2.0)})")
    if exists("c3-1t", "c3-2t", "c3x-1t"):
        t2, tx = runs_of(out, "c3-2t")[0], runs_of(out, "c3x-1t")[0]
        # speed-up / ceiling per pair = (t1 / t2) / (2 t1 / tx) = tx / (2 t2)
        share = sorted(x / (2 * y) for x, y in zip(tx, t2))
        med = float(np.median(share))
        lines.append(f"4. two threads on case 1 (PIZ), speed-up / ceiling per interleaved pair: median {med:.2f} "
                     f"({share[0]:.2f}-{share[-1]:.2f}) (at least 0.95: {mark(med >= 0.95)})")
    _, r = pairs_over_suns("base-{}", "c2-{}", "c2")
    if r:
        lines.append(f"5. RGB-fast, default quality and PIZ file: baseline / case 2 per interleaved pair {min(r):.1f}-{max(r):.1f}x "
                     f"(at least 10x in every pair: {mark(min(r) >= 10)})")
    if exists("c4-10", "c6-hemi") and "10" in base:
        single, _ = time_of(out, "c4-10")
        multi, _ = time_of(out, "c6-hemi")
        lines.append(f"6. 512 x 256 upper hemisphere, 41 wl, PIZ: default scene (6 orders, tables cached) {multi:.3f} s, "
                     f"{multi / base['10']:.2f} x the baseline's time; case 1's scene (single scattering) {single:.3f} s, "
                     f"{single / base['10']:.2f} x (target: at most 0.5 x the process time of Blender's Nishita texture "
                     f"for the same view, which is not in the repository: {mark(None)})")
    return lines


def codec_alone(out, case):
    """Seconds PIZ alone takes to write case's own file on 2 threads (CASE-codec.tsv from bench/exr_codecs.cpp
    --same, a line per library and run): the median of each library's runs, the faster library's (the
    codec's limit here), or None."""
    path = out / f"{case}-codec.tsv"
    if not path.exists():
        return None
    runs = {}
    for line in path.read_text().splitlines():
        if line.strip():
            codec, _, sec, _, _ = line.split("\t")
            runs.setdefault(codec, []).append(float(sec))
    return min(float(np.median(v)) for v in runs.values()) if runs else None


def issue37_lines(out, base):
    """Issue 37's targets 3 and 6 (the CLI's first and cached render of the default scene; the spectral
    EXR's writing against the codec alone), pass / FAIL."""
    lines = []
    if all((out / f"{n}.time").exists() for n in ("c37-cold", "c37-warm")):
        cold, _ = time_of(out, "c37-cold")
        warm, _ = time_of(out, "c37-warm")
        lines += ["Issue 37's targets 3 and 6, from this run:",
                  f"3. default scene 512 x 512 (41 wl, 6 orders, PIZ): no cached tables {cold:.2f} s (at most 2 s: "
                  f"{mark(cold <= 2.0)}); tables cached, median of 5 {warm:.3f} s (at most 0.3 s: {mark(warm <= 0.3)})"]
        if "30" in base:
            b = base["30"]
            lines.append(f"   against the baseline's median at sun 30 in this run ({b:.3f} s): {cold / b:.1f} x (at most 5 x: "
                         f"{mark(cold <= 5 * b)}) and {warm / b:.2f} x (at most 0.75 x: {mark(warm <= 0.75 * b)})")
    c1_alone, c5_alone = codec_alone(out, "c1"), codec_alone(out, "c5")
    if c1_alone is None and c5_alone is None:
        return lines
    lines.append("6. the spectral EXR against the codec alone: the render's own file written again with PIZ on 2 "
                 "threads (bench/exr_codecs.cpp --same, the faster of OpenEXR's two libraries, medians):")
    if c1_alone is not None and all((out / f"{n}.time").exists() for n in ("c1-30", "c1n-30")):
        extra = time_of(out, "c1-30")[0] - time_of(out, "c1n-30")[0]
        lines.append(f"   case 1 (512 x 512 x 44 channels, sun 30): PIZ adds {extra:.3f} s to the uncompressed render "
                     f"(medians), PIZ alone {c1_alone:.3f} s: {extra / c1_alone:.2f} x "
                     f"(at most 1.10 x: {mark(extra <= 1.1 * c1_alone)})")
    if c5_alone is not None and (out / "c5-10.time").exists():
        wall, rss = time_of(out, "c5-10")
        lines.append(f"   case 5 (8192 x 4096 x 84 channels): the whole render {wall:.1f} s, PIZ alone {c5_alone:.1f} s: "
                     f"{wall / c5_alone:.2f} x (at most 1.10 x: {mark(wall <= 1.1 * c5_alone)}); peak RSS {rss:.0f} MB "
                     f"(at most 1 GB: {mark(rss <= 1024)})")
    return lines


def main():
    out = Path(sys.argv[1])
    rows = [line.rstrip("\n").split("\t") for line in (out / "manifest.tsv").read_text().splitlines()]
    base = {}
    for kind, name, label, sun in rows:
        if kind != "base":
            continue
        wall, rss = time_of(out, name)
        img = read_pfm(out / f"{name}.pfm")[:511, :511]
        ref, wl = read_exr(out / f"ref-base511-{sun}.exr")
        ref = ref[:, :, [wl.index(680.0), wl.index(550.0), wl.index(440.0)]]
        p50, p99 = rel_error(img, ref)
        base[sun] = wall
        print(f"baseline render time (its own clock, sun {sun}): "
              + (out / f"{name}.log").read_text().strip().split(";")[0])
        rows_out = base.setdefault("rows", [])
        rows_out.append((label, sun, wall_cell(out, name), 1.0, p50, p99, rss, None))
    has_base = any(k != "rows" for k in base)
    table = []
    table_p99 = {}
    refcheck = None
    for kind, name, label, sun in rows:
        if kind == "base":
            continue
        if kind == "refcheck":
            a, _ = read_exr(out / "ref-c1-2.exr")
            b, _ = read_exr(out / f"{name}.exr")
            refcheck = rel_error(a, b)
            continue
        wall, rss = time_of(out, name)
        p50 = p99 = None
        if kind == "main":
            img, _ = read_exr(out / f"{name}.exr")
            ref, _ = read_exr(out / f"ref-{name}.exr")
            p50, p99 = rel_error(img, ref)
        ratio = wall / base[sun] if has_base and sun in base and label.startswith(("1", "2", "3", "4")) else None
        table.append((label, sun, wall_cell(out, name), ratio, p50, p99, rss, stages_of(out, name)))
        if p99 is not None:
            table_p99[name] = p99
    if has_base:
        table = sorted(base["rows"], key=lambda r: -float(r[1])) + table

    def f(v, fmt):
        return "-" if v is None else format(v, fmt)

    cols = ["case", "sun (deg)", "wall (s): median (range, runs)"] + (["time / baseline"] if has_base else []) + [
        "tables / image / files (s)", "p50 rel. err.", "p99 rel. err.", "peak RSS (MB)"]
    print()
    print("| " + " | ".join(cols) + " |")
    print("| --- | " + " | ".join("---:" for _ in cols[1:]) + " |")
    for label, sun, wall, ratio, p50, p99, rss, stages in table:
        split = "-" if stages is None else " / ".join(f"{v:.3f}" for v in stages)
        cells = [label, sun, wall] + ([f(ratio, ".3f")] if has_base else []) + [
            split, f(p50, ".1e"), f(p99, ".1e"), f"{rss:.0f}"]
        print("| " + " | ".join(cells) + " |")
    refs = sorted(out.glob("ref-*.time"))
    print()
    print("reference renders (every pixel marched, 256 view segments, 1024 x 2048 sun table), wall s: "
          + ", ".join(f"{p.name[4:-5]} {time_of(out, p.name[:-5])[0]:.1f}" for p in refs))
    print()
    for line in paired_lines(out, base):
        print(line)
    if refcheck:
        print(f"reference check, case 1 at sun 2: 256 vs 512 view segments differ by p50 {refcheck[0]:.1e}, "
              f"p99 {refcheck[1]:.1e}")
    for block in (codec_lines(out), target_lines(out, base, table_p99), issue37_lines(out, base)):
        if block:
            print()
            print("\n".join(block))


if __name__ == "__main__":
    main()
