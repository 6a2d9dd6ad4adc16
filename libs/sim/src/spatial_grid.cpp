// SpatialGrid (spatial_grid.hpp): the counting-sort rebuild of the grid each tick and the k-nearest
// query (a SIMD gather of candidate spans ring by ring, then exact ranking with ties by row).
#include "throng/sim/spatial_grid.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "throng/core/assert.hpp"
#include "throng/core/simd.hpp"
#include "lanes.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace throng::sim {

void SpatialGrid::configure(const core::Aabb& bounds, float cellSize) {
  THRONG_ASSERT(cellSize > 0.0f && bounds.valid());
  cellSize_ = cellSize;
  invCell_ = 1.0f / cellSize;
  originX_ = bounds.min.x;
  originY_ = bounds.min.y;
  nx_ = std::max(1, static_cast<int>(std::ceil((bounds.max.x - bounds.min.x) * invCell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((bounds.max.y - bounds.min.y) * invCell_)));
  cellStart_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
}

void SpatialGrid::rebuild(std::span<const float> posX, std::span<const float> posY, const core::TaskSystem& tasks) {
  const std::size_t n = posX.size();
  size_ = n;
  avx2_ = core::simdPath() == core::SimdPath::Avx2;
  rows_.assign(n + kPad, 0);
  // Counting sort, stable in row order (serial: a few ns per agent). Each row's cell is worked out
  // twice rather than kept: 4 bytes an agent less at a million agents.
  const auto cellOf = [&](std::size_t i) {
    return static_cast<std::size_t>(cellY(posY[i])) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cellX(posX[i]));
  };
  std::fill(cellStart_.begin(), cellStart_.end(), 0u);
  for (std::size_t i = 0; i < n; ++i) ++cellStart_[cellOf(i) + 1];
  for (std::size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  cursor_.assign(cellStart_.begin(), cellStart_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) rows_[cursor_[cellOf(i)]++] = static_cast<std::uint32_t>(i);
  cellX_.assign(n + kPad, 0.0f);
  cellY_.assign(n + kPad, 0.0f);
  tasks.parallelFor(n, tasks.grain(4096), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      cellX_[k] = posX[rows_[k]];
      cellY_[k] = posY[rows_[k]];
    }
  });
}

namespace {

/// Candidates buffered on the stack (a multiple of 8); k <= kStackCandidates / 4 needs no heap.
constexpr std::size_t kStackCandidates = 256;
/// Rings gathered before the first stop test: at ~1 agent per cell and k = 10 the 10th neighbour
/// lies in ring 2 nearly always, so the 5 × 5 block is read as five spans.
constexpr int kFirstRings = 2;
/// Above this many candidates the final ranking (quadratic) is preceded by a selection pass.
constexpr std::size_t kRankMax = 64;

// The kernels below are written once for vectors of W lanes (GCC/Clang vector extensions) and
// inlined into two entry points: W = 4 (the portable path: SSE2 on x86-64, NEON on ARM) and W = 8
// compiled for AVX2. They use comparisons, integer sums, permutes and the exactly rounded float
// subtraction, multiplication and addition in the same order, so both give the same bits.
using simd::Lanes;

/// A candidate as one integer: the bits of its distance² (a non-negative float, whose bit patterns
/// order like its values) above its row, so comparing keys compares (distance², row).
inline std::uint64_t packKey(float d2, std::uint32_t row) {
  return (static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(d2)) << 32) | row;
}

/// Candidate buffer: distances² and rows in two arrays, gathered unordered.
struct Candidates {
  float* d2;
  std::uint32_t* row;
  std::size_t capacity;  // a multiple of 8, > 2k
  std::size_t n = 0;
};

/// Keeps only the k smallest (distance², row) candidates (k < c.n), unordered.
void keepSmallest(Candidates& c, std::size_t k, std::uint64_t* scratch) {
  for (std::size_t i = 0; i < c.n; ++i) scratch[i] = packKey(c.d2[i], c.row[i]);
  std::nth_element(scratch, scratch + (k - 1), scratch + c.n);
  for (std::size_t i = 0; i < k; ++i) {
    c.d2[i] = std::bit_cast<float>(static_cast<std::uint32_t>(scratch[i] >> 32));
    c.row[i] = static_cast<std::uint32_t>(scratch[i]);
  }
  c.n = k;
}

