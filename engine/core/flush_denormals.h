#pragma once
// Denormal floats flushed to zero (FTZ) and read as zero (DAZ) within a scope, restored after.
//
// Why: Embree switches both on in the TBB worker threads it builds its BVH with (its
// recommended mode for traversal) and leaves the calling thread alone, so the same task gives
// other bits wherever denormals occur depending on whether a worker or the calling thread
// runs it (measured: a PEM solve whose channels ran as tasks differed in 18 texels of 1.8e-35
// by one float ulp from the same solve on the main thread). A task that must give the same
// bits on any thread states the mode itself. x86 (MXCSR) only; elsewhere a no-op.
#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace specula {

class ScopedFlushDenormals {
public:
#if defined(__SSE2__)
    ScopedFlushDenormals() : saved_(_mm_getcsr()) {
        _mm_setcsr(saved_ | kFtz | kDaz);
    }
    ~ScopedFlushDenormals() {
        _mm_setcsr(saved_);
    }
#else
    ScopedFlushDenormals() = default;
#endif
    ScopedFlushDenormals(const ScopedFlushDenormals&) = delete;
    ScopedFlushDenormals& operator=(const ScopedFlushDenormals&) = delete;

private:
#if defined(__SSE2__)
    static constexpr unsigned kFtz = 0x8000u, kDaz = 0x0040u;
    unsigned saved_;
#endif
};

} // namespace specula
