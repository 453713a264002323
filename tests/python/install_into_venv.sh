#!/usr/bin/env bash
# Installs the built Python module as a user would, into a fresh virtual environment made with
# Debian's python3 (seeing Debian's numpy, matplotlib and Jupyter), with `cmake --install
# --component python`, and gives the environment its own Jupyter kernel. Then checks, from a
# folder outside the repository and without PYTHONPATH, that `import skyspec` loads the installed
# module with its type stubs beside it and finds the program run_job runs (installed by the same
# component into the environment's bin, found with neither SKYSPEC_CLI nor PATH). The fixture of
# the installed-module tests; installed_clients.sh checks the installed files with other tools.
# Usage: install_into_venv.sh PYTHON BUILD_DIR VENV
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
