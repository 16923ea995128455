// Stability of the material point update at the extremes, reported as a table.
//
// Each case is one material point (zero initial stress, ε̄ = 0) and ONE update
// with a 3D strain increment of uniaxial-strain (Δε = a e1⊗e1) or pure-shear
// (Δε = a (e1⊗e2 + e2⊗e1)) type, a a multiple of the yield strain σ0/E.
// The test recomputes, independently of the library and from the parameters it
// chose (linear hardening σᵥ = θ(T)(σ0 + h ε̄), θ = 1 − ω(T − T_ref),
// G(T) = G0 g(T)):
//   - the criterion residual from the returned state:
//       J2:      |σ̄ − σᵥ(ε̄)| / σᵥ(ε̄)
//       Perzyna: |σ̄ − σᵥ(ε̄) − η^{1/n} (Δε̄/Δt)^{1/m}| / σ̄        (eq. 18)
//   - the consistency of the plastic strain with the radial return,
//       |σ̄ − (q_trial − 3GΔε̄)| / σ̄,  q_trial = √(3/2)|dev(H:Δε)|;
//   - the branch (plastic iff q_trial > σᵥ(0, T)).
// Cases: increment size 1..1000 × yield strain (J2); Perzyna rate sensitivity
// m = 1..100; Perzyna η from 0 to 1e6 (η → 0 must reproduce J2 to 1e-10);
// linear thermal softening up to and beyond θ = 0 (σᵥ ≤ 0 must be reported
// as anvil::MaterialPointError), also with a temperature-dependent modulus;
// a modulus temperature factor g(T) ≤ 0 alone (K, G ≤ 0 must be reported as
// MaterialPointError naming the moduli); near-incompressibility ν = 0.499;
// extreme Perzyna viscosity η = 1e6..1e12 MPa s^{1/m} with m = 20, 100, with
// η independent of ε̄ (a = 0) and decreasing with it (a = −0.5), where the
// root Δε̄* of the return map is 1e-59..1e-881: the test finds ln Δε̄* itself
// by bisection in ln Δε̄ (no underflow) and requires convergence where
// Δε̄* ≥ 1e-290, and either convergence or Δε̄ = 0 ("elastic to working
// precision", the stress then checked against the criterion at Δε̄*) below.
//
// Passes if every case converged (≤ 200 return iterations) with criterion and
// consistency residuals ≤ 1e-10, or failed with MaterialPointError exactly
// where σᵥ ≤ 0 or K, G ≤ 0 (with a message naming the cause), and η → 0
// matched J2 to 1e-10.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/scene.h>
#include <anvil/material/material_point.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

using namespace dealii;
using namespace anvil;

namespace
{
  constexpr double tolerance      = 1e-10;
  constexpr unsigned int max_iter = 200;

  /// The parameters of one case; the test builds the input from them and
  /// uses the same numbers in its closed forms.
  struct Parameters
  {
    bool   perzyna = false;
    double E = 200000, nu = 0.3;
    double sigma0 = 250, h = 1000;
    double omega = 0, T_ref = 293;  // thermal softening of the yield stress (0: none)
    double omega_g = 0;             // modulus temperature factor g = 1 − ω_g (T − 293)
    double eta = 0, n = 1, m = 1;   // Perzyna
    double a = 0, eps_eta = 0.05;   // η(ε̄) = η (1 + ε̄/ε_η)^a
    double dt = 1e-3;               // s
    double T  = 293;                // K
    char   type       = 'u';        // 'u' uniaxial strain, 's' pure shear
    double multiple   = 10;         // increment / yield strain σ0/E
    bool   compare_j2 = false;      // also run rate-independent J2 and compare
    bool   report_root = false;     // print the return map's root (Perzyna)

