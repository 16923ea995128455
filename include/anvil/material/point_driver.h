#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <anvil/material/material_point.h>
#include <anvil/material/objective_rates.h>

#include <array>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * The material-point driver, `anvil --material-point point.prm`: one
   * material point driven along prescribed strain, stress, deformation
   * gradient and temperature paths, one CSV row per step. What a user needs
   * to calibrate a law before running a scene.
   *
   * The .prm file has three sections:
   *
   *   subsection Material   (exactly what MaterialFactory declares)
   *   subsection Path
   *     set Control              = strain | deformation gradient
   *     set End time             = 1                     # s
   *     set Steps                = 100
   *     set Strain               = exx: 0.01*t           # strain control
   *     set Stress               = eyy: 0                # strain control
   *     set Deformation gradient = F11: 1 + t; F12: t    # deformation gradient control
   *     set Temperature          = 293                   # K
   *     set Adiabatic            = false
   *   end
   *   subsection Output
   *     set File    = point.csv       # relative to the .prm file's directory
   *     set Summary =                 # empty: point.summary.json beside the CSV
   *   end
   *
   * Strain control: the components named in Strain (tensor components exx eyy
   * ezz exy eyz exz, not engineering shear) are prescribed; every other
   * component is stress-controlled (the value named in Stress, 0 if not
   * named) and found by a local Newton loop on the point's tangent. ΔR = I,
   * the strain columns are the sum of the increments.
   *
   * Deformation-gradient control: F(t) (identity for the components not
   * named, F(0) = I), Hughes–Winget increments (IncrementalKinematics). The
   * strain columns are the increments accumulated in the co-rotated frame,
   * ε_{n+1} = ΔR ε_n ΔRᵀ + Δε (the sum of Δε when ΔR = I), so that a
   * hypoelastic point has σ = H : ε along any path.
   *
   * Every input is checked (with Scene::fail, naming the entry) before any
   * work; the path is evaluated at every step beforehand.
   */
  class MaterialPointDriver
  {
  public:
    /// Declare Material, Path and Output (a Scene::Declarator ignores body names).
    static void declare_parameters(dealii::ParameterHandler &prm);

    /// Parse and check the parameters of @p scene (already read with
    /// declare_parameters()). Throws InputError on bad input.
    explicit MaterialPointDriver(Scene &scene);
    ~MaterialPointDriver();

    /**
     * Drive the point, write the CSV (only if @p write) and, if @p log, print
     * a one-line summary to it. Throws SimulationError naming the step if the
     * point cannot be updated or the local Newton loop does not converge; the
     * steps done until then are in the CSV.
     */
    void run(bool write, std::ostream *log);

    /// The CSV file name (Output/File, resolved against the .prm's directory).
    const std::string &output_file() const { return file; }
    /// The summary's file name (Output/Summary, or the CSV's with .summary.json).
    const std::string &summary_file() const { return summary; }

  private:
    enum class Control
    {
      strain,
      deformation_gradient
    };

    /// One scalar expression in t.
    using Expression = std::shared_ptr<dealii::FunctionParser<1>>;

    Expression parse(const std::string &expression, const std::string &path,
                     const std::string &what) const;
    static double value(const Expression &f, double t);

    void parse_strain_control(const std::string &strain, const std::string &stress);
    void parse_deformation_gradient(const std::string &text);
    void check_path();

    /// The state a summary reports: the last step done and its response.
    struct Final
    {
      unsigned int                  steps = 0, max_return = 0, max_local = 0;
      double                        time = 0, temperature = 0, wall_time = 0;
      dealii::SymmetricTensor<2, 3> strain;
      MaterialResponse              response;
    };
    /// Write the summary (JSON, point_summary.cc) with @p status.
    void write_summary(const Final &final, const std::string &status) const;

    /// One step t_k -> t_k+1 under strain control; returns the local iterations.
    unsigned int strain_step(unsigned int                   step,
                             double                         t_new,
                             dealii::SymmetricTensor<2, 3> &strain,
                             MaterialIncrement             &increment,
                             MaterialResponse              &response);

    Scene                                &scene;
    std::shared_ptr<const MaterialModel>  model;
    std::unique_ptr<MaterialPoint>        point;

    Control      control   = Control::strain;
    double       end_time  = 1;
    ObjectiveRate objective_rate = ObjectiveRate::jaumann;
    unsigned int n_steps   = 1;
    bool         adiabatic = false;
    std::string  file, summary;

    /// Strain control: per component (xx yy zz xy yz xz) the strain or the stress path.
    std::array<bool, 6>       strain_controlled{};
    std::array<Expression, 6> component_path;
    /// Deformation-gradient control: F_ij(t), null for the identity's value.
    std::array<std::array<Expression, 3>, 3> F_path;
    Expression                               temperature;
  };
} // namespace anvil
