// The J2 point's isothermal update has an instance of its own for the
// common law (J2Model::Kernel::simple: constant moduli and expansion, linear
// hardening without softening, rate-independent), which reads K, G and β
// as constants and skips the laws' branches. Its answers must be the
// general instance's, bit for bit: the same law written so that the
// general instance runs it (a modulus temperature factor `linear` with
// softening 0: g(T) = 1 (1 − 0 (T − T_ref)) = 1, the constant's value)
// is the independent reference. Random σₙ, ΔR (identity, planar, 3D), Δε
// (elastic and plastic), T, ΔT, Δt and J; every request the mechanics and
// the point driver make. Every response field and the point's state are
// compared as bits, the sign of a zero included (except in ∂σ/∂T: the
// reference's g'/g is −0).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/j2_plasticity.h>

#include "check.h"

#include <cmath>
#include <cstring>
#include <random>
#include <string>

using namespace dealii;
using namespace anvil;

namespace
{
  std::mt19937                           rng(19);
  std::uniform_real_distribution<double> uniform(-1, 1);

  const std::string elastic = "subsection Elasticity\n set Young's modulus = 200000\n"
                              " set Poisson's ratio = 0.3\n set Thermal expansion = 1.2e-5\n";
  const std::string linear  = "subsection Hardening\n set Model = linear\n"
                              " set Initial yield stress = 250\n set Hardening modulus = 1000\nend\n";
  // The same law through TemperatureLaw's general path.
  const std::string general_factor = " subsection Modulus temperature factor\n  set Model = linear\n"
                                     "  set Value = 1\n  set Softening = 0\n end\n";

  /// Equal as numbers, and as bits unless @p sign_free (then ±0 alike).
  bool same(const double a, const double b, const bool sign_free)
  {
    return sign_free ? a == b || (std::isnan(a) && std::isnan(b)) :
                       std::memcmp(&a, &b, sizeof a) == 0;
  }
  template <class Tensor>
  bool same_raw(const Tensor &a, const Tensor &b, const bool sign_free)
  {
    for (unsigned int i = 0; i < a.n_independent_components; ++i)
      if (!same(a.access_raw_entry(i), b.access_raw_entry(i), sign_free))
        return false;
    return true;
  }

  /// ΔR: Hughes–Winget of a random spin (planar: about the 2-axis only).
  Tensor<2, 3> rotation(const int kind)
  {
    Tensor<2, 3> R = unit_symmetric_tensor<3>();
    if (kind == 0)
      return R;
    Tensor<2, 3> w;
    w[0][1] = 0.05 * uniform(rng), w[1][0] = -w[0][1];
    if (kind == 2)
      {
        w[0][2] = 0.05 * uniform(rng), w[2][0] = -w[0][2];
        w[1][2] = 0.05 * uniform(rng), w[2][1] = -w[1][2];
      }
    const Tensor<2, 3> I = unit_symmetric_tensor<3>();
    return invert(I - 0.5 * w) * (I + 0.5 * w);
  }
} // namespace

