#pragma once
// Private to the engine: the two step kernels are compiled for several x86-64 levels and the best
// one the CPU supports is picked at load time (GCC function multi-versioning, an ifunc). Binaries
// stay portable (no -march=native); AVX2 / AVX-512 machines run 8 / 16 lanes instead of SSE2's 4.
// Results are bit-identical on every level: the kernels use only correctly rounded IEEE
// operations (+ - * / sqrt, conversions) and the engine is built with -ffp-contract=off, so no
// FMA is ever formed. Sanitizer builds (ifunc resolvers run before the sanitizer runtime) and
// non-GCC or non-x86 builds get the single portable version.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(BHM_ENGINE_NO_DISPATCH)
#define BHM_ENGINE_KERNEL \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define BHM_ENGINE_KERNEL
#endif
