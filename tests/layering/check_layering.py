#!/usr/bin/env python3
"""The layers of docs/architecture.md, checked: a layer includes only itself and the layers below.

The build already refuses an upward include in any source it compiles (cmake/Layers.cmake: each
layer's object library sees only a view of itself and the layers below). This test adds what a
compile cannot see and proves the mechanism works:

1. every project #include of every file of src/<layer>/ and of every public header (its layer as
   cmake/Layers.cmake assigns it) resolves inside that layer's view, whichever file includes it
   (a header that only higher layers include would otherwise escape), and no include climbs with
   "..";
2. the scan itself finds a planted upward include (so this check can fail);
3. for each layer and the one above it, a probe source that includes a header of the layer above,
   compiled with the exact command the build uses for a source of the lower layer
   (compile_commands.json; preprocessing only, where includes are resolved), FAILS with "No such
   file or directory", and the same probe with the upper layer's command succeeds: an upward
   include fails to compile, and only because of the layering.

usage: check_layering.py SOURCE_DIR BUILD_DIR LAYER [LAYER ...]
"""
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)


def project_includes(text, layers):
    """The includes of a file that name a project header: <layer>/... or skyspec/..."""
    for inc in INCLUDE.findall(text):
        top = inc.split("/")[0]
        if top in layers or top == "skyspec" or ".." in inc.split("/"):
            yield inc


def violations_of(text, layer, views, layers):
    out = []
    for inc in project_includes(text, layers):
        if ".." in inc.split("/"):
            out.append(f'"{inc}" climbs out of its folder')
        elif not os.path.exists(os.path.join(views, layer, inc)):
            out.append(f'"{inc}" is not visible from layer {layer}')
    return out


def public_header_layers(views, layers):
    """public header -> the lowest layer whose view holds it."""
    owner = {}
    for layer in layers:
        folder = os.path.join(views, layer, "skyspec")
        for name in sorted(os.listdir(folder)):
            owner.setdefault(name, layer)
    return owner


def scan(source, views, layers):
    problems = []
    checked = 0
    for layer in layers:
        root = os.path.join(source, "src", layer)
        for dirpath, _, files in os.walk(root):
            for f in sorted(files):
                if f.endswith((".hpp", ".cpp", ".h")):
                    path = os.path.join(dirpath, f)
                    with open(path, encoding="utf-8") as fh:
                        for v in violations_of(fh.read(), layer, views, layers):
                            problems.append(f"{os.path.relpath(path, source)} (layer {layer}): {v}")
                    checked += 1
    owner = public_header_layers(views, layers)
    public = sorted(os.listdir(os.path.join(source, "include", "skyspec")))
    for name in public:
        if name not in owner:
            problems.append(f"include/skyspec/{name}: no layer (cmake/Layers.cmake)")
            continue
        with open(os.path.join(source, "include", "skyspec", name), encoding="utf-8") as fh:
            for v in violations_of(fh.read(), owner[name], views, layers):
                problems.append(f"include/skyspec/{name} (layer {owner[name]}): {v}")
        checked += 1
    return problems, checked


def compile_command_for(build, source, layer):
    with open(os.path.join(build, "compile_commands.json"), encoding="utf-8") as fh:
        entries = json.load(fh)
    # (a unity build compiles the layer's unity_*.cxx files: any source of the layer's target will do)
    for e in entries:
        if f"/skyspec_{layer}.dir/" in e.get("command", ""):
            return e
    raise SystemExit(f"layering: no compile command of a src/{layer}/ source in compile_commands.json")


def compile_probe(entry, probe_text, tmp):
    probe = os.path.join(tmp, "probe.cpp")
    with open(probe, "w", encoding="utf-8") as fh:
        fh.write(probe_text)
    args = shlex.split(entry["command"])
    # Drop the output and the source of the original command; keep every flag and include path.
    kept, skip = [], False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-c", "-MF", "-MT", "-MQ"):
            skip = a != "-c"
            continue
        if a in ("-MD", "-MMD") or a == entry["file"]:
            continue
        kept.append(a)
    # Preprocessing is where an include is resolved or refused ("No such file or directory"), and
    # it costs a fraction of a compile (the probes' headers pull in Eigen, OpenEXR, toml++).
    r = subprocess.run(kept + ["-E", "-o", os.devnull, probe], cwd=entry["directory"], capture_output=True, text=True)
    return r.returncode, r.stderr


def probe_headers(source, views, layers, layer):
    """Headers of `layer` to include from the layer below: its first internal and its first public header."""
    folder = os.path.join(source, "src", layer)
    internal = sorted(f for f in os.listdir(folder) if f.endswith(".hpp"))
    public = sorted(h for h, owner in public_header_layers(views, layers).items() if owner == layer)
    return [f"{layer}/{h}" for h in internal[:1]] + [f"skyspec/{h}" for h in public[:1]]


def main():
    source, build, layers = sys.argv[1], sys.argv[2], sys.argv[3:]
    views = os.path.join(build, "layer-views")
    failures = 0

    problems, checked = scan(source, views, layers)
    for p in problems:
        print("FAIL upward include:", p)
    failures += len(problems)
    print(f"scan: {checked} files, {len(problems)} upward includes")

    # skyspec.hpp, "the public API in one include", includes every public header.
    with open(os.path.join(source, "include", "skyspec", "skyspec.hpp"), encoding="utf-8") as fh:
        umbrella = set(INCLUDE.findall(fh.read()))
    for name in sorted(os.listdir(os.path.join(source, "include", "skyspec"))):
        if name != "skyspec.hpp" and f"skyspec/{name}" not in umbrella:
            print(f"FAIL include/skyspec/skyspec.hpp does not include skyspec/{name}")
            failures += 1

    # The scan finds what it is for.
    planted = violations_of('#include "io/png_image.hpp"\n#include "skyspec/scene.hpp"\n', "colour", views, layers)
    allowed = violations_of('#include "colour/exposure.hpp"\n#include "skyspec/colour.hpp"\n', "io", views, layers)
    if len(planted) != 2 or allowed:
        print("FAIL the scan does not tell a planted upward include from a downward one:", planted, allowed)
        failures += 1
    else:
        print("scan self-test: planted upward includes found, downward ones allowed")

    with tempfile.TemporaryDirectory() as tmp:
        for lower, upper in zip(layers, layers[1:]):
            for header in probe_headers(source, views, layers, upper):
                text = f'#include "{header}"\n'
                rc_low, err_low = compile_probe(compile_command_for(build, source, lower), text, tmp)
                rc_up, err_up = compile_probe(compile_command_for(build, source, upper), text, tmp)
                refused = rc_low != 0 and "No such file or directory" in err_low and header in err_low
                if refused and rc_up == 0:
                    print(f"probe: {lower} including {header}: refused; {upper} including it: compiles")
                else:
                    failures += 1
                    print(f"FAIL probe {lower} -> {header}: lower rc {rc_low}, upper rc {rc_up}")
                    print((err_low + err_up)[-2000:])
    print("layering:", "FAILED" if failures else "passed", f"({failures} problems)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
