#!/usr/bin/env python3
"""Skylight polarisation from the vector Monte Carlo reference (issue 23): the neutral points
(Arago, Babinet, Brewster) along the sun's vertical circle and the degree of linear polarisation
90 degrees from the sun, for suns from 0 to 30 degrees; and how much the scalar transport (the
renderer's and the scalar reference's) misses in intensity by ignoring polarisation.

    /usr/bin/python3 bench/polarisation.py [--skyspec build/skyspec] [--paths 20000] [--suns 0,5,10,20,30]
        [--preset default] [--set KEY=VALUE ...] [--markdown FILE]
        [--intensity-suns 30,10,2] [--intensity-paths 100000] [--parts neutral,intensity,renderer]

The third part, renderer: the renderer's polarisation (output.polarisation: SkyRenderer::stokes)
against the vector reference's at the standard probes (`skyspec reference --stokes --compare`),
suns of --intensity-suns, 450 and 650 nm: DoLP, and its intensity against the reference's I. With
it, the neutral-point table gives the renderer's figures beside the reference's (from the same
probes: no extra paths).

For each sun it runs `skyspec reference --stokes` at probes every --step degrees along the solar and
antisolar verticals (450 and 550 nm). In the frame of the vertical plane through the line of sight,
skylight in the sun's vertical circle is polarised horizontally (Q < 0) except between a neutral
point and the sun or the antisolar point, where multiple scattering turns it vertical (Q > 0). A
neutral point is where Q changes sign (linear interpolation between probes; the +- is the standard
error of Q over the slope). Distances: Arago above the antisolar point, Babinet above the sun,
Brewster below it. Published: Arago about 20 deg above the antisolar point (higher in turbid
air), Babinet and Brewster about 15-20 deg above and below the sun (Glossary of Meteorology, AMS,
after Neuberger 1951). Exits 0 whatever the result (it measures).
"""
import argparse
import json
import math
import subprocess
import time

WAVELENGTHS = [450, 550]


def run(skyspec, preset, sun, probes, paths, sets, wavelengths=WAVELENGTHS, compare=False):
    cmd = [skyspec, "reference", "--preset", preset, "--sun-elevation", str(sun), "--wavelengths",
           ",".join(map(str, wavelengths)), "--paths", str(paths), "--stokes", "--format", "json", "-q"]
    if compare:
        cmd.append("--compare")
    for az, el in probes:
        cmd += ["--probe", f"{az:g},{el:g}"]
    for s in sets:
        cmd += ["--set", s]
    return json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)


