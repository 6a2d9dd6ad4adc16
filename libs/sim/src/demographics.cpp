// demographics — speed draws by population, age table and impairment; see demographics.hpp.
#include "demographics.hpp"

#include <algorithm>
#include <array>

#include "throng/core/rng.hpp"

namespace throng::sim {
namespace {

// RiMEA guideline test 7 (after Weidmann 1993, walking speed over age on level ground): under 30,
// 30 to 50, over 50. The under-30 band starts with children; the table's ages span 5 to 80 years.
constexpr std::array<AgeSpeedBand, 3> kWeidmannAge{{
    {kMinAge, 30.0f, 0.58f, 1.61f},
    {30.0f, 50.0f, 1.41f, 1.54f},
    {50.0f, kMaxAge + 1.0f, 0.68f, 1.41f},
}};

}  // namespace

std::span<const AgeSpeedBand> weidmannAgeBands() { return kWeidmannAge; }

Walker drawWalker(const PopulationDesc& pop, std::uint64_t seed, std::uint64_t id) {
  core::Rng rng(seed, id, core::RngPurpose::Speed);
  Walker w;
  const DemographicsDesc& demo = pop.demographics;
  if (demo.table == SpeedTable::None) {
    const double v = pop.speedSd > 0 ? rng.normal(pop.speedMean, pop.speedSd) : pop.speedMean;
    w.speed = static_cast<float>(std::clamp(v, static_cast<double>(pop.speedMin), static_cast<double>(pop.speedMax)));
    return w;
  }
  // Three draws, always in this order: impaired or not, age, speed within the band.
  w.impaired = rng.uniform() < demo.impaired;
  w.age = static_cast<float>(rng.uniform(demo.ageMin, demo.ageMax));
  const double u = rng.uniform();
  float lo = kImpairedSpeedMin, hi = kImpairedSpeedMax;
  if (!w.impaired) {
    const AgeSpeedBand* band = &kWeidmannAge.back();
    for (const AgeSpeedBand& b : kWeidmannAge) {
      if (w.age < b.ageMax) {
        band = &b;
        break;
      }
    }
    lo = band->speedMin;
    hi = band->speedMax;
  }
  w.speed = static_cast<float>(lo + (hi - lo) * u);
  return w;
}

}  // namespace throng::sim
