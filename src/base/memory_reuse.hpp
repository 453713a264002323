// Freed memory kept for reuse in a process that renders many frames (the viewer). glibc returns a
// large block (a frame's spectral image, OpenColorIO's buffers) to the system when it is freed, so
// that the next frame's block of the same size is faulted in again 4 KiB page by page; on a
// virtual machine, while another thread faults pages in too, they can cost more than the frame's
// rendering (docs/performance.md, "The viewer's frames"). After this call the process keeps freed
// blocks in its heap and reuses them.
#pragma once

namespace skyspec {

/// Large blocks from the heap, not from their own mappings; freed memory stays in the heap (up to
/// 1 GiB at its top); one heap for every thread (a thread's own heap would return its blocks
/// again). Call early, before the threads that allocate start. Without glibc: nothing to do.
void keep_freed_memory_for_reuse();

}  // namespace skyspec