    std::string input() const
    {
      std::ostringstream s;
      s.precision(17);
      s << "set Model = " << (perzyna ? "Perzyna" : "J2") << "\n"
        << "subsection Elasticity\n set Young's modulus = " << E << "\n set Poisson's ratio = " << nu
        << "\n set Reference temperature = 293\n";
      if (omega_g != 0)
        s << " subsection Modulus temperature factor\n  set Model = linear\n  set Softening = "
          << omega_g << "\n end\n";
      s << "end\n"
        << "subsection Hardening\n set Model = linear\n set Initial yield stress = " << sigma0
        << "\n set Hardening modulus = " << h << "\n";
      if (omega != 0)
        s << " subsection Thermal softening\n  set Model = linear\n  set Softening coefficient = "
          << omega << "\n  set Reference temperature = " << T_ref << "\n end\n";
      s << "end\n";
      if (perzyna)
        s << "subsection Viscosity\n subsection Eta\n  set Value = " << eta
          << "\n end\n subsection n\n  set Value = " << n << "\n end\n subsection m\n  set Value = "
          << m << "\n end\n set Strain exponent = " << a << "\n set Strain reference = " << eps_eta
          << "\nend\n";
      return s.str();
    }

    // Closed forms, independent of the library.
    double theta() const { return omega != 0 ? 1 - omega * (T - T_ref) : 1.; }
    double G() const { return E / (2 * (1 + nu)) * (1 - omega_g * (T - 293)); }
    double K() const { return E / (3 * (1 - 2 * nu)) * (1 - omega_g * (T - 293)); }
    double yield(const double eps) const { return theta() * (sigma0 + h * eps); }
    double overstress(const double dp) const
    {
      return perzyna && eta > 0 && dp > 0 ?
               std::pow(eta * std::pow(1 + dp / eps_eta, a), 1 / n) * std::pow(dp / dt, 1 / m) :
               0.;
    }
    /// The same in terms of x = ln Δε̄ (Δε̄ may be far below the smallest double).
    double overstress_log(const double x) const
    {
      const double dp = std::exp(x); // 0 if it underflows: then 1 + dp/ε_η = 1
      return perzyna && eta > 0 ?
               std::exp((std::log(eta) + a * std::log1p(dp / eps_eta)) / n + (x - std::log(dt)) / m) :
               0.;
    }
    /// ln Δε̄* of the Perzyna return map q_trial − 3GΔε̄ − σᵥ(Δε̄) − V(Δε̄) = 0 by
    /// bisection in x = ln Δε̄ on [−1e5, ln(q_trial/3G)].
    double log_root(const double q_trial) const
    {
      auto r = [&](const double x) {
        const double dp = std::exp(x);
        return q_trial - 3 * G() * dp - yield(dp) - overstress_log(x);
      };
      double lo = -1e5, hi = std::log(q_trial / (3 * G()));
      for (unsigned int i = 0; i < 200 && hi - lo > 1e-15 * std::abs(hi); ++i)
        (r(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
      return 0.5 * (lo + hi);
    }
    SymmetricTensor<2, 3> increment() const
    {
      const double          a = multiple * sigma0 / E;
      SymmetricTensor<2, 3> de;
      if (type == 'u')
        de[0][0] = a;
      else
        de[0][1] = a;
      return de;
    }
  };

  double von_mises(const SymmetricTensor<2, 3> &s) { return std::sqrt(1.5) * deviator(s).norm(); }

  std::shared_ptr<const MaterialModel> make_model(const std::string &settings)
  {
    return MaterialFactory::create_from_text(settings);
  }

  MaterialResponse run(const Parameters &p)
  {
    const auto        model = make_model(p.input());
    auto              point = model->create_point();
    MaterialIncrement inc;
    inc.strain_increment      = p.increment();
    inc.temperature           = p.T;
    inc.temperature_increment = 0;
    inc.time_step             = p.dt;
    MaterialResponse response;
    point->update(inc, request_stress | request_tangent, response);
    return response;
  }

  std::string number(const double x, const char *format = "%.3e")
  {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, x);
    return buffer;
  }

  unsigned int n_cases = 0, n_passed = 0, n_expected_errors = 0;

  /// Below this root (ln) the update may return Δε̄ = 0: elastic to working precision.
  const double log_working_precision = std::log(1e-290);

