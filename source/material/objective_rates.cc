// The selection of the objective rate and the Green-Naghdi rotation (polar
// decomposition); the log spin lives in logarithmic_rate.cc.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/objective_rates.h>

#include <cmath>
#include <stdexcept>

namespace anvil
{
  using namespace dealii;

  ObjectiveRate objective_rate_from_string(const std::string &name)
  {
    if (name == "Jaumann")
      return ObjectiveRate::jaumann;
    if (name == "Green-Naghdi")
      return ObjectiveRate::green_naghdi;
    if (name == "logarithmic")
      return ObjectiveRate::logarithmic;
    throw std::invalid_argument("unknown objective rate '" + name + "': expected " +
                                objective_rate_selection());
  }

  std::string objective_rate_name(const ObjectiveRate rate)
  {
    switch (rate)
      {
        case ObjectiveRate::green_naghdi:
          return "Green-Naghdi";
        case ObjectiveRate::logarithmic:
          return "logarithmic";
        default:
          return "Jaumann";
      }
  }

  Tensor<2, 3> polar_rotation(const Tensor<2, 3> &F)
  {
    // R = F U⁻¹ with U⁻¹ = Σ λ_a^(-1/2) N_a ⊗ N_a from C = FᵀF = Σ λ_a N_a ⊗ N_a.
    const SymmetricTensor<2, 3> C = symmetrize(transpose(F) * F);
    const auto                  eig = eigenvectors(C, SymmetricTensorEigenvectorMethod::jacobi);
    SymmetricTensor<2, 3>       U_inv;
    for (const auto &e : eig)
      U_inv += (1. / std::sqrt(e.first)) * symmetrize(outer_product(e.second, e.second));
    return F * Tensor<2, 3>(U_inv);
  }
} // namespace anvil
