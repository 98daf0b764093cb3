#include "common/map/placed_keys_avx2.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace slamer {

#if defined(__x86_64__) && defined(__GNUC__)

bool placed_keys_avx2_available() {
  __builtin_cpu_init();  // idempotent; needed where this runs before libgcc's own constructor
  return __builtin_cpu_supports("avx2");
}

__attribute__((target("avx2"))) std::size_t place_dense_keys_avx2(const float* x, const float* y, std::size_t n,
                                                                  float c, float s, float tx, float ty, int32_t width,
                                                                  float width_f, float height_f, int32_t off_key,
                                                                  int32_t* keys) {
  const __m256 vc = _mm256_set1_ps(c), vs = _mm256_set1_ps(s), vtx = _mm256_set1_ps(tx), vty = _mm256_set1_ps(ty);
  const __m256 zero = _mm256_setzero_ps(), vwidth = _mm256_set1_ps(width_f), vheight = _mm256_set1_ps(height_f);
  const __m256i width_cells = _mm256_set1_epi32(width), off_map = _mm256_set1_epi32(off_key);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256 px = _mm256_loadu_ps(x + i), py = _mm256_loadu_ps(y + i);
    const __m256 gx = _mm256_add_ps(_mm256_sub_ps(_mm256_mul_ps(vc, px), _mm256_mul_ps(vs, py)), vtx);
    const __m256 gy = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vs, px), _mm256_mul_ps(vc, py)), vty);
    // Ordered compares: a NaN point is off the grid.
    const __m256 inside =
        _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(gx, zero, _CMP_GE_OQ), _mm256_cmp_ps(gy, zero, _CMP_GE_OQ)),
                      _mm256_and_ps(_mm256_cmp_ps(gx, vwidth, _CMP_LT_OQ), _mm256_cmp_ps(gy, vheight, _CMP_LT_OQ)));
    // On the grid truncation is the floor; off it the key is replaced.
    const __m256i key =
        _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(gy), width_cells), _mm256_cvttps_epi32(gx));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(keys + i),
                        _mm256_blendv_epi8(off_map, key, _mm256_castps_si256(inside)));
  }
  return i;
}

#else

bool placed_keys_avx2_available() {
  return false;
}

std::size_t place_dense_keys_avx2(const float*, const float*, std::size_t, float, float, float, float, int32_t, float,
                                  float, int32_t, int32_t*) {
  return 0;
}

#endif

}  // namespace slamer
