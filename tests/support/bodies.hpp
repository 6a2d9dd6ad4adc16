// How deep two bodies of the anticipation model (avm, the default) overlap: ellipses of shoulder
// width 2r across their heading and depth passageRatio · 2r along it (docs/crowd-model.md). Shared by
// the tests that bound overlaps in crowds walking with the default model.
#pragma once
#include <algorithm>
#include <cmath>

namespace throng::test {

/// How far into each other two bodies of radius sum l and depth ratio q stand [m] (≤ 0: apart):
/// (dx, dy) is the vector between their centres, (oax, oay) and (obx, oby) their unit headings. The
/// distance at which they touch along the line of centres is the mean of each ellipse's reach
/// along it.
inline double ellipseOverlap(double dx, double dy, double oax, double oay, double obx, double oby, double l = 0.4,
                             double q = 0.65) {
  const double d = std::hypot(dx, dy);
  const double ux = d > 1e-9 ? dx / d : 1.0, uy = d > 1e-9 ? dy / d : 0.0;
  const auto reach = [&](double ox, double oy) {
    const double along = ox * ux + oy * uy, across = ox * uy - oy * ux;
    return l * q / std::sqrt(along * along + q * q * across * across);
  };
  return 0.5 * (reach(oax, oay) + reach(obx, oby)) - d;
}

}  // namespace throng::test
