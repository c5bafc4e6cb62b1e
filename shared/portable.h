// The dialect every file in shared/ is written in: a strict subset that glslang (GLSL 4.60),
// g++ (C++17 with GLM) and nvcc (CUDA with GLM) all compile to the same arithmetic.
//
// Rules for shared/ (each one broke something somewhere):
//  - Float literals carry an `f`, unsigned ones a `u`. `2.0` is double in C++.
//  - One random draw per statement: GLSL evaluates arguments left to right, g++ right to left.
//  - Parameters are PH_IN (read-only; a const reference in C++), PH_INOUT or PH_OUT.
//    Never assign to a PH_IN parameter.
//  - No recursion, no pointers, no references, no bool/vec2/vec3-array/mat3 members in buffer
//    structs, no `#pragma once` (glslang 12 chokes): include guards only.
//  - Hash and count in `uint`: signed overflow wraps in GLSL and is undefined in C++.
//  - No transcendental functions (sin, cos, exp, pow, log) on any path that decides where a photon
//    or a ray goes: they differ between libm, lavapipe and CUDA, and the backends must agree bit for
//    bit. math.h has a polynomial sinCos2Pi for that. sqrt and division are correctly rounded
//    everywhere we run; FMA contraction is off in the builds that are compared (g++ -ffp-contract=off,
//    nvcc --fmad=false for parity).
//  - Mesa (lavapipe) rewrites a lerp-shaped expression a + t·(b - a), e.g. x·(y - 1) + 1, into
//    an flrp that it computes with an FMA, so the result differs from g++ in the last bit. Declare
//    such a result PH_PRECISE (GLSL `precise`: no contraction, no inexact rewrites; empty in C++).
//  - Names reserved in GLSL stay unused: sample, input, output, filter, buffer, shared, half,
//    active, common, partition, and anything with a double underscore.
//  - A dispatch over a type (LIGHT_*, MATERIAL_*, PRIM_*, MAP_*) is a switch with a case for each
//    value and no default, after PH_COVERS(TYPE_COUNT, cases): the host refuses unknown values, so
//    nothing may pretend to handle them, and a new value fails to compile where it has no case.
//  - A parameter one version of a function does not read is marked PH_UNUSED(name) (C++ warns).
//  - Buffer structs are declared `struct PH_ALIGN16 Name`.
//  - Buffers are reached through BUF(name): a global buffer in GLSL, a member of the Bindings
//    struct in C++ that every such function receives first (BUF_PARAM / BUF_ARG; BUF_PARAM_ALONE
//    and BUF_ARG_ALONE where it is the only parameter).
//  - Atomics are PH_ATOMIC_ADD(buffer element, value) and PH_ATOMIC_MAX, which return the old
//    value: GLSL's atomicAdd/atomicMax, CUDA's, relaxed __atomic builtins on the CPU. PH_RESERVE_SLOT(counter)
//    hands out one slot of an append buffer (on CUDA, one atomic per warp for all its threads).
//    PH_TALLY_ADD and PH_TALLY_MAX are atomics whose old value nobody reads, on counters that
//    every thread of a stage hits (histograms, maxima): on CUDA a warp's threads that name the
//    same counter combine their values first and send one atomic.
//  - PH_ANY_LANE(condition) (C++ and CUDA): whether the condition holds for any lane of the
//    caller's warp that runs the call with it; on the CPU, a warp of one, the condition itself.
//    Only for deciding when lanes do work together, never what the work computes.
#ifndef PHOTON_SHARED_PORTABLE_H
#define PHOTON_SHARED_PORTABLE_H

#ifndef __cplusplus
// ---- GLSL ------------------------------------------------------------------------------------
#define PH_FN
#define PH_FN_OUTLINED
#define PH_IN(T) in T
#define PH_INOUT(T) inout T
#define PH_OUT(T) out T
#define PH_CONST const
#define PH_NAMESPACE_BEGIN
#define PH_NAMESPACE_END
#define PH_PRECISE precise
#define PH_UNUSED(x)
#define PH_COVERS(count, cases)
#define PH_ALIGN16
#define PH_LOAD_VEC4(lvalue) (lvalue)
#define PH_LOAD_UVEC4(lvalue) (lvalue)
#define PH_STORE_UVEC4(lvalue, value) (lvalue) = (value)
#define PH_WEIGHT_EXP(x) exp(x)
#define PH_WEIGHT_DIVIDE(a, b) ((a) / (b))
#define BUF_PARAM
#define BUF_ARG
#define BUF_PARAM_ALONE
#define BUF_ARG_ALONE
#define BUF(name) name
#define PH_ATOMIC_ADD(lvalue, value) atomicAdd(lvalue, value)
#define PH_ATOMIC_MAX(lvalue, value) atomicMax(lvalue, value)
#define PH_RESERVE_SLOT(counter) atomicAdd(counter, 1u)
#define PH_TALLY_ADD(lvalue, value) atomicAdd(lvalue, value)
#define PH_TALLY_MAX(lvalue, value) atomicMax(lvalue, value)