int main()
{
  testing::Checks check(testing::Checks::Print::failures_only);
  const auto simple_model  = MaterialFactory::create_from_text("set Model = J2\n" + elastic + "end\n" + linear);
  const auto general_model =
    MaterialFactory::create_from_text("set Model = J2\n" + elastic + general_factor + "end\n" + linear);
  auto       simple  = simple_model->create_point();
  auto       general = general_model->create_point();
  const auto &ks = dynamic_cast<const J2Model &>(*simple_model).kernel();
  const auto &kg = dynamic_cast<const J2Model &>(*general_model).kernel();
  check(ks.simple && !kg.simple, "the plain law has the simple instance, the reference not");

  const MaterialRequest requests[] = {
    request_stress,
    request_stress | request_tangent,
    request_stress | request_tangent | request_factored_tangent,
    request_stress | request_tangent | request_temperature_derivative | request_dissipation,
    request_stress | request_temperature_derivative | request_dissipation};
  unsigned int n_plastic = 0, n_compared = 0, mismatches = 0;
  for (unsigned int k = 0; k < 600; ++k)
    {
      SymmetricTensor<2, 3> sigma_n, de;
      const int             kind = k % 3; // identity, planar, 3D
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          if (kind == 2 || (i < 2 && j < 2) || i == j)
            sigma_n[i][j] = 200 * uniform(rng), de[i][j] = (k % 2 ? 0.02 : 2e-4) * uniform(rng);
      MaterialIncrement inc;
      inc.strain_increment      = de;
      inc.rotation_increment    = rotation(kind);
      inc.temperature           = 293 + 300 * (1 + uniform(rng));
      inc.temperature_increment = 5 * uniform(rng);
      inc.time_step             = 1e-3 * (1.5 + uniform(rng));
      inc.volume_ratio          = 1 + 0.01 * uniform(rng);
      const MaterialRequest request = requests[k % 5];
      simple->set_stress(sigma_n);
      general->set_stress(sigma_n);
      // A committed plastic strain, through the checkpoint format.
      std::vector<double> state = simple->save_state();
      state.back()              = 0.05 * (1 + uniform(rng));
      simple->load_state(state);
      general->load_state(state);

      MaterialResponse rs, rg;
      simple->update(inc, request, rs);
      general->update(inc, request, rg);
      const bool sign_free = false;
      bool       ok =
        same_raw(rs.stress, rg.stress, sign_free) && rs.factored.active == rg.factored.active &&
        rs.sensitivity_is_identity == rg.sensitivity_is_identity &&
        same(rs.plastic_work_rate, rg.plastic_work_rate, sign_free) &&
        same(rs.plastic_dissipation_rate, rg.plastic_dissipation_rate, sign_free) &&
        same(rs.thermoelastic_heating_rate, rg.thermoelastic_heating_rate, sign_free) &&
        same(rs.equivalent_plastic_strain, rg.equivalent_plastic_strain, sign_free) &&
        rs.return_iterations == rg.return_iterations &&
        same_raw(rs.volume_ratio_sensitivity, rg.volume_ratio_sensitivity, sign_free) &&
        same_raw(simple->stress(), general->stress(), sign_free);
      if (request & request_tangent)
        {
          if (rs.factored.active)
            {
              const FactoredTangent &a = rs.factored, &b = rg.factored;
              ok = ok && same(a.bulk, b.bulk, sign_free) && same(a.deviatoric, b.deviatoric, sign_free) &&
                   same(a.normal, b.normal, sign_free) &&
                   same(a.sensitivity_deviatoric, b.sensitivity_deviatoric, sign_free) &&
                   same(a.sensitivity_normal, b.sensitivity_normal, sign_free);
              for (unsigned int c = 0; c < 6; ++c)
                ok = ok && same(a.n[c], b.n[c], sign_free);
            }
          else
            ok = ok && same_raw(rs.tangent, rg.tangent, sign_free) &&
                 (rs.sensitivity_is_identity ||
                  same_raw(rs.rotated_stress_sensitivity, rg.rotated_stress_sensitivity, sign_free));
        }
      if (request & request_temperature_derivative)
        // (g'/g is +0 for the constant factor, −0 for the linear one with ω = 0.)
        ok = ok && same_raw(rs.stress_temperature_derivative, rg.stress_temperature_derivative, true);
      n_plastic += rs.equivalent_plastic_strain > state.back();
      ++n_compared;
      mismatches += ok ? 0 : 1;
      check(ok, "update " + std::to_string(k) + " (rotation kind " + std::to_string(kind) +
                  ", request " + std::to_string(request) + "): simple = general bit for bit");
    }
  std::cout << "  " << n_compared << " updates compared, " << n_plastic << " plastic, "
            << mismatches << " different\n";
  check(n_plastic > 100 && n_plastic < n_compared - 100, "both branches compared");
  return check.finish();
}
