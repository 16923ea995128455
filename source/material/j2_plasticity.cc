#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>

#include <cmath>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  // ---------------------------------------------------------------- PerzynaLaw

  void PerzynaLaw::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Viscosity");
    prm.enter_subsection("Eta");
    TemperatureLaw::declare_parameters(prm, "0", "viscosity eta(T) in MPa^n s^(n/m), >= 0");
    prm.leave_subsection();
    prm.enter_subsection("n");
    TemperatureLaw::declare_parameters(prm, "1", "exponent n(T) on eta (seed eq. 14), > 0");
    prm.leave_subsection();
    prm.enter_subsection("m");
    TemperatureLaw::declare_parameters(prm, "1", "rate sensitivity m(T) (seed eq. 14), > 0");
    prm.leave_subsection();
    prm.declare_entry("Strain reference", "1", Patterns::Double(0),
                      "eps_eta in eta(eps, T) = eta(T) (1 + eps/eps_eta)^a, dimensionless, > 0.");
    prm.declare_entry("Strain exponent", "0", Patterns::Double(),
                      "a in eta(eps, T) = eta(T) (1 + eps/eps_eta)^a, dimensionless (0: no "
                      "dependence on plastic strain).");
    prm.leave_subsection();
  }

  void PerzynaLaw::parse_parameters(ParameterHandler  &prm,
                                    const Scene       &scene,
                                    const std::string &path,
                                    const double       T_ref)
  {
    const std::string p = path + "/Viscosity";
    prm.enter_subsection("Viscosity");
    prm.enter_subsection("Eta");
    eta.parse_parameters(prm, scene, p + "/Eta", T_ref);
    prm.leave_subsection();
    prm.enter_subsection("n");
    n.parse_parameters(prm, scene, p + "/n", T_ref);
    prm.leave_subsection();
    prm.enter_subsection("m");
    m.parse_parameters(prm, scene, p + "/m", T_ref);
    prm.leave_subsection();
    strain_reference = prm.get_double("Strain reference");
    strain_exponent  = prm.get_double("Strain exponent");
    prm.leave_subsection();
    enabled = true;
    if (eta.reference() < 0)
      scene.fail(p + "/Eta/Value", "= " + std::to_string(eta.reference()) + ": expected eta >= 0");
    if (!(n.reference() > 0))
      scene.fail(p + "/n/Value", "= " + std::to_string(n.reference()) + ": expected n > 0");
    if (!(m.reference() > 0))
      scene.fail(p + "/m/Value", "= " + std::to_string(m.reference()) + ": expected m > 0");
    if (!(strain_reference > 0))
      scene.fail(p + "/Strain reference", "must be > 0");
  }

  PerzynaLaw::Value PerzynaLaw::evaluate(const double eps, const double dp, const double dt,
                                         const double T) const
  {
    Value v;
    const double eta_T = eta.value(T);
    if (!enabled || eta_T <= 0 || dp <= 0)
      {
        // The derivative at dp = 0 is infinite for m > 1; callers keep dp > 0.
        return v;
      }
    const double nT = n.value(T), mT = m.value(T);
    const double g    = std::pow(1 + eps / strain_reference, strain_exponent);
    const double e    = eta_T * g; // η(ε̄, T)
    const double rate = dp / dt;
    v.stress          = std::pow(e, 1 / nT) * std::pow(rate, 1 / mT);
    // d/dΔε̄: the rate term and η's dependence on ε̄ = ε̄_n + Δε̄.
    const double dlng = strain_exponent / (strain_reference + eps);
    v.derivative      = v.stress * (1 / (mT * dp) + dlng / nT);
    // ∂/∂T of ln V = (1/n) ln η − (1/m) ... with n(T), m(T), η(T).
    const double dlnV = eta.derivative(T) / (eta_T * nT) -
                        n.derivative(T) / (nT * nT) * std::log(e) -
                        m.derivative(T) / (mT * mT) * std::log(rate);
    v.temperature_derivative = v.stress * dlnV;
    return v;
  }

  // ---------------------------------------------------------------- J2Model

  void J2Model::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Elasticity");
    ElasticLaw::declare_parameters(prm);
    prm.leave_subsection();
    HardeningLaw::declare_parameters(prm);
    PerzynaLaw::declare_parameters(prm);
  }

  void J2Model::parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path)
  {
    prm.enter_subsection("Elasticity");
    elastic.parse_parameters(prm, scene, path + "/Elasticity");
    prm.leave_subsection();
    if (plastic)
      hardening.parse_parameters(prm, scene, path);
  }

  namespace
  {
    class J2Point : public MaterialPoint
    {
    public:
      explicit J2Point(const J2Model &model)
        : model(model)
      {}

      void update(const MaterialIncrement &increment,
                  const MaterialRequest    request,
                  MaterialResponse        &response) override
      {
        if (!increment.adiabatic)
          {
            compute(increment, increment.temperature, increment.temperature_increment, request,
                    response);
            return;
          }
        // Armero–Simo: the step's own heating changes the temperature the
        // return map sees. ΔT_ad = Δt (χẆirr + Ẇthel)/(ρc) is a scalar
        // fixed point; secant iteration (it contracts strongly for metals).
        double x0 = 0, f0 = 0, x1 = 0, f1 = 0;
        for (unsigned int it = 0; it < 50; ++it)
          {
            compute(increment, increment.temperature + x1, increment.temperature_increment + x1,
                    request, response);
            f1 = response.adiabatic_temperature_increment - x1;
            if (std::abs(f1) <= 1e-12 * (1 + std::abs(x1)))
              break;
            double next = x1 + f1; // plain fixed point first
            if (it > 0 && f1 != f0)
              next = x1 - f1 * (x1 - x0) / (f1 - f0);
            x0 = x1, f0 = f1, x1 = next;
            if (it == 49)
              throw MaterialPointError("the adiabatic temperature change did not converge");
          }
        response.adiabatic_temperature_increment = x1;
      }

      void commit() override
      {
        stress_n = current;
        eps_n    = eps_c;
      }
      void revert() override
      {
        current = stress_n;
        eps_c   = eps_n;
      }
      const SymmetricTensor<2, 3> &stress() const override { return current; }
      const SymmetricTensor<2, 3> &committed_stress() const override { return stress_n; }
      double equivalent_plastic_strain() const override { return eps_c; }
      void   set_stress(const SymmetricTensor<2, 3> &s) override { stress_n = current = s; }

      std::vector<double> save_state() const override
      {
        std::vector<double> state;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            state.push_back(stress_n[i][j]);
        state.push_back(eps_n);
        return state;
      }
      void load_state(const std::vector<double> &state) override
      {
        unsigned int k = 0;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            stress_n[i][j] = state.at(k++);
        eps_n   = state.at(k);
        current = stress_n;
        eps_c   = eps_n;
      }

    private:
      void compute(const MaterialIncrement &inc, double T, double dT, MaterialRequest request,
                   MaterialResponse &response);
      /// Δε̄ solving r(Δε̄) = q_tr − 3GΔε̄ − σᵥ(ε̄ₙ + Δε̄) − V(Δε̄) = 0.
      double return_map(double q_tr, double G, double T, double dt, unsigned int &iterations) const;

      const J2Model        &model;
      SymmetricTensor<2, 3> stress_n, current;
      double                eps_n = 0, eps_c = 0;
    };

    double J2Point::return_map(const double q_tr, const double G, const double T, const double dt,
                               unsigned int &iterations) const
    {
      auto residual = [&](const double dp, double &slope) {
        const auto Y = model.hardening.evaluate(eps_n + dp, T);
        const auto V = model.viscosity.evaluate(eps_n + dp, dp, dt, T);
        slope        = -3 * G - Y.slope - V.derivative;
        return q_tr - 3 * G * dp - Y.stress - V.stress;
      };
      // The root is bracketed by [0, q_tr/3G]: r(0) > 0 (plastic branch) and
      // r(q_tr/3G) = −σᵥ − V < 0 while the yield stress is positive.
      double lo = 0, hi = q_tr / (3 * G), slope = 0;
      if (residual(hi, slope) > 0)
        throw MaterialPointError("no plastic solution: the yield stress is not positive after "
                                 "the increment (T = " + std::to_string(T) + " K)");
      const auto Y0 = model.hardening.evaluate(eps_n, T);
      double     dp = std::min(0.5 * hi, (q_tr - Y0.stress) / (3 * G + std::max(Y0.slope, 0.)));
      const double tolerance = 1e-13 * q_tr;
      for (iterations = 1; iterations <= 200; ++iterations)
        {
          const double r = residual(dp, slope);
          if (std::abs(r) <= tolerance)
            return dp;
          (r > 0 ? lo : hi) = dp;
          double next = dp - r / slope;
          // Safeguard: stay inside the bracket, else bisect (steep rate terms, m ≫ 1).
          if (!(next > lo && next < hi) || !std::isfinite(next))
            next = 0.5 * (lo + hi);
          if (std::abs(next - dp) <= 1e-16 * std::max(dp, 1e-300) || hi - lo <= 1e-16 * hi)
            return next;
          dp = next;
        }
      throw MaterialPointError("the return map did not converge in 200 iterations");
    }

    void J2Point::compute(const MaterialIncrement &inc, const double T, const double dT,
                          const MaterialRequest request, MaterialResponse &response)
    {
      const ElasticLaw           &el   = model.elastic;
      const double                K    = el.bulk_modulus(T);
      const double                G    = el.shear_modulus(T);
      const double                beta = el.thermal_expansion;
      static const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();

      // Trial state: rotated σ_n plus H(T) : (Δε − βΔT I), eq. (9), (10), (19).
      const Tensor<2, 3> &R = inc.rotation_increment;
      const SymmetricTensor<2, 3> rotated =
        symmetrize(R * Tensor<2, 3>(stress_n) * transpose(R));
      const SymmetricTensor<2, 3> de      = inc.strain_increment - beta * dT * I;
      const double                tr_de   = trace(de);
      const SymmetricTensor<2, 3> trial   = rotated + K * tr_de * I + 2 * G * deviator(de);
      const SymmetricTensor<2, 3> s_trial = deviator(trial);
      const double                norm_s  = s_trial.norm();
      const double                q_trial = std::sqrt(1.5) * norm_s;

      double                dp = 0, H = 0;
      HardeningLaw::Value   Y, Y_start;
      PerzynaLaw::Value     V;
      response.return_iterations = 0;
      if (model.plastic)
        {
          Y = Y_start = model.hardening.evaluate(eps_n, T);
          if (!(Y.stress > 0))
            throw MaterialPointError("the yield stress is " + std::to_string(Y.stress) +
                                     " MPa <= 0 at T = " + std::to_string(T) +
                                     " K (thermal softening removed all strength)");
          if (q_trial > Y.stress)
            {
              dp = return_map(q_trial, G, T, inc.time_step, response.return_iterations);
              Y  = model.hardening.evaluate(eps_n + dp, T);
              V  = model.viscosity.evaluate(eps_n + dp, dp, inc.time_step, T);
              H  = Y.slope + V.derivative;
            }
        }

      const SymmetricTensor<2, 3> n = norm_s > 0 ? s_trial / norm_s : SymmetricTensor<2, 3>();
      current = trial - std::sqrt(6.) * G * dp * n; // radial return
      eps_c   = eps_n + dp;

      response.stress                    = current;
      response.equivalent_plastic_strain = eps_c;

      if (request & request_tangent)
        {
          // Constant fourth-order tensors, built once (building them per call
          // cost a tenth of the assembly).
          static const SymmetricTensor<4, 3> I_dev = deviator_tensor<3>();
          static const SymmetricTensor<4, 3> IxI   = outer_product(I, I);
          static const SymmetricTensor<4, 3> I_sym = identity_tensor<3>();
          if (dp > 0)
            {
              // Consistent tangent of the radial return (Simo & Hughes 1998, box 3.2,
              // with H' including the viscous term of eq. 18).
              const double a = 3 * G * dp / q_trial, b = 3 * G / (3 * G + H);
              const SymmetricTensor<4, 3> nn = outer_product(n, n);
              response.tangent = K * IxI + 2 * G * ((1 - a) * I_dev + (a - b) * nn);
              response.sensitivity_is_identity    = false;
              response.rotated_stress_sensitivity = I_sym - b * nn - a * (I_dev - nn);
            }
          else
            {
              response.tangent                 = K * IxI + 2 * G * I_dev;
              response.sensitivity_is_identity = true;
            }
        }

      if (request & request_temperature_derivative)
        {
          // ∂σ/∂T_{n+1} at fixed Δε and σ_n (T_n fixed, so ∂ΔT/∂T = 1).
          const double                g  = el.relative_modulus_derivative(T);
          const SymmetricTensor<2, 3> dtrial =
            g * (K * tr_de * I + 2 * G * deviator(de)) - 3 * K * beta * I;
          SymmetricTensor<2, 3> ds = dtrial;
          if (dp > 0)
            {
              const double dG     = g * G;
              const double dq     = std::sqrt(1.5) * (n * dtrial);
              const double ddp    = (dq - 3 * dG * dp - Y.temperature_derivative -
                                  V.temperature_derivative) / (3 * G + H);
              const SymmetricTensor<2, 3> dn = (deviator(dtrial) - (n * dtrial) * n) / norm_s;
              ds -= std::sqrt(6.) * ((dG * dp + G * ddp) * n + G * dp * dn);
            }
          response.stress_temperature_derivative = ds;
        }

      // Heat sources over the step (always cheap; needed by the adiabatic loop).
      const double dt     = inc.time_step;
      const double q_end  = q_trial - 3 * G * dp;
      const double q_old  = std::sqrt(1.5) * deviator(stress_n).norm();
      // Ẇirr = σ̄ ε̄̇ (eq. 21) with σ̄ averaged over the step (exact for linear
      // hardening); flow starts at the yield stress if the step began elastic.
      const double work = dp > 0 ? 0.5 * (std::max(q_old, Y_start.stress) + q_end) * dp : 0.;
      response.plastic_work_rate        = work / dt;
      response.plastic_dissipation_rate = el.taylor_quinney * work / dt;
      // Ẇthel = −3Kβ T tr(Δεᵉ)/Δt (plastic flow is isochoric), doc/thermodynamics.md.
      response.thermoelastic_heating_rate = -3 * K * beta * T * tr_de / dt;
      response.adiabatic_temperature_increment =
        (el.taylor_quinney * work - 3 * K * beta * T * tr_de) / (el.density * el.heat_capacity);
    }
  } // namespace

  std::unique_ptr<MaterialPoint> J2Model::create_point() const
  {
    return std::make_unique<J2Point>(*this);
  }
} // namespace anvil
