#include <anvil/core/scene.h>
#include <anvil/material/hypoelastic.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    class HypoelasticPoint : public MaterialPoint
    {
    public:
      explicit HypoelasticPoint(const HypoelasticModel &model)
        : model(model)
      {}

      void update(const MaterialIncrement &increment,
                  const MaterialRequest    request,
                  MaterialResponse        &response) override
      {
        // Incrementally objective update: rotate σ_n with ΔR, then add H:Δε.
        const Tensor<2, 3> &R       = increment.rotation_increment;
        const Tensor<2, 3>  rotated = R * Tensor<2, 3>(stress_n) * transpose(R);
        current = symmetrize(rotated) + model.elasticity() * increment.strain_increment;
        response.stress                  = current;
        response.sensitivity_is_identity = true;
        if (request & request_tangent)
          response.tangent = model.elasticity();
        response.plastic_dissipation_rate  = 0;
        response.equivalent_plastic_strain = 0;
      }

      void commit() override { stress_n = current; }
      void revert() override { current = stress_n; }

      const SymmetricTensor<2, 3> &stress() const override { return current; }
      const SymmetricTensor<2, 3> &committed_stress() const override { return stress_n; }
      void set_stress(const SymmetricTensor<2, 3> &s) override { stress_n = current = s; }

      std::vector<double> save_state() const override
      {
        std::vector<double> state;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            state.push_back(stress_n[i][j]);
        return state;
      }
      void load_state(const std::vector<double> &state) override
      {
        unsigned int k = 0;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            stress_n[i][j] = state.at(k++);
        current = stress_n;
      }

    private:
      const HypoelasticModel &model;
      SymmetricTensor<2, 3>   stress_n, current;
    };
  } // namespace

  void HypoelasticModel::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Young's modulus", "0", Patterns::Double(0),
                      "Young's modulus E in MPa. Give either this or Bulk modulus (the other 0).");
    prm.declare_entry("Bulk modulus", "0", Patterns::Double(0),
                      "Bulk modulus K in MPa (seed eq. 10). Give either this or Young's modulus.");
    prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(),
                      "Poisson's ratio ν, dimensionless, -1 < ν < 0.5.");
    prm.declare_entry("Density", "7.8e-9", Patterns::Double(0),
                      "Mass density ρ in t/mm³ (= N·s²/mm⁴); steel 7.8e-9, aluminium 2.7e-9.");
  }

  HypoelasticModel::Parameters HypoelasticModel::parse_parameters(ParameterHandler  &prm,
                                                                  const Scene       &scene,
                                                                  const std::string &path)
  {
    Parameters   p;
    const double E  = prm.get_double("Young's modulus");
    const double K  = prm.get_double("Bulk modulus");
    const double nu = prm.get_double("Poisson's ratio");
    if (!(nu > -1. && nu < 0.5))
      scene.fail(path + "/Poisson's ratio",
                 "= " + std::to_string(nu) + ": expected -1 < ν < 0.5");
    if ((E > 0) == (K > 0))
      scene.fail(path + "/Young's modulus",
                 "and 'Bulk modulus': expected exactly one of them > 0 (the other 0)");
    p.bulk_modulus  = K > 0 ? K : E / (3. * (1. - 2. * nu));
    p.shear_modulus = 3. * p.bulk_modulus * (1. - 2. * nu) / (2. * (1. + nu));
    p.density       = prm.get_double("Density");
    return p;
  }

  HypoelasticModel::HypoelasticModel(const Parameters &parameters)
    : parameters(parameters)
  {
    const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
    hooke = parameters.bulk_modulus * outer_product(I, I) +
            2. * parameters.shear_modulus * deviator_tensor<3>();
  }

  std::unique_ptr<MaterialPoint> HypoelasticModel::create_point() const
  {
    return std::make_unique<HypoelasticPoint>(*this);
  }
} // namespace anvil