/// Fills the entries from c.n up to the next multiple of W with +inf (never below a limit, never
/// before anyone in the ranking) and returns that multiple; the capacity is a multiple of 8.
template <int W>
THRONG_KERNEL std::size_t padCandidates(Candidates& c) {
  const std::size_t m = (c.n + (W - 1)) & ~static_cast<std::size_t>(W - 1);
  for (std::size_t i = c.n; i < m; ++i) {
    c.d2[i] = std::numeric_limits<float>::infinity();
    c.row[i] = 0;
  }
  return m;
}

/// For each mask of `Lanes` bits, the lanes whose bit is set, in order, one per byte (the rest 0):
/// the lane order that packs a block's kept candidates to its front.
template <class Word, unsigned Lanes>
constexpr std::array<Word, (1u << Lanes)> packTable() {
  std::array<Word, (1u << Lanes)> t{};
  for (Word mask = 0; mask < t.size(); ++mask) {
    Word out = 0, at = 0;
    for (Word lane = 0; lane < Lanes; ++lane) {
      if ((mask >> lane) & 1u) out |= lane << (8 * at++);
    }
    t[mask] = out;
  }
  return t;
}
constexpr auto kPack4 = packTable<std::uint32_t, 4>();

/// Keeps, in order, the candidates with distance² < limit (entries up to the next multiple of W
/// padded with +inf), four at a time: each group of four is written whole at the output cursor in
/// the order kPack4 gives for its mask, and the cursor moves by the count kept (no branch on the
/// data, no per-candidate dependency). Writes never pass the group being read.
template <int W>
THRONG_KERNEL void keepBelow(Candidates& c, float limit) {
  const std::size_t end = padCandidates<W>(c);
  std::size_t m = 0;
  for (std::size_t j = 0; j < end; j += 4) {
    const float* d = c.d2 + j;
    const std::uint32_t* r = c.row + j;
#if defined(__x86_64__)
    const auto mask = static_cast<unsigned>(_mm_movemask_ps(_mm_cmplt_ps(_mm_loadu_ps(d), _mm_set1_ps(limit))));  // SSE2
#else
    const unsigned mask = static_cast<unsigned>(d[0] < limit) | static_cast<unsigned>(d[1] < limit) << 1 |
                          static_cast<unsigned>(d[2] < limit) << 2 | static_cast<unsigned>(d[3] < limit) << 3;
#endif
    const std::uint32_t pick = kPack4[mask];
    const unsigned l0 = pick & 3u, l1 = (pick >> 8) & 3u, l2 = (pick >> 16) & 3u, l3 = (pick >> 24) & 3u;
    const float d0 = d[l0], d1 = d[l1], d2 = d[l2], d3 = d[l3];
    const std::uint32_t r0 = r[l0], r1 = r[l1], r2 = r[l2], r3 = r[l3];
    c.d2[m] = d0, c.d2[m + 1] = d1, c.d2[m + 2] = d2, c.d2[m + 3] = d3;
    c.row[m] = r0, c.row[m + 1] = r1, c.row[m + 2] = r2, c.row[m + 3] = r3;
    m += static_cast<std::size_t>(std::popcount(mask));
  }
  c.n = m;
}

#if defined(__x86_64__)
constexpr auto kPack8 = packTable<std::uint64_t, 8>();

/// keepBelow with eight lanes and AVX2's lane permute: one compare, one mask, two permutes per
/// group of eight. Not inlined (its instructions need the AVX2 target, which inlining checks
/// against the template that calls it).
[[gnu::target("avx2"), gnu::noinline]] void keepBelowAvx2(Candidates& c, float limit) {
  const std::size_t end = (c.n + 7) & ~std::size_t{7};  // padded by padCandidates<8>
  const __m256 lim = _mm256_set1_ps(limit);
  std::size_t m = 0;
  for (std::size_t j = 0; j < end; j += 8) {
    const __m256 d = _mm256_loadu_ps(c.d2 + j);
    const __m256i r = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c.row + j));
    const auto mask = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d, lim, _CMP_LT_OQ)));
    const __m256i perm = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(static_cast<long long>(kPack8[mask])));
    _mm256_storeu_ps(c.d2 + m, _mm256_permutevar8x32_ps(d, perm));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(c.row + m), _mm256_permutevar8x32_epi32(r, perm));
    m += static_cast<std::size_t>(std::popcount(mask));
  }
  c.n = m;
}
#endif