#else
// ---- C++ and CUDA ----------------------------------------------------------------------------
#include <cstdint>
#include <glm/glm.hpp>
#ifdef __CUDACC__
#define PH_FN __host__ __device__ inline
// A real call on CUDA: code that few threads run (a rare branch inside a hot loop) then does not
// set the registers of the loop around it. (GLSL has no calls; the CPU inlines as it likes.)
#define PH_FN_OUTLINED __host__ __device__ __noinline__ inline
#else
#define PH_FN inline
#define PH_FN_OUTLINED inline
#endif
#define PH_IN(T) const T&
#define PH_INOUT(T) T&
#define PH_OUT(T) T&
#define PH_CONST constexpr
#define PH_NAMESPACE_BEGIN \
    namespace photon {     \
    using namespace glm;   \
    using uint = std::uint32_t;
#define PH_NAMESPACE_END }
#define PH_PRECISE
#define PH_UNUSED(x) (void)(x)  // a parameter this version of a function does not need
// Before a switch over a type: it has `cases` cases, which must be all of the type's `count`
// values; adding a value fails the C++ and CUDA builds at every switch that lacks its case (the
// GLSL shaders compile the same source, which g++ checks first).
#define PH_COVERS(count, cases) static_assert((count) == (cases), "a case for every value of " #count)
// Buffer structs are multiples of 16 bytes; saying so lets compilers load them 16 bytes at a time
// (GLM's vec3 alone would make them 4-byte aligned).
#define PH_ALIGN16 alignas(16)
// A vec4 or uvec4 in a buffer, read or written whole. GLM's vectors are 4-byte aligned, so nvcc
// reads and writes them as four 4-byte accesses (GLSL compilers and the CPU do as they like);
// through float4 and uint4 it is one 16-byte access: the denoiser's taps read their neighbours so.
#ifdef __CUDACC__
#define PH_LOAD_VEC4(lvalue) ::photon::loadVec4(&(lvalue))
#define PH_LOAD_UVEC4(lvalue) ::photon::loadUvec4(&(lvalue))
#define PH_STORE_UVEC4(lvalue, value) ::photon::storeUvec4(&(lvalue), (value))
#else
#define PH_LOAD_VEC4(lvalue) (lvalue)
#define PH_LOAD_UVEC4(lvalue) (lvalue)
#define PH_STORE_UVEC4(lvalue, value) (lvalue) = (value)
#endif
// exp(x) and a / b where the result is only a weight (the denoiser's edge-stopping functions): in
// CUDA's fast kernels the special-function unit's approximations, which GLSL drivers use for
// every exp and division anyway; exact on the CPU and in CUDA's parity kernels, which match it.
#if defined(__CUDA_ARCH__) && !defined(PHOTON_PARITY_KERNELS)
#define PH_WEIGHT_EXP(x) __expf(x)
#define PH_WEIGHT_DIVIDE(a, b) __fdividef((a), (b))
#else
#define PH_WEIGHT_EXP(x) exp(x)
#define PH_WEIGHT_DIVIDE(a, b) ((a) / (b))
#endif
#define BUF_PARAM const Bindings &bindings,
#define BUF_ARG bindings,
#define BUF_PARAM_ALONE const Bindings &bindings
#define BUF_ARG_ALONE bindings
#define BUF(name) bindings.name

#ifdef __CUDACC__
#include <cooperative_groups.h>
#include <cooperative_groups/reduce.h>
#include <type_traits>
namespace photon {
__host__ __device__ __forceinline__ glm::vec4 loadVec4(const glm::vec4* p) {
#ifdef __CUDA_ARCH__
    float4 v = *reinterpret_cast<const float4*>(p);
    return glm::vec4(v.x, v.y, v.z, v.w);
#else
    return *p;
#endif
}

__host__ __device__ __forceinline__ glm::uvec4 loadUvec4(const glm::uvec4* p) {
#ifdef __CUDA_ARCH__
    uint4 v = *reinterpret_cast<const uint4*>(p);
    return glm::uvec4(v.x, v.y, v.z, v.w);
#else
    return *p;
#endif
}

__host__ __device__ __forceinline__ void storeUvec4(glm::uvec4* p, const glm::uvec4& value) {
#ifdef __CUDA_ARCH__
    *reinterpret_cast<uint4*>(p) = make_uint4(value.x, value.y, value.z, value.w);
#else
    *p = value;
#endif
}

// One slot of an append buffer for each calling thread: the threads of a warp that append at the
// same time share one atomic, since a million threads on one counter would queue up at L2.
__device__ inline std::uint32_t reserveSlotCoalesced(std::uint32_t* counter) {
    namespace cg = cooperative_groups;
    cg::coalesced_group active = cg::coalesced_threads();
    std::uint32_t base = 0u;
    if (active.thread_rank() == 0) {
        base = atomicAdd(counter, active.size());
    }
    return active.shfl(base, 0) + active.thread_rank();
}

// PH_TALLY_*: the calling threads of a warp that name the same counter reduce their values with
// `op` (one match and one redux instruction) and the first of them sends the atomic. A pixel stage
// that tallies every pixel into a few bins otherwise queues two million atomics at one address.
template <typename Op>
__device__ inline void tallyCoalesced(std::uint32_t* counter, std::uint32_t value, Op op) {
    namespace cg = cooperative_groups;
    cg::coalesced_group same = cg::labeled_partition(cg::coalesced_threads(), reinterpret_cast<unsigned long long>(counter));
    std::uint32_t combined = cg::reduce(same, value, op);
    if (same.thread_rank() == 0) {
        if constexpr (std::is_same_v<Op, cg::plus<std::uint32_t>>) {
            atomicAdd(counter, combined);
        } else {
            atomicMax(counter, combined);
        }
    }
}
}  // namespace photon
#endif
#ifdef __CUDA_ARCH__
#define PH_ATOMIC_ADD(lvalue, value) atomicAdd(&(lvalue), (value))
#define PH_ATOMIC_MAX(lvalue, value) atomicMax(&(lvalue), (value))
#define PH_RESERVE_SLOT(counter) reserveSlotCoalesced(&(counter))
#define PH_TALLY_ADD(lvalue, value) tallyCoalesced(&(lvalue), (value), cooperative_groups::plus<std::uint32_t>())
#define PH_TALLY_MAX(lvalue, value) tallyCoalesced(&(lvalue), (value), cooperative_groups::greater<std::uint32_t>())
#define PH_ANY_LANE(condition) (__any_sync(__activemask(), (condition)) != 0)
#define PH_SPECULATIVE_TRAVERSAL  // intersect.h: the warp's lanes test their leaves together
#else
namespace photon {
// GCC has no __atomic_fetch_max: a compare-and-swap loop, relaxed like the others.
inline std::uint32_t atomicMaxRelaxed(std::uint32_t& target, std::uint32_t value) {
    std::uint32_t old = __atomic_load_n(&target, __ATOMIC_RELAXED);
    while (old < value && !__atomic_compare_exchange_n(&target, &old, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
    return old;
}
}  // namespace photon
#define PH_ATOMIC_ADD(lvalue, value) __atomic_fetch_add(&(lvalue), (value), __ATOMIC_RELAXED)
#define PH_ATOMIC_MAX(lvalue, value) ::photon::atomicMaxRelaxed(lvalue, value)
#define PH_RESERVE_SLOT(counter) PH_ATOMIC_ADD(counter, 1u)
#define PH_TALLY_ADD(lvalue, value) (void)PH_ATOMIC_ADD(lvalue, value)
#define PH_TALLY_MAX(lvalue, value) (void)PH_ATOMIC_MAX(lvalue, value)
#ifndef PH_ANY_LANE  // a test may stand for a warp (tests/speculative_traversal_test.cpp)
#define PH_ANY_LANE(condition) (condition)
#endif
#endif
#endif

#endif
