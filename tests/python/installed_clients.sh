#!/usr/bin/env bash
# Real clients of the Python module that install_into_venv.sh installed into VENV, from a folder
# outside the repository: mypy (Debian's python3-mypy) type-checks a script against the installed
# stubs (the stub-only package skyspec-stubs, PEP 561) and must report exactly the one type error
# planted in it; mypy's stubtest finds the installed stubs equal to the installed module; and
# docs/python.md's Jupyter recipe, run as written in a scratch home, gives a kernel that Debian's
# Jupyter finds and runs a notebook in. Usage: installed_clients.sh VENV
set -euo pipefail
venv=$1
allowlist=$(cd "$(dirname "${BASH_SOURCE[0]}")/../../python" && pwd)/stubtest-allowlist.txt
outside=$(mktemp -d)
trap 'rm -rf "$outside"' EXIT
cd "$outside"
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