/// Drops candidates that cannot be among the k smallest: four trial limits around `expectedSq`
/// (the k-th distance² the local density predicts) are counted in one pass, and the candidates
/// below the smallest limit with at least k below it are kept — exact for any trial limits. With
/// no such limit, those below `admitted` are kept (this also drops the scan's +inf fillers).
template <int W>
THRONG_KERNEL void narrow(Candidates& c, std::size_t k, float expectedSq, float admitted) {
  using L = Lanes<W>;
  const float limits[4] = {0.8f * expectedSq, expectedSq, 1.25f * expectedSq, 1.6f * expectedSq};
  typename L::F lim0, lim1, lim2, lim3;
  L::fill(lim0, limits[0]), L::fill(lim1, limits[1]), L::fill(lim2, limits[2]), L::fill(lim3, limits[3]);
  typename L::I below0, below1, below2, below3;
  L::fill(below0, 0), L::fill(below1, 0), L::fill(below2, 0), L::fill(below3, 0);
  const std::size_t end = padCandidates<W>(c);
  for (std::size_t j = 0; j < end; j += W) {
    typename L::F d;
    std::memcpy(&d, c.d2 + j, sizeof d);
    below0 -= static_cast<typename L::I>(d < lim0);  // masks are -1 where true
    below1 -= static_cast<typename L::I>(d < lim1);
    below2 -= static_cast<typename L::I>(d < lim2);
    below3 -= static_cast<typename L::I>(d < lim3);
  }
  const auto kk = static_cast<std::int32_t>(k);
  const int lane = L::sum(below0) >= kk ? 0 : L::sum(below1) >= kk ? 1 : L::sum(below2) >= kk ? 2 : L::sum(below3) >= kk ? 3 : 4;
  const float keep = lane == 4 ? admitted : std::min(admitted, limits[lane]);
#if defined(__x86_64__)
  if constexpr (W == 8) {
    keepBelowAvx2(c, keep);  // already padded to a multiple of 8 above
    return;
  }
#endif
  keepBelow<W>(c, keep);
}

/// Writes the rows of the min(k, n) smallest candidates to out in (distance², row) order: each
/// candidate's rank is the number of candidates before it in that order (W at a time; the row
/// comparison runs only for the rare exact distance ties). `ranked` holds n rows.
template <int W>
THRONG_KERNEL std::size_t writeRanked(Candidates& c, std::size_t k, std::uint32_t* ranked, std::uint32_t* out) {
  using L = Lanes<W>;
  const std::size_t m = padCandidates<W>(c);
  for (std::size_t i = 0; i < c.n; ++i) {
    const float di = c.d2[i];
    typename L::F dv;
    L::fill(dv, di);
    typename L::I less, equal;
    L::fill(less, 0), L::fill(equal, 0);
    for (std::size_t j = 0; j < m; j += W) {
      typename L::F dj;
      std::memcpy(&dj, c.d2 + j, sizeof dj);
      less -= static_cast<typename L::I>(dj < dv);  // masks are -1 where true
      equal -= static_cast<typename L::I>(dj == dv);
    }
    auto rank = static_cast<std::size_t>(L::sum(less));
    if (L::sum(equal) > 1) {
      for (std::size_t j = 0; j < c.n; ++j) rank += static_cast<std::size_t>(c.d2[j] == di && c.row[j] < c.row[i]);
    }
    ranked[rank] = c.row[i];
  }
  const std::size_t count = std::min(k, c.n);
  std::copy(ranked, ranked + count, out);
  return count;
}

/// Scratch for one query: the candidate arrays (on the stack for small k, per-thread heap for large).
struct QueryScratch {
  alignas(32) float stackD2[kStackCandidates];
  std::uint32_t stackRow[kStackCandidates];
  std::uint64_t stackKeys[kStackCandidates];
  std::uint32_t stackRanked[kStackCandidates];
  Candidates c{stackD2, stackRow, kStackCandidates};
  std::uint64_t* keys = stackKeys;
  std::uint32_t* ranked = stackRanked;

