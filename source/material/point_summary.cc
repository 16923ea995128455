#include <anvil/core/csv_history.h>
#include <anvil/core/scene.h>
#include <anvil/material/point_driver.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  /// The driver's summary: what a scene's summary.json says of a run (what
  /// was run, how it ended, the answer with units, what it cost), so that
  /// studies and scripts read a point run as they read a scene's.
  void MaterialPointDriver::write_summary(const Final &final, const std::string &status) const
  {
    static const char *const      names[6]            = {"xx", "yy", "zz", "xy", "yz", "xz"};
    static constexpr unsigned int index[6][2]         = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
    const SymmetricTensor<2, 3>  &s                   = final.response.stress;
    Summary                       out;
    out.set("driver", "material point");
    out.set("scene", scene.filename());
    out.set("status", status);
    out.set("model", model->name());
    out.set("control", control == Control::strain ? "strain" : "deformation gradient");
    out.set("adiabatic", adiabatic ? "true" : "false");
    out.set("steps", final.steps);
    out.set("requested_steps", n_steps);
    out.set("time", final.time);
    out.set("end_time", end_time);
    out.set("history", file);
    out.set("temperature", final.temperature);
    for (unsigned int c = 0; c < 6; ++c)
      out.set("stress", std::string("s") + names[c], s[index[c][0]][index[c][1]] + 0.);
    for (unsigned int c = 0; c < 6; ++c)
      out.set("strain", std::string("e") + names[c], final.strain[index[c][0]][index[c][1]] + 0.);
    const SymmetricTensor<2, 3> dev = deviator(s);
    out.set("von_mises", std::sqrt(1.5 * (dev * dev)));
    out.set("pressure", -trace(s) / 3. + 0.);
    out.set("equivalent_plastic_strain", final.response.equivalent_plastic_strain);
    out.set("max_return_iterations", final.max_return);
    out.set("max_local_iterations", final.max_local);
    out.set("wall_time", final.wall_time);
    for (const auto &[key, unit] : std::initializer_list<std::pair<const char *, const char *>>{
           {"time", "s"}, {"end_time", "s"}, {"temperature", "K"}, {"stress", "MPa"},
           {"strain", "-"}, {"von_mises", "MPa"}, {"pressure", "MPa"},
           {"equivalent_plastic_strain", "-"}, {"wall_time", "s"}})
      out.set("units", key, unit);
    out.write(summary);
  }
} // namespace anvil
