#pragma once

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /// A named point of the reference configuration (Output/Probes), mm.
  template <int dim>
  struct ProbePoint
  {
    std::string        name;
    dealii::Point<dim> point;
  };

  /// Reads Output/Probes ('name: x, y[, z]; ...'); InputError on a bad item.
  template <int dim>
  std::vector<ProbePoint<dim>> parse_probe_points(const std::string &text, const Scene &scene);
} // namespace anvil
