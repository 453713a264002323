// Fault injection for tests/cli/test_faults.sh, loaded with LD_PRELOAD: fdatasync(2) fails with
// EIO, as it does when a disk cannot write what it was given. skyspec flushes each band of its
// spectral EXR with fdatasync (spectral_exr.cpp); the render must stop with a clear error and
// leave no file. fsync(2), which commits the finished file, is left alone.
#include <cerrno>

extern "C" int fdatasync(int) {
  errno = EIO;
  return -1;
}
