// The common subset of GLSL and C++/GLM that the shared kernel is written
// in. PRECISE is GLSL `precise` (SPIR-V NoContraction): with the host's
// -ffp-contract=off it keeps every float operation in the same order, so the
// CPU and the shader round identically. OUT marks out-parameters, FN a
// kernel function (inline members in the CPU instance, host/kernel).
// UNUSED marks a parameter kept for a seam that does not use it yet.
// A constant is one literal (0.318309886f, not 1.0f / 3.14159265f, and not
// a product of literals): glslang may fold a constant expression in another
// precision than C++ does, which moved camera paths by an ulp.
#ifndef SPECTRACE_KERNEL_LANG_H
#define SPECTRACE_KERNEL_LANG_H

#ifdef __cplusplus
#define PRECISE
#define OUT(T) T&
#define INOUT(T) T&
#define FN inline
#define UNUSED(x) (void)(x)
#else
#define PRECISE precise
#define OUT(T) out T
#define INOUT(T) inout T
#define FN
#define UNUSED(x)
#endif

#endif  // SPECTRACE_KERNEL_LANG_H