  void header(const std::string &title)
  {
    std::cout << "\n" << title << "\n";
    std::printf("%-26s %-34s %5s %5s %11s %10s %9s %9s %9s %4s\n", "case", "parameters", "iter",
                "conv", "sigma_eq", "dp", "crit.res", "cons.res", "vs J2", "ok");
  }

  void check(const std::string &name, const std::string &parameters, const Parameters &p)
  {
    ++n_cases;
    // Expected clear errors: K, G ≤ 0 (checked first), else σᵥ ≤ 0.
    const bool moduli_error = !(p.G() > 0 && p.K() > 0);
    const bool expect_error = moduli_error || !(p.yield(0) > 0);
    const std::string expected_cause  = moduli_error ? "K, G <= 0" : "sigma_v <= 0";
    const std::string expected_phrase = moduli_error ? "elastic moduli are not positive" : "yield stress";

    // q_trial = √(3/2)|dev(H:Δε)| with H = K δ⊗δ + 2G I_dev at T.
    const SymmetricTensor<2, 3> I       = unit_symmetric_tensor<3>();
    const SymmetricTensor<4, 3> H       = p.K() * outer_product(I, I) + 2 * p.G() * deviator_tensor<3>();
    const double                q_trial = von_mises(H * p.increment());
    const bool                  plastic = q_trial > p.yield(0);

    MaterialResponse r;
    std::string      error;
    bool             other_exception = false;
    try
      {
        r = run(p);
      }
    catch (const MaterialPointError &e)
      {
        error = e.what();
      }
    catch (const std::exception &e)
      {
        error           = std::string("unexpected exception: ") + e.what();
        other_exception = true;
      }

    if (!error.empty())
      {
        const bool ok =
          expect_error && !other_exception && error.find(expected_phrase) != std::string::npos;
        n_expected_errors += ok;
        n_passed += ok;
        std::printf("%-26s %-34s %5s %5s %11s %10s %9s %9s %9s %4s\n", name.c_str(),
                    parameters.c_str(), "-", "error", "-", "-", "-", "-", "-", ok ? "yes" : "NO");
        std::cout << "    "
                  << (ok ? "expected clear error (" + expected_cause + "): " :
                      expect_error ? "UNCLEAR (expected " + expected_cause + "): " :
                                     "UNEXPECTED: ")
                  << error << "\n";
        return;
      }

    const double sigma = von_mises(r.stress);
    const double dp    = r.equivalent_plastic_strain;
    const double Y     = p.yield(dp);
    // Perzyna: the root of the return map in ln Δε̄, found by the test.
    const double x_root = p.perzyna && plastic ? p.log_root(q_trial) : 0.;
    // Δε̄ = 0 in the plastic branch where the root is below working precision.
    const bool   underflow = p.perzyna && plastic && !(dp > 0) && x_root < log_working_precision;
    double       criterion;
    if (dp > 0)
      criterion = p.perzyna ? std::abs(sigma - Y - p.overstress(dp)) / sigma :
                              std::abs(sigma - Y) / Y;
    else if (underflow) // the generalized criterion at the true root
      criterion = std::abs(sigma - p.yield(std::exp(x_root)) - p.overstress_log(x_root)) / sigma;
    else // elastic branch: the criterion must not be violated (f ≤ 0)
      criterion = std::max(sigma - Y, 0.) / Y;
    const double consistency = std::abs(sigma - (q_trial - 3 * p.G() * dp)) / sigma;

    double difference = -1;
    if (p.compare_j2)
      {
        Parameters j2 = p;
        j2.perzyna    = false;
        const auto rj = run(j2);
        difference    = (r.stress - rj.stress).norm() / rj.stress.norm();
      }
    const bool must_match = p.compare_j2 && p.eta <= 1e-12;

    bool ok = !expect_error && r.return_iterations <= max_iter && criterion <= tolerance &&
              consistency <= tolerance && ((dp > 0) == plastic || underflow);
    if (must_match)
      ok = ok && difference <= tolerance;
    n_passed += ok;

    std::printf("%-26s %-34s %5u %5s %11.5e %10.4e %9.2e %9.2e %9s %4s\n", name.c_str(),
                parameters.c_str(), r.return_iterations, dp > 0 ? "yes" : underflow ? "e.w.p" : "elast",
                sigma, dp, criterion, consistency,
                difference < 0 ? "-" : number(difference, "%.2e").c_str(), ok ? "yes" : "NO");
    if (p.report_root && p.perzyna && plastic)
      std::cout << "    root dp* = 10^" << number(x_root / std::log(10.), "%.2f") << ": "
                << (dp > 0 ? "converged to dp = " + number(dp) + " in " +
                               std::to_string(r.return_iterations) + " iterations" :
                    underflow ? std::string("below working precision, returned elastic (dp = 0, ") +
                                  std::to_string(r.return_iterations) + " iterations)" :
                                std::string("returned dp = 0 but dp* is representable"))
                << "\n";
    if (expect_error)
      std::cout << "    FAILED: " << expected_cause
                << " but the update did not throw MaterialPointError\n";
    else if ((dp > 0) != plastic && !underflow)
      std::cout << "    FAILED: wrong branch (q_trial = " << q_trial
                << ", sigma_v = " << p.yield(0) << ")\n";
    else if (!ok)
      std::cout << "    FAILED: q_trial = " << q_trial << " MPa, sigma_v(eps) = " << Y
                << " MPa, overstress " << p.overstress(dp) << " MPa\n";
  }

