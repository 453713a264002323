#!/usr/bin/env bash
# Installs the built Python module as a user would, into a fresh virtual environment made with
# Debian's python3 (seeing Debian's numpy, matplotlib and Jupyter), with `cmake --install
# --component python`, and gives the environment its own Jupyter kernel. Then checks, from a
# folder outside the repository and without PYTHONPATH, that `import skyspec` loads the installed
# module with its type stubs beside it and finds the program run_job runs (installed by the same
# component into the environment's bin, found with neither SKYSPEC_CLI nor PATH), and that mypy (Debian's python3-mypy) type-checks a script
# against the installed stubs (the stub-only package skyspec-stubs, PEP 561): it must find the
# module and report the one type error planted in the script; and that mypy's stubtest finds the
# installed stubs equal to the installed module. Usage: install_into_venv.sh PYTHON
# BUILD_DIR VENV
set -euo pipefail
python=$1 build=$2 venv=$3
rm -rf "$venv"
"$python" -m venv --system-site-packages --without-pip "$venv"
cmake --install "$build" --component python --prefix "$venv"
"$venv/bin/python" -m ipykernel install --sys-prefix --name python3 >/dev/null
outside=$(mktemp -d)
trap 'rm -rf "$outside"' EXIT
cd "$outside"
env -u PYTHONPATH -u SKYSPEC_CLI PATH=/usr/bin:/bin "$venv/bin/python" - "$venv" <<'PY'
import os, sys
import skyspec
venv = os.path.realpath(sys.argv[1])
where = os.path.realpath(skyspec.__file__)
assert where.startswith(venv + os.sep), f"skyspec was imported from {where}, not from {venv}"
stubs = os.path.join(os.path.dirname(where), "skyspec.pyi")
assert os.path.exists(stubs), f"no type stubs beside the module ({stubs})"
print(f"import skyspec: {where} (version {skyspec.__version__}), stubs {stubs}")
# run_job's program: installed by the same component, found without SKYSPEC_CLI or PATH.
import skyspec_jobs, subprocess
program = skyspec_jobs.find_skyspec()
assert os.path.realpath(program) == os.path.join(venv, "bin", "skyspec"), f"run_job would run {program}"
version = subprocess.run([program, "--version"], capture_output=True, text=True, check=True).stdout.strip()
print(f"run_job's program: {program} ({version})")
PY
cat >"$outside/typed.py" <<'PY'
import skyspec
version: str = skyspec.__version__
names: list = skyspec.preset_names()
wrong: int = skyspec.__version__  # the planted error: a str is not an int
PY
if env -u PYTHONPATH "$venv/bin/python" -m mypy --no-incremental --cache-dir=/dev/null "$outside/typed.py" \
  >"$outside/mypy.txt" 2>&1; then
  echo "mypy found no error in a script with one:"; cat "$outside/mypy.txt"; exit 1
fi
grep -q 'typed.py:4: error: Incompatible types in assignment (expression has type "str", variable has type "int")' \
  "$outside/mypy.txt" && grep -q "Found 1 error" "$outside/mypy.txt" \
  || { echo "mypy did not check the script against the installed stubs:"; cat "$outside/mypy.txt"; exit 1; }
echo "mypy: the installed stubs are found (skyspec-stubs) and checked"
# stubtest (mypy's): the installed stubs against the installed module, every name and signature;
# python/stubtest-allowlist.txt lists what is as intended and why.
allowlist=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../python" && pwd)/stubtest-allowlist.txt
(cd "$outside" && env -u PYTHONPATH "$venv/bin/python" -m mypy.stubtest skyspec --allowlist "$allowlist") \
  || { echo "stubtest: the installed stubs differ from the module"; exit 1; }
# docs/python.md's Jupyter recipe as written, in a scratch home: a user kernel "skyspec" running
# the environment's Python, which Debian's Jupyter (not the environment's) finds and runs a notebook in.
home="$outside/home"
mkdir -p "$home"
HOME="$home" "$venv/bin/python" -m ipykernel install --user --name skyspec --display-name "Python 3 (skyspec)" >/dev/null
cat >"$outside/check.ipynb" <<'NB'
{"cells": [{"cell_type": "code", "execution_count": null, "metadata": {}, "outputs": [],
  "source": ["import sys, skyspec\n", "print(sys.executable, skyspec.__file__, skyspec.__version__)"]}],
 "metadata": {}, "nbformat": 4, "nbformat_minor": 5}
NB
(cd "$outside" && env -u PYTHONPATH -u JUPYTER_PATH -u JUPYTER_DATA_DIR HOME="$home" PATH=/usr/bin:/bin \
  /usr/bin/jupyter nbconvert --to notebook --execute --ExecutePreprocessor.kernel_name=skyspec \
  --output executed.ipynb check.ipynb >/dev/null 2>&1) || { echo "the Jupyter recipe's kernel did not run the notebook"; exit 1; }
grep -q "$venv/bin/python" "$outside/executed.ipynb" && grep -q "site-packages/skyspec" "$outside/executed.ipynb" \
  || { echo "the notebook did not import skyspec from $venv:"; cat "$outside/executed.ipynb"; exit 1; }
echo "Jupyter: the docs' kernel \"skyspec\" runs $venv/bin/python and imports skyspec"
