# Shared by scripts/render-default.sh and scripts/test.sh: install what is missing, then build.
# Idempotent: with everything installed and built, it only asks dpkg and make.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Debian bookworm packages: compiler and build tools, the libraries the build finds with
# find_package, and the tools the tests use to open our outputs (exrheader, oiiotool, ociocheck),
# to run jobs (Dask) and to run the documented Slurm script on a single-node Slurm; GNU time for
# the merge's memory check (cli_tiles).
SKYSPEC_PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev libopenexr-dev libimath-dev libopencolorio-dev libtbb-dev libpng-dev
  libtomlplusplus-dev libcli11-dev libboost-test-dev libhowardhinnant-date-dev liblcms2-dev libssl-dev libnetcdf-dev libcpp-httplib-dev libgdal-dev
  openexr openimageio-tools opencolorio-tools time
  nlohmann-json3-dev
  pybind11-dev python3-dev python3-numpy python3-matplotlib python3-openimageio
  jupyter-nbconvert python3-ipykernel python3-mypy
  python3-distributed python3-dask python3-netcdf4 slurm-wlm munge
)
# The test command also drives the viewer's page in a real browser (tests/viewer): Debian's
# Chromium, its WebDriver and Selenium's Python client.
SKYSPEC_TEST_PACKAGES=(chromium chromium-driver python3-selenium)
# Only live fuzzing (scripts/fuzz.sh) compiles with clang and its libFuzzer runtime; the main job
# and the test command do not install them.
SKYSPEC_FUZZ_PACKAGES=(clang-14 libclang-rt-14-dev)

# install_missing_packages [PACKAGE...]: SKYSPEC_PACKAGES and these, those not installed yet.
install_missing_packages() {
  local missing=()
  for p in "${SKYSPEC_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "skyspec: installing missing packages: ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

# In CI (CI=true, as CI services set it) compiler warnings are errors: -DSKYSPEC_WERROR=ON.
werror_flag() {
  if [ "${CI:-}" = true ]; then echo -DSKYSPEC_WERROR=ON; else echo -DSKYSPEC_WERROR=OFF; fi
}

# build [TARGET...]: configures build/ (Release, a unity build: SKYSPEC_UNITY in CMakeLists.txt) if
# needed, then builds the targets (all without any). A build/ configured by hand keeps its settings.
build() {
  if [ ! -f build/CMakeCache.txt ] || [ "${CI:-}" = true ]; then
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSKYSPEC_UNITY=ON "$(werror_flag)" >&2
  fi
  local targets=()
  for t in "$@"; do targets+=(--target "$t"); done
  cmake --build build -j"$(nproc)" "${targets[@]}" >&2
}

# The same sources built with AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/
# (-O1 with line tables, a unity build; no Python module: an instrumented extension cannot be
# loaded by an uninstrumented python3).
# This build also proves that the code builds for AVX-512 with warnings as errors: on a CPU with
# AVX-512 it targets x86-64-v4 and runs the tests there; elsewhere it targets the machine and also
# compiles the numeric layers' sources for x86-64-v4 without running them (SKYSPEC_ARCH_CHECK).
build_sanitized() {
  local arch=(-DSKYSPEC_ARCH=native -DSKYSPEC_ARCH_CHECK=x86-64-v4)
  grep -qw avx512f /proc/cpuinfo 2>/dev/null && arch=(-DSKYSPEC_ARCH=x86-64-v4 -DSKYSPEC_ARCH_CHECK=)
  if [ ! -f build-asan/CMakeCache.txt ] || [ "${CI:-}" = true ]; then
    cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
      -DSKYSPEC_SANITIZE=ON -DSKYSPEC_UNITY=ON -DSKYSPEC_BUILD_PYTHON=OFF "${arch[@]}" "$(werror_flag)" >&2
  fi
  cmake --build build-asan -j"$(nproc)" >&2
}

# The fuzz targets (tests/fuzz/) with clang's libFuzzer, ASan and UBSan in build-fuzz/: only the
# library, the CLI's internal library and the three fuzzers are built, not the test suites.
# SKYSPEC_FUZZ_SECONDS is how long each CTest fuzz_* test fuzzes (scripts/fuzz.sh: 60 s by
# default). -O1 with line
# tables only: symbolised reports at a lower compile cost than -O2 -g.
build_fuzz() {
  if [ ! -f build-fuzz/CMakeCache.txt ] || [ "${CI:-}" = true ] || [ -n "${SKYSPEC_FUZZ_SECONDS:-}" ]; then
    cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DSKYSPEC_FUZZ=ON -DSKYSPEC_UNITY=ON \
      -DSKYSPEC_BUILD_TESTS=OFF -DSKYSPEC_BUILD_PYTHON=OFF -DSKYSPEC_ARCH= \
      -DSKYSPEC_FUZZ_SECONDS="${SKYSPEC_FUZZ_SECONDS:-12}" >&2
  fi
  cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene fuzz_cli fuzz_exr >&2
}