def crossings(points):
    """points: (distance, Q, se) sorted by distance; the first sign change from Q < 0 (far) to Q > 0 (near)
    scanning from the far end, as (distance, +-)."""
    for (d0, q0, e0), (d1, q1, e1) in zip(points, points[1:]):
        if (q0 > 0) != (q1 > 0):
            t = q0 / (q0 - q1)
            slope = abs(q1 - q0) / abs(d1 - d0)
            return d0 + t * (d1 - d0), math.hypot(e0, e1) / slope
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--skyspec", default="build/skyspec")
    ap.add_argument("--paths", type=int, default=20000)
    ap.add_argument("--suns", default="0,5,10,20,30")
    ap.add_argument("--preset", default="default")
    ap.add_argument("--step", type=float, default=2.0)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--markdown")
    ap.add_argument("--intensity-suns", default="30,10,2", help="suns of the scalar-vs-vector intensity table ('' for none)")
    ap.add_argument("--intensity-paths", type=int, default=100000)
    ap.add_argument("--parts", default="neutral,intensity,renderer")
    a = ap.parse_args()
    parts = a.parts.split(",")
    rows = []
    t0 = time.time()
    for sun in [float(s) for s in a.suns.split(",")] if "neutral" in parts else []:
        els = [0.5 + a.step * i for i in range(int(89 / a.step) + 1)]
        anti = [(180.0, e) for e in els]
        solar = [(0.0, e) for e in els if abs(e - sun) > 3.0]
        probes = anti + solar + [(90.0, 0.5)]
        r = run(a.skyspec, a.preset, sun, probes, a.paths, a.set, compare="renderer" in parts)
        for i, lam in enumerate(WAVELENGTHS):
            ps = r["probes"]

            def figures(key, error_key):
                """Neutral points and DoLP from the Stokes vectors under `key` (the reference's, with their
                standard errors, or the renderer's, exact)."""
                def q_of(p):
                    return p[key][i][1], p[error_key][i][1] if error_key else 0.0
                # Arago: along the antisolar vertical, distance above the antisolar point = el + sun.
                arago = crossings(sorted((p["elevation_deg"] + sun, *q_of(p)) for p in ps[:len(anti)]))
                babinet = crossings(sorted((p["elevation_deg"] - sun, *q_of(p)) for p in ps[len(anti):len(anti) + len(solar)]
                                           if p["elevation_deg"] > sun))
                brewster = crossings(sorted((sun - p["elevation_deg"], *q_of(p)) for p in ps[len(anti):len(anti) + len(solar)]
                                            if p["elevation_deg"] < sun))
                across = ps[-1][key][i]
                dolp90 = math.hypot(across[1], across[2]) / across[0]
                dolp_max = max(math.hypot(p[key][i][1], p[key][i][2]) / p[key][i][0] for p in ps)
                return arago, babinet, brewster, dolp90, dolp_max
            rows.append((sun, lam, figures("stokes", "stokes_standard_error"),
                         figures("renderer_stokes", None) if "renderer" in parts else None))
    def fmt(c):
        if c is None:
            return "none in view"
        return f"{c[0]:.1f} +- {c[1]:.1f}" if c[1] > 0 else f"{c[0]:.1f}"
    both = any(renderer for *_, renderer in rows)
    lines = [] if not rows else ["| sun (deg) | nm | Arago above antisolar point (deg) | Babinet above sun (deg) | Brewster below sun (deg) "
             "| DoLP 90 deg from sun, horizon | DoLP max on the sun's vertical |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for sun, lam, ref, ren in rows:
        cells = [fmt(ref[k]) + (f" / {fmt(ren[k])}" if ren else "") for k in range(3)]
        cells += [f"{ref[k]:.3f}" + (f" / {ren[k]:.3f}" if ren else "") for k in (3, 4)]
        lines.append(f"| {sun:g} | {lam} | " + " | ".join(cells) + " |")
    if rows:
        lines.append("")
        lines.append(f"{'the vector reference / the renderer (output.polarisation); ' if both else ''}preset {a.preset}, "
                     f"{a.paths} paths per probe, probes every {a.step:g} deg; {time.time() - t0:.0f} s")
    if a.intensity_suns and "intensity" in parts:
        # The standard probes (no --probe): the vector intensity against the scalar one, each from
        # its own paths, with the combined standard error.
        t1 = time.time()
        lines += ["", "| sun (deg) | probe | " + " | ".join(f"{w} nm" for w in [400, 450, 550, 650, 750]) + " |",
                  "| ---: | --- |" + " ---: |" * 5]
        for sun in [float(x) for x in a.intensity_suns.split(",")]:
            r = run(a.skyspec, a.preset, sun, [], a.intensity_paths, a.set, [400, 450, 550, 650, 750])
            for p in r["probes"]:
                cells = []
                for i in range(5):
                    I, e = p["stokes"][i][0], p["stokes_standard_error"][i][0]
                    L, le = p["radiance"][i], p["standard_error"][i]
                    cells.append(f"{100 * (I / L - 1):+.2f} +- {100 * math.hypot(e / L, le * I / L**2):.2f} %")
                lines.append(f"| {sun:g} | {p['label']} | " + " | ".join(cells) + " |")
        lines.append("")
        lines.append(f"(vector I - scalar radiance) / scalar radiance, +- one combined standard error; preset {a.preset}, "
                     f"{a.intensity_paths} paths each; {time.time() - t1:.0f} s")
    if a.intensity_suns and "renderer" in parts:
        t2 = time.time()
        lines += ["", "| sun (deg) | probe | DoLP 450 nm: reference / renderer | DoLP 650 nm: reference / renderer "
                  "| I 450 nm: renderer - reference | I 650 nm: renderer - reference |",
                  "| ---: | --- | ---: | ---: | ---: | ---: |"]
        for sun in [float(x) for x in a.intensity_suns.split(",")]:
            r = run(a.skyspec, a.preset, sun, [], a.paths, a.set, [450, 650], compare=True)
            for p in r["probes"]:
                cells, intensity = [], []
                for i in range(2):
                    s_mc, s_r, e = p["stokes"][i], p["renderer_stokes"][i], p["stokes_standard_error"][i][0]
                    cells.append(f"{math.hypot(s_mc[1], s_mc[2]) / s_mc[0]:.3f} / {math.hypot(s_r[1], s_r[2]) / s_r[0]:.3f}")
                    intensity.append(f"{100 * (s_r[0] / s_mc[0] - 1):+.2f} % ({(s_r[0] - s_mc[0]) / e:+.1f} sigma)")
                cells += intensity
                lines.append(f"| {sun:g} | {p['label']} | " + " | ".join(cells) + " |")
        lines.append("")
        lines.append(f"degree of linear polarisation, the vector reference (all orders) / the renderer (output.polarisation); "
                     f"the renderer's intensity against the reference's I; preset {a.preset}, {a.paths} paths; "
                     f"{time.time() - t2:.0f} s")
    text = "\n".join(lines)
    print(text)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
