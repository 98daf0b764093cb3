// The placing step of LikelihoodField::sum_placed on a dense field, eight end
// points at a time with AVX2 (x86-64 only, chosen at run time): each point is
// rotated and translated onto the grid and gets its cell's row-major key, or
// a given key off the grid. The rounding is the portable code's ((c x - s y) + tx and
// (s x + c y) + ty, no fused multiply-add, which would move points across
// cell edges), so the keys and then the sums are the same to the bit.
//
// Why: with SSE2's four lanes and no 32-bit multiply, placing was over half
// of sum_placed's time; eight lanes halve sum_placed (BM_SumPlaced). The
// lookups stay scalar: AVX2's gathers were no faster than them on the AMD
// EPYC this was measured on.
//
// Only this function is compiled for AVX2 (a target attribute): the rest of
// the build keeps the x86-64 baseline and runs on any x86-64 machine.
#pragma once

#include <cstddef>
#include <cstdint>

namespace slamer {

// Whether this machine runs place_dense_keys_avx2 (always false off x86-64).
bool placed_keys_avx2_available();

// keys[i] = y_i * width + x_i for the cell (x_i, y_i) of point i on a grid of
// width x height cells (width and height as floats too), off_key off it, for
// i = 0 .. k - 1 with k the largest multiple of 8 not over n; returns k. Call
// only where placed_keys_avx2_available().
std::size_t place_dense_keys_avx2(const float* x, const float* y, std::size_t n, float c, float s, float tx, float ty,
                                  int32_t width, float width_f, float height_f, int32_t off_key, int32_t* keys);

}  // namespace slamer
