// Names and small helpers the material-point driver's two files share: the
// path parser (point_path.cc) and the driver (point_driver.cc). Private to
// source/material.
#pragma once

#include <deal.II/base/symmetric_tensor.h>

#include <sstream>
#include <string>

namespace anvil
{
  namespace point_driver_detail
  {
    // The 6 independent components of a symmetric 3x3 tensor, in CSV order.
    constexpr unsigned int component_index[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
    const char *const      strain_names[6]       = {"exx", "eyy", "ezz", "exy", "eyz", "exz"};
    const char *const      stress_names[6]       = {"sxx", "syy", "szz", "sxy", "syz", "sxz"};

    inline const std::string path_control     = "Path/Control";
    inline const std::string path_end_time    = "Path/End time";
    inline const std::string path_steps       = "Path/Steps";
    inline const std::string path_strain      = "Path/Strain";
    inline const std::string path_stress      = "Path/Stress";
    inline const std::string path_F           = "Path/Deformation gradient";
    inline const std::string path_temperature = "Path/Temperature";
    inline const std::string path_file        = "Output/File";

    inline double &component(dealii::SymmetricTensor<2, 3> &t, const unsigned int c)
    {
      return t[component_index[c][0]][component_index[c][1]];
    }
    inline double component(const dealii::SymmetricTensor<2, 3> &t, const unsigned int c)
    {
      return t[component_index[c][0]][component_index[c][1]];
    }

    inline std::string number(const double x)
    {
      std::ostringstream s;
      s.precision(6);
      s << x;
      return s.str();
    }
  } // namespace point_driver_detail
} // namespace anvil
