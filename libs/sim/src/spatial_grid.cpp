// SpatialGrid (spatial_grid.hpp): the counting-sort rebuild of the grid each tick and the k-nearest
// query (a SIMD gather of candidate spans ring by ring, then exact ranking with ties by row).
#include "throng/sim/spatial_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "throng/core/assert.hpp"

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

/// Candidates buffered on the stack (a multiple of 4); k <= kStackCandidates / 4 needs no heap.
constexpr std::size_t kStackCandidates = 256;
/// Rings gathered before the first stop test: at ~1 agent per cell and k = 10 the 10th neighbour
/// lies in ring 2 nearly always, so the 5 × 5 block is read as five spans.
constexpr int kFirstRings = 2;
/// Above this many candidates the final ranking (quadratic) is preceded by a selection pass.
constexpr std::size_t kRankMax = 64;

// Four-lane vectors (GCC/Clang vector extensions: SSE2 on x86-64, NEON on ARM).
using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));

/// A candidate as one integer: the bits of its distance² (a non-negative float, whose bit patterns
/// order like its values) above its row, so comparing keys compares (distance², row).
inline std::uint64_t packKey(float d2, std::uint32_t row) {
  return (static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(d2)) << 32) | row;
}

/// Candidate buffer: distances² and rows in two arrays, gathered unordered.
struct Candidates {
  float* d2;
  std::uint32_t* row;
  std::size_t capacity;  // a multiple of 4, > 2k
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

/// Drops candidates that cannot be among the k smallest: four trial limits around `expectedSq`
/// (the k-th distance² the local density predicts) are counted in one pass, and the candidates
/// below the smallest limit with at least k below it are kept — exact for any trial limits. With
/// no such limit, those below `admitted` are kept (this also drops the scan's +inf fillers).
void narrow(Candidates& c, std::size_t k, float expectedSq, float admitted) {
  const F4 limits = {0.8f * expectedSq, expectedSq, 1.25f * expectedSq, 1.6f * expectedSq};
  I4 below = {0, 0, 0, 0};
  for (std::size_t j = 0; j < c.n; ++j) {
    const F4 d = {c.d2[j], c.d2[j], c.d2[j], c.d2[j]};
    below -= static_cast<I4>(d < limits);
  }
  const auto kk = static_cast<std::int32_t>(k);
  const int lane = below[0] >= kk ? 0 : below[1] >= kk ? 1 : below[2] >= kk ? 2 : below[3] >= kk ? 3 : 4;
  const float limit = lane == 4 ? admitted : std::min(admitted, limits[lane]);
  std::size_t m = 0;
  for (std::size_t j = 0; j < c.n; ++j) {
    c.d2[m] = c.d2[j];
    c.row[m] = c.row[j];
    m += static_cast<std::size_t>(c.d2[j] < limit);
  }
  c.n = m;
}

/// Writes the rows of the min(k, n) smallest candidates to out in (distance², row) order: each
/// candidate's rank is the number of candidates before it in that order (four at a time; the row
/// comparison runs only for the rare exact distance ties). `ranked` holds n rows.
std::size_t writeRanked(Candidates& c, std::size_t k, std::uint32_t* ranked, std::uint32_t* out) {
  const std::size_t m = (c.n + 3) & ~std::size_t{3};
  for (std::size_t i = c.n; i < m; ++i) {  // padding: never before anyone, never tied
    c.d2[i] = std::numeric_limits<float>::infinity();
    c.row[i] = 0;
  }
  for (std::size_t i = 0; i < c.n; ++i) {
    const float di = c.d2[i];
    const F4 d4 = {di, di, di, di};
    I4 less = {0, 0, 0, 0}, equal = {0, 0, 0, 0};
    for (std::size_t j = 0; j < m; j += 4) {
      F4 dj;
      std::memcpy(&dj, c.d2 + j, sizeof dj);
      less -= static_cast<I4>(dj < d4);  // masks are -1 where true
      equal -= static_cast<I4>(dj == d4);
    }
    std::size_t rank = static_cast<std::size_t>(less[0] + less[1] + less[2] + less[3]);
    if (equal[0] + equal[1] + equal[2] + equal[3] > 1) {
      for (std::size_t j = 0; j < c.n; ++j) rank += static_cast<std::size_t>(c.d2[j] == di && c.row[j] < c.row[i]);
    }
    ranked[rank] = c.row[i];
  }
  const std::size_t count = std::min(k, c.n);
  std::copy(ranked, ranked + count, out);
  return count;
}

}  // namespace

