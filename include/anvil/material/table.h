#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * Tables of (x, y) pairs, the form of tabulated laws ("x1 : y1, x2 : y2, ...").
   * parse_table() reads one and checks it (at least two pairs, x strictly
   * increasing; errors via Scene::fail naming @p path); interpolate() is linear
   * in between and, outside, constant or extended with the end slope.
   */
  void parse_table(const std::string   &text,
                   const Scene         &scene,
                   const std::string   &path,
                   std::vector<double> &x,
                   std::vector<double> &y);

  /// {y(v), dy/dv}; outside the table: constant (@p extrapolate false) or the end slope.
  inline std::pair<double, double> interpolate(const std::vector<double> &x,
                                               const std::vector<double> &y,
                                               const double               v,
                                               const bool                 extrapolate)
  {
    if (v <= x.front() && !extrapolate)
      return {y.front(), 0};
    if (v >= x.back() && !extrapolate)
      return {y.back(), 0};
    std::size_t i = std::upper_bound(x.begin(), x.end(), v) - x.begin();
    i             = std::min<std::size_t>(std::max<std::size_t>(i, 1), x.size() - 1);
    const double slope = (y[i] - y[i - 1]) / (x[i] - x[i - 1]);
    return {y[i - 1] + slope * (v - x[i - 1]), slope};
  }
} // namespace anvil
