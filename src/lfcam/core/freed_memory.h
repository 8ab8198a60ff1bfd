#pragma once
// Freed memory kept for reuse. glibc's malloc returns large freed blocks to the kernel (blocks
// above a threshold that moves with what was freed, and the heap's top beyond twice it), so a
// loop that makes and frees a few megabytes of scratch a view (the build's and the import's
// resampling, chroma upsampling, decoded images) takes a fresh page fault every 4 KB, every
// view: on a virtual machine whose faults are dear, most of the command's time
// (docs/benchmarks.md, "Freed memory kept for reuse"). A freed block is reused, not added to:
// the peaks measured there are the same within 10%, though what was freed is not handed back.
namespace lfcam {

// Every block comes from the heap (malloc maps none of its own; lfcam maps its largest buffers
// itself: light fields, cost volumes), and the heap keeps what is freed. Call once, first thing
// in main(), before any thread starts; a no-op where malloc is not glibc's
// (AddressSanitizer's).
void KeepFreedMemoryForReuse();

}  // namespace lfcam
