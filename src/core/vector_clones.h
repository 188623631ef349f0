/* RECON_VECTOR_CLONES: on x86-64 the build targets the baseline (SSE2); a
 * function so marked also gets an AVX2 clone, picked at load time when the
 * CPU has it (GCC function multiversioning; clang 14, which builds the fuzz
 * targets, keeps a clone's resolver local to its file, so it gets none). For
 * the whole-row and whole-sample loops of the segmentation and the
 * extraction's pixel checks. No FMA (C11 mode does not contract a * b + c):
 * both clones round alike. */
#ifndef CELADON_CORE_VECTOR_CLONES_H
#define CELADON_CORE_VECTOR_CLONES_H

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define RECON_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RECON_VECTOR_CLONES
#endif

#endif