  std::string type_name(const char type) { return type == 'u' ? "uniax" : "shear"; }
} // namespace

int main()
{
  std::cout << "Material point stability at the extremes: one update from the virgin state.\n"
               "E = 200000 MPa, nu = 0.3 (unless stated), linear hardening sigma_v = theta(T) "
               "(250 + 1000 eps) MPa,\nyield strain 1.25e-3; 'uniax' = uniaxial strain, 'shear' = "
               "pure shear increment.\n"
               "crit.res: J2 |s - sv|/sv, Perzyna |s - sv - eta^(1/n) (dp/dt)^(1/m)|/s "
               "(elastic: max(s - sv, 0)/sv);\n"
               "cons.res: |s - (q_trial - 3 G dp)|/s;  vs J2: |sigma - sigma_J2|/|sigma_J2|.\n";

  header("1. Increment size, rate-independent J2, linear hardening");
  for (const char type : {'u', 's'})
    for (const double k : {1., 10., 100., 1000.})
      {
        Parameters p;
        p.type     = type;
        p.multiple = k;
        check("J2 " + number(k, "%g") + "x " + type_name(type), "s0=250 h=1000", p);
      }

  header("2. Perzyna rate sensitivity, eta = 100 MPa s, n = 1, dt = 1e-3 s, 100x uniaxial strain");
  for (const double m : {1., 2., 5., 10., 20., 50., 100.})
    {
      Parameters p;
      p.perzyna  = true;
      p.eta      = 100;
      p.m        = m;
      p.multiple = 100;
      check("Perzyna m=" + number(m, "%g"), "eta=100 n=1 m=" + number(m, "%g") + " dt=1e-3", p);
    }

  header("3. Perzyna viscosity, n = 1, dt = 1e-3 s, 10x uniaxial strain (eta <= 1e-12 must equal "
         "J2)");
  for (const double m : {1., 5.})
    for (const double eta : {0., 1e-12, 1e-6, 1e-3, 1., 1e3, 1e6})
      {
        Parameters p;
        p.perzyna    = true;
        p.eta        = eta;
        p.m          = m;
        p.multiple   = 10;
        p.compare_j2 = true;
        check("Perzyna eta=" + number(eta, "%g"), "eta=" + number(eta, "%g") + " n=1 m=" +
                                                    number(m, "%g") + " dt=1e-3",
              p);
      }

  header("4. Thermal softening theta = 1 - 2e-3 (T - 293), J2, 10x pure shear (theta = 0 at 793 K)");
  for (const double omega_g : {0., 4e-4})
    for (const double T : {293., 500., 700., 780., 790., 793., 800.})
      {
        Parameters p;
        p.omega    = 2e-3;
        p.omega_g  = omega_g;
        p.T        = T;
        p.type     = 's';
        p.multiple = 10;
        check("J2 T=" + number(T, "%g") + (omega_g != 0 ? " +modulus" : ""),
              "theta=" + number(p.theta(), "%.3g") +
                (omega_g != 0 ? " g=" + number(1 - omega_g * (T - 293), "%.3g") : ""),
              p);
      }
  for (const double T : {293., 700., 790., 793.})
    {
      Parameters p;
      p.perzyna  = true;
      p.eta      = 100;
      p.m        = 5;
      p.omega    = 2e-3;
      p.omega_g  = 4e-4;
      p.T        = T;
      p.type     = 's';
      p.multiple = 10;
      check("Perzyna T=" + number(T, "%g") + " +modulus",
            "m=5 theta=" + number(p.theta(), "%.3g") + " g=" + number(1 - 4e-4 * (T - 293), "%.3g"),
            p);
    }

  header("5. Near-incompressible nu = 0.499, 100x yield strain");
  for (const bool perzyna : {false, true})
    for (const char type : {'u', 's'})
      {
        Parameters p;
        p.nu       = 0.499;
        p.perzyna  = perzyna;
        p.eta      = 100;
        p.m        = 10;
        p.type     = type;
        p.multiple = 100;
        check(std::string(perzyna ? "Perzyna" : "J2") + " nu=0.499 " + type_name(type),
              perzyna ? "eta=100 n=1 m=10 dt=1e-3" : "s0=250 h=1000", p);
      }

  header("6. Modulus temperature factor alone g = 1 - 2e-3 (T - 293), 10x pure shear (g = 0 at 793 "
         "K: K, G <= 0 must be a clear error)");
  for (const bool perzyna : {false, true})
    for (const double T : {293., 700., 793., 900.})
      {
        Parameters p;
        p.perzyna  = perzyna;
        p.eta      = 100;
        p.m        = 5;
        p.omega_g  = 2e-3;
        p.T        = T;
        p.type     = 's';
        p.multiple = 10;
        check(std::string(perzyna ? "Perzyna" : "J2") + " T=" + number(T, "%g") + " g only",
              "g=" + number(1 - 2e-3 * (T - 293), "%.3g") + (perzyna ? " eta=100 m=5" : ""), p);
      }

  header("7. Extreme Perzyna viscosity, n = 1, dt = 1e-3 s, 10x uniaxial strain; eta(eps) = eta (1 + "
         "eps/0.05)^a\n   (e.w.p.: the root dp* underflows, returned elastic to working precision; "
         "crit.res then at dp*)");
  // a = -0.5: eta falls with eps (the rate law bounds the root with eta at the largest eps);
  // h < 0: sigma_v falls (no bound from the rate law: the iteration alone).
  for (const auto &[a, h] : std::vector<std::pair<double, double>>{{0., 1000.}, {-0.5, 1000.}, {0., -1000.}})
    for (const double m : {20., 100.})
      for (const double eta : {1e6, 1e9, 1e12})
        {
          Parameters p;
          p.perzyna     = true;
          p.eta         = eta;
          p.m           = m;
          p.a           = a;
          p.h           = h;
          p.multiple    = 10;
          p.report_root = true;
          check("Perzyna " + number(eta, "%g") + " m=" + number(m, "%g") + (a < 0 ? " a<0" : "") +
                  (h < 0 ? " h<0" : ""),
                "eta=" + number(eta, "%g") + " n=1 m=" + number(m, "%g") + " a=" + number(a, "%g") +
                  " h=" + number(h, "%g"),
                p);
        }

  const bool ok = n_passed == n_cases;
  std::cout << "\n"
            << (ok ? "PASS" : "FAIL") << ": " << n_passed << " of " << n_cases << " cases ok ("
            << n_expected_errors << " expected clear errors where sigma_v <= 0 or K, G <= 0)"
            << std::endl;
  return ok ? 0 : 1;
}