  explicit QueryScratch(std::size_t k) {
    if (k <= kStackCandidates / 4) return;
    thread_local std::vector<float> heapD2;
    thread_local std::vector<std::uint32_t> heapRow;
    thread_local std::vector<std::uint64_t> heapKeys;
    thread_local std::vector<std::uint32_t> heapRanked;
    const std::size_t capacity = (4 * k + 7) & ~std::size_t{7};
    if (heapD2.size() < capacity) {
      heapD2.resize(capacity);
      heapRow.resize(capacity);
      heapKeys.resize(capacity);
      heapRanked.resize(capacity);
    }
    c = Candidates{heapD2.data(), heapRow.data(), capacity};
    keys = heapKeys.data();
    ranked = heapRanked.data();
  }
};

/// Gathers candidates around (x, y). Admission: distance² < limit (range² at first; after a
/// selection pass, just above the k-th smallest distance², so ties with it are kept and settled by
/// row at the end). Self is the only candidate with its row.
template <int W>
struct Gather {
  using L = Lanes<W>;
  Candidates& c;
  std::size_t k;
  std::uint64_t* keys;
  float rangeSq;
  float limit;
  const float* ex;
  const float* ey;
  const std::uint32_t* er;
  float qx, qy;
  std::uint32_t self;

  /// Entries [first, last) (cells of one grid row are contiguous: one span per grid row), W at a
  /// time and without branches: every entry is stored, those that cannot be neighbours (self, out
  /// of range or past the limit, lanes beyond the span) with distance² = +inf; narrow() drops
  /// them. The arrays' slack (kPad) makes the last group of W readable.
  THRONG_KERNEL void operator()(std::uint32_t first, std::uint32_t last) {
    typename L::I lane, infBits, selfRow;
    for (int l = 0; l < W; ++l) lane[l] = l;
    L::fill(infBits, 0x7f800000);
    L::fill(selfRow, static_cast<std::int32_t>(self));
    typename L::F vx, vy;
    L::fill(vx, qx), L::fill(vy, qy);
    while (first < last) {
      if (c.n + W > c.capacity) {
        keepSmallest(c, k, keys);
        limit = std::min(rangeSq, std::nextafter(*std::max_element(c.d2, c.d2 + k), std::numeric_limits<float>::infinity()));
      }
      const std::size_t room = (c.capacity - c.n) & ~static_cast<std::size_t>(W - 1);
      const std::uint32_t stop = first + static_cast<std::uint32_t>(std::min<std::size_t>(last - first, room));
      typename L::F lim;
      L::fill(lim, limit);
      std::size_t n = c.n;
      for (std::uint32_t i = first; i < stop; i += W) {
        typename L::F px, py;
        typename L::I rows;
        std::memcpy(&px, ex + i, sizeof px);
        std::memcpy(&py, ey + i, sizeof py);
        std::memcpy(&rows, er + i, sizeof rows);
        const typename L::F dx = px - vx, dy = py - vy;
        const typename L::F d2 = dx * dx + dy * dy;
        typename L::I remaining;
        L::fill(remaining, static_cast<std::int32_t>(stop - i));
        const typename L::I valid = static_cast<typename L::I>(d2 < lim) & (rows != selfRow) & (lane < remaining);
        typename L::I d2Bits;
        std::memcpy(&d2Bits, &d2, sizeof d2Bits);
        const typename L::I bits = (d2Bits & valid) | (infBits & ~valid);
        std::memcpy(c.d2 + n, &bits, sizeof bits);
        std::memcpy(c.row + n, &rows, sizeof rows);
        n += std::min<std::size_t>(W, stop - i);
      }
      c.n = n;
      first = stop;
    }
  }

  /// Are there at least k candidates with distance² < limitSq (then no farther cell matters)?
  [[nodiscard]] THRONG_KERNEL bool haveK(float limitSq) const {
    if (c.n < k) return false;
    std::size_t below = 0;
    for (std::size_t i = 0; i < c.n; ++i) below += static_cast<std::size_t>(c.d2[i] < limitSq);
    return below >= k;
  }
};

}  // namespace