namespace {

/// Scratch for one query: the candidate arrays (on the stack for small k, per-thread heap for large).
struct QueryScratch {
  alignas(16) float stackD2[kStackCandidates];
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
    const std::size_t capacity = 4 * k;
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
struct Gather {
  Candidates& c;
  std::size_t k;
  std::uint64_t* keys;
  float rangeSq;
  float limit;
  const float* ex;
  const float* ey;
  const std::uint32_t* er;
  F4 qx, qy;
  I4 selfRow;

  /// Entries [first, last) (cells of one grid row are contiguous: one span per grid row), four at
  /// a time and without branches: every entry is stored, those that cannot be neighbours (self,
  /// out of range or past the limit, lanes beyond the span) with distance² = +inf; narrow() drops
  /// them. The arrays' slack makes the last group of four readable.
  inline void operator()(std::uint32_t first, std::uint32_t last) {
    const I4 lane = {0, 1, 2, 3};
    const I4 infBits = {0x7f800000, 0x7f800000, 0x7f800000, 0x7f800000};
    while (first < last) {
      if (c.n + 4 > c.capacity) {
        keepSmallest(c, k, keys);
        limit = std::min(rangeSq, std::nextafter(*std::max_element(c.d2, c.d2 + k), std::numeric_limits<float>::infinity()));
      }
      const std::size_t room = (c.capacity - c.n) & ~std::size_t{3};
      const std::uint32_t stop = first + static_cast<std::uint32_t>(std::min<std::size_t>(last - first, room));
      const F4 lim = {limit, limit, limit, limit};
      std::size_t n = c.n;
      for (std::uint32_t i = first; i < stop; i += 4) {
        F4 px, py;
        I4 rows;
        std::memcpy(&px, ex + i, sizeof px);
        std::memcpy(&py, ey + i, sizeof py);
        std::memcpy(&rows, er + i, sizeof rows);
        const F4 dx = px - qx, dy = py - qy;
        const F4 d2 = dx * dx + dy * dy;
        const I4 remaining = {static_cast<std::int32_t>(stop - i), static_cast<std::int32_t>(stop - i),
                              static_cast<std::int32_t>(stop - i), static_cast<std::int32_t>(stop - i)};
        const I4 valid = static_cast<I4>(d2 < lim) & (rows != selfRow) & (lane < remaining);
        const I4 bits = (std::bit_cast<I4>(d2) & valid) | (infBits & ~valid);
        std::memcpy(c.d2 + n, &bits, sizeof bits);
        std::memcpy(c.row + n, &rows, sizeof rows);
        n += std::min<std::size_t>(4, stop - i);
      }
      c.n = n;
      first = stop;
    }
  }

  /// Are there at least k candidates with distance² < limitSq (then no farther cell matters)?
  [[nodiscard]] bool haveK(float limitSq) const {
    if (c.n < k) return false;
    std::size_t below = 0;
    for (std::size_t i = 0; i < c.n; ++i) below += static_cast<std::size_t>(c.d2[i] < limitSq);
    return below >= k;
  }
};

}  // namespace

std::size_t SpatialGrid::nearest(float x, float y, float range, std::size_t k, std::uint32_t self,
                                 std::uint32_t* out) const {
  if (k == 0) return 0;
  QueryScratch scratch(k);
  const auto s = static_cast<std::int32_t>(self);
  Gather gather{scratch.c, k, scratch.keys, range * range, range * range, cellX_.data(), cellY_.data(), rows_.data(),
                F4{x, x, x, x}, F4{y, y, y, y}, I4{s, s, s, s}};
  const int blockCells = gatherRings(x, y, range, gather);
  // Uniform density over the block read first: the k-th neighbour is expected at π r² ρ = k.
  Candidates& c = scratch.c;
  const float area = static_cast<float>(blockCells) * cellSize_ * cellSize_;
  narrow(c, k, static_cast<float>(k) * area / (3.14159265f * static_cast<float>(std::max<std::size_t>(c.n, 1))), gather.limit);
  if (c.n > kRankMax && c.n > k) keepSmallest(c, k, scratch.keys);
  return writeRanked(c, k, scratch.ranked, out);
}

template <class G>
int SpatialGrid::gatherRings(float x, float y, float range, G& gather) const {
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

}  // namespace throng::sim
