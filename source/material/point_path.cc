// The material-point driver's path: the Strain/Stress/Deformation gradient
// items parsed into expressions of t, and the whole path evaluated once
// before any work, so that a bad path fails with one line naming the entry.
#include <anvil/core/expression.h>
#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/material/point_driver.h>

#include "point_driver_names.h"

#include <cmath>

namespace anvil
{
  using namespace dealii;
  using namespace point_driver_detail;

  namespace
  {
    std::string name_list(const std::vector<std::string> &names)
    {
      std::string out;
      for (unsigned int i = 0; i < names.size(); ++i)
        out += (i ? ", " : "") + names[i];
      return out;
    }

    /// "a: expr; b: expr" -> (name, expression) pairs, in order; empty items are skipped.
    std::vector<std::pair<std::string, std::string>> split_items(const std::string &text,
                                                                 const Scene       &scene,
                                                                 const std::string &path)
    {
      std::vector<std::pair<std::string, std::string>> items;
      for (const auto &item : split_outside_parentheses(text, ';'))
        {
          if (item.empty())
            continue;
          const auto colon = item.find(':');
          if (colon == std::string::npos || trim(item.substr(0, colon)).empty() ||
              trim(item.substr(colon + 1)).empty())
            scene.fail(path, "has the item '" + item +
                               "': expected ';'-separated 'component: expression' items, "
                               "e.g. 'exx: 0.01*t; exy: 0'");
          items.emplace_back(trim(item.substr(0, colon)), trim(item.substr(colon + 1)));
        }
      return items;
    }

    /// Index of @p name in @p names (or in @p aliases), or -1.
    int find_name(const std::string              &name,
                  const std::vector<std::string> &names,
                  const std::vector<std::string> &aliases = {})
    {
      for (unsigned int i = 0; i < names.size(); ++i)
        if (name == names[i] || (i < aliases.size() && name == aliases[i]))
          return static_cast<int>(i);
      return -1;
    }
  } // namespace

  MaterialPointDriver::Expression MaterialPointDriver::parse(const std::string &expression,
                                                             const std::string &path,
                                                             const std::string &what) const
  {
    auto f = parse_expression<1>(expression, "t", false, scene, path, what);
    return f;
  }

  double MaterialPointDriver::value(const Expression &f, const double t)
  {
    return f->value(Point<1>(t));
  }

  void MaterialPointDriver::parse_strain_control(const std::string &strain,
                                                 const std::string &stress)
  {
    const std::vector<std::string> strains(strain_names, strain_names + 6);
    const std::vector<std::string> stresses(stress_names, stress_names + 6);

    strain_controlled.fill(false);
    for (const auto &[name, expression] : split_items(strain, scene, path_strain))
      {
        const int c = find_name(name, strains);
        if (c < 0)
          scene.fail(path_strain, "names the unknown component '" + name + "' (expected one of " +
                                    name_list(strains) + ")");
        if (strain_controlled[c])
          scene.fail(path_strain, "names '" + name + "' twice");
        strain_controlled[c] = true;
        component_path[c]    = parse(expression, path_strain, name);
      }

    std::array<bool, 6> named{};
    for (const auto &[name, expression] : split_items(stress, scene, path_stress))
      {
        const int c = find_name(name, stresses, strains);
        if (c < 0)
          scene.fail(path_stress, "names the unknown component '" + name + "' (expected one of " +
                                    name_list(stresses) + ", or " + name_list(strains) + ")");
        if (named[c])
          scene.fail(path_stress, "names the component " + strains[c] + " twice");
        if (strain_controlled[c])
          scene.fail(path_stress,
                     "names '" + name + "', which 'Path/Strain' prescribes already: each "
                     "component is either strain- or stress-controlled");
        named[c]          = true;
        component_path[c] = parse(expression, path_stress, name);
      }
  }

  void MaterialPointDriver::parse_deformation_gradient(const std::string &text)
  {
    for (const auto &[name, expression] : split_items(text, scene, path_F))
      {
        if (name.size() != 3 || name[0] != 'F' || name[1] < '1' || name[1] > '3' ||
            name[2] < '1' || name[2] > '3')
          scene.fail(path_F, "names the unknown component '" + name +
                               "' (expected F11, F12, ..., F33)");
        const unsigned int i = name[1] - '1', j = name[2] - '1';
        if (F_path[i][j])
          scene.fail(path_F, "names '" + name + "' twice");
        F_path[i][j] = parse(expression, path_F, name);
      }
  }

  void MaterialPointDriver::check_path()
  {
    // Evaluate the whole path once, before any work.
    for (unsigned int k = 0; k <= n_steps; ++k)
      {
        const double t  = end_time * k / n_steps;
        const double T  = value(temperature, t);
        const auto   at = " at t = " + number(t) + " s";
        if (!std::isfinite(T) || !(T > 0))
          scene.fail(path_temperature, "is " + number(T) + " K" + at + ": expected T > 0");
        if (control == Control::strain)
          for (unsigned int c = 0; c < 6; ++c)
            if (component_path[c])
              {
                const double v = value(component_path[c], t);
                const auto  &path = strain_controlled[c] ? path_strain : path_stress;
                if (!std::isfinite(v))
                  scene.fail(path, "gives " + number(v) + " for " + strain_names[c] + at);
                if (k == 0 && strain_controlled[c] && std::abs(v) > 1e-14)
                  scene.fail(path, std::string("gives ") + strain_names[c] + " = " + number(v) +
                                     " at t = 0: the point starts unstrained (expected 0)");
              }
        if (control == Control::deformation_gradient)
          {
            Tensor<2, 3> F = unit_symmetric_tensor<3>();
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                if (F_path[i][j])
                  {
                    F[i][j] = value(F_path[i][j], t);
                    if (!std::isfinite(F[i][j]))
                      scene.fail(path_F, "gives F" + std::to_string(i + 1) +
                                           std::to_string(j + 1) + " = " + number(F[i][j]) + at);
                  }
            if (k == 0 && (F - Tensor<2, 3>(unit_symmetric_tensor<3>())).norm() > 1e-12)
              {
                std::string values;
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int j = 0; j < 3; ++j)
                    if (std::abs(F[i][j] - (i == j)) > 1e-12)
                      values += std::string(values.empty() ? "" : ", ") + "F" +
                                std::to_string(i + 1) + std::to_string(j + 1) + " = " +
                                number(F[i][j]);
                scene.fail(path_F, "gives " + values +
                                     " at t = 0: expected F(0) = I (the point starts undeformed)");
              }
            const double J = determinant(F);
            if (!(J > 0))
              scene.fail(path_F, "gives det F = " + number(J) + at + ": expected det F > 0");
          }
      }
  }
} // namespace anvil