template <class G>
THRONG_KERNEL int SpatialGrid::gatherRings(float x, float y, float range, G& gather) const {
  auto cellIndex = [&](int gx, int gy) {
    return static_cast<std::size_t>(gy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(gx);
  };
  const int cx = cellX(x), cy = cellY(y);
  // Distance from (x, y) to the nearest edge of its own cell: ring r cells are at least
  // (r - 1) * cellSize + edge away.
  const float fx = x - (originX_ + static_cast<float>(cx) * cellSize_);
  const float fy = y - (originY_ + static_cast<float>(cy) * cellSize_);
  const float edge = std::max(0.0f, std::min(std::min(fx, cellSize_ - fx), std::min(fy, cellSize_ - fy)));
  const int maxRing = static_cast<int>(std::ceil(range * invCell_)) + 1;
  // Rings 0..firstRings at once, one span per grid row (extra cells only cost time: the ranking
  // is exact over any superset of the true neighbours).
  const int firstRings = std::min(kFirstRings, maxRing);
  const int bx0 = std::max(0, cx - firstRings), bx1 = std::min(nx_ - 1, cx + firstRings);
  const int by0 = std::max(0, cy - firstRings), by1 = std::min(ny_ - 1, cy + firstRings);
  const int blockCells = (bx1 - bx0 + 1) * (by1 - by0 + 1);
  for (int gy = by0; gy <= by1; ++gy) gather(cellStart_[cellIndex(bx0, gy)], cellStart_[cellIndex(bx1, gy) + 1]);
  const float rangeSq = range * range;
  for (int ring = firstRings + 1; ring <= maxRing; ++ring) {
    const float minDist = static_cast<float>(ring - 1) * cellSize_ + edge;
    if (minDist * minDist >= rangeSq) break;
    if (gather.haveK(minDist * minDist)) break;
    const int x0 = cx - ring, x1 = cx + ring, y0 = cy - ring, y1 = cy + ring;
    if (x0 < 0 && y0 < 0 && x1 >= nx_ && y1 >= ny_) break;  // the ring lies wholly outside the grid
    const int gx0 = std::max(0, x0), gx1 = std::min(nx_ - 1, x1);
    if (y0 >= 0) gather(cellStart_[cellIndex(gx0, y0)], cellStart_[cellIndex(gx1, y0) + 1]);
    if (y1 < ny_) gather(cellStart_[cellIndex(gx0, y1)], cellStart_[cellIndex(gx1, y1) + 1]);
    for (int gy = std::max(0, y0 + 1); gy <= std::min(ny_ - 1, y1 - 1); ++gy) {
      if (x0 >= 0) gather(cellStart_[cellIndex(x0, gy)], cellStart_[cellIndex(x0, gy) + 1]);
      if (x1 < nx_) gather(cellStart_[cellIndex(x1, gy)], cellStart_[cellIndex(x1, gy) + 1]);
    }
  }
  return blockCells;
}


template <int W>
THRONG_KERNEL std::size_t SpatialGrid::nearestIn(float x, float y, float range, std::size_t k, std::uint32_t self,
                                                 std::uint32_t* out) const {
  if (k == 0) return 0;
  QueryScratch scratch(k);
  Gather<W> gather{scratch.c, k, scratch.keys, range * range, range * range, cellX_.data(), cellY_.data(), rows_.data(),
                   x, y, self};
  const int blockCells = gatherRings(x, y, range, gather);
  // Uniform density over the block read first: the k-th neighbour is expected at π r² ρ = k.
  Candidates& c = scratch.c;
  const float area = static_cast<float>(blockCells) * cellSize_ * cellSize_;
  narrow<W>(c, k, static_cast<float>(k) * area / (3.14159265f * static_cast<float>(std::max<std::size_t>(c.n, 1))), gather.limit);
  if (c.n > kRankMax && c.n > k) keepSmallest(c, k, scratch.keys);
  return writeRanked<W>(c, k, scratch.ranked, out);
}

std::size_t SpatialGrid::nearest(float x, float y, float range, std::size_t k, std::uint32_t self,
                                 std::uint32_t* out) const {
#if defined(__x86_64__)
  if (avx2_) return nearestAvx2(x, y, range, k, self, out);
#endif
  return nearestIn<4>(x, y, range, k, self, out);
}

#if defined(__x86_64__)
[[gnu::target("avx2")]] std::size_t SpatialGrid::nearestAvx2(float x, float y, float range, std::size_t k,
                                                            std::uint32_t self, std::uint32_t* out) const {
  return nearestIn<8>(x, y, range, k, self, out);
}
#else
std::size_t SpatialGrid::nearestAvx2(float x, float y, float range, std::size_t k, std::uint32_t self,
                                     std::uint32_t* out) const {
  return nearestIn<4>(x, y, range, k, self, out);
}
#endif

}  // namespace throng::sim
