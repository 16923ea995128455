#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <anvil/core/registry.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * What a caller wants from a material point update, like FEValues' update
   * flags: the mechanics asks for stress and tangent, the heat equation for
   * dissipation. Nothing that is not requested is computed.
   */
  enum MaterialRequest : unsigned int
  {
    request_stress                 = 1,
    request_tangent                = 2,
    request_temperature_derivative = 4,
    request_dissipation            = 8,
  };

  inline MaterialRequest operator|(MaterialRequest a, MaterialRequest b)
  {
    return static_cast<MaterialRequest>(static_cast<unsigned int>(a) | static_cast<unsigned int>(b));
  }

  /**
   * One increment [t_n, t_n+1] seen by a material point. Tensors are always
   * 3x3: plane strain and axisymmetric problems embed their 2x2 kinematics
   * (zero or hoop out-of-plane component), so the laws never depend on dim.
   */
  struct MaterialIncrement
  {
    /// Incremental strain Δε = sym(ΔL), ΔL = ∂Δu/∂x at the mid-point configuration.
    dealii::SymmetricTensor<2, 3> strain_increment;
    /// Incremental rotation ΔR (Hughes–Winget: (I - ½Δω)⁻¹(I + ½Δω)); rotates σ_n.
    dealii::Tensor<2, 3> rotation_increment = dealii::unit_symmetric_tensor<3>();
    /// Temperature at t_n+1 and its change over the step, K.
    double temperature           = 293.;
    double temperature_increment = 0.;
    double time_step             = 1.; // s
    /// J = dv/dV at the point: the heat sources are per current volume, the
    /// capacity ρ₀c per reference volume, so ΔT_ad = J Δt (χẆirr + Ẇthel)/(ρ₀c).
    double volume_ratio = 1.;
    /**
     * Adiabatic update (Armero–Simo split): the point heats by its own
     * dissipation and thermoelastic effect during the increment,
     * ρc ΔT = Δt (χ Ẇirr + Ẇthel), solved together with the return map;
     * `temperature`/`temperature_increment` are then the values at the start of
     * the isothermal phase (ΔT from conduction only).
     */
    bool adiabatic = false;
  };

  /**
   * What an update returns. σ = M(σ̃_n, Δε, T) with σ̃_n = ΔR σ_n ΔRᵀ the
   * rotated previous stress; the mechanics linearises the rotation itself and
   * needs ∂σ/∂Δε (`tangent`) and ∂σ/∂σ̃_n (`rotated_stress_sensitivity`,
   * identity for hypoelasticity, so it is flagged rather than stored).
   */
  struct MaterialResponse
  {
    dealii::SymmetricTensor<2, 3> stress;
    dealii::SymmetricTensor<4, 3> tangent;
    bool                          sensitivity_is_identity = true;
    dealii::SymmetricTensor<4, 3> rotated_stress_sensitivity;
    dealii::SymmetricTensor<2, 3> stress_temperature_derivative;
    /// Ẇirr = σ̄ ε̄̇ᵛᵖ (eq. 21), MPa/s = mW/mm³: the plastic work rate.
    double plastic_work_rate = 0.;
    /// χ Ẇirr: the part of the plastic work that becomes heat (eq. 8, 20), MPa/s.
    double plastic_dissipation_rate = 0.;
    /// Ẇthel = −3Kβ T tr(Δεᵉ)/Δt (eq. 22 with the sign from thermodynamics,
    /// doc/thermodynamics.md): an elastic expansion cools. MPa/s.
    double thermoelastic_heating_rate = 0.;
    /// ∂σ/∂ln J at fixed Δε (adiabatic update: ΔT_ad ∝ J), zero otherwise;
    /// the mechanics adds ∂σ/∂ln J tr(δF F⁻¹) to δσ.
    dealii::SymmetricTensor<2, 3> volume_ratio_sensitivity;
    /// Temperature change of the step if adiabatic: Δt (χẆirr + Ẇthel)/(ρc), K.
    double adiabatic_temperature_increment = 0.;
    /// Equivalent (visco)plastic strain after the increment.
    double equivalent_plastic_strain = 0.;
    /// Iterations of the return map (0 in the elastic branch).
    unsigned int return_iterations = 0;
  };

  /**
   * The state of one quadrature point and the law that updates it. The law's
   * parameters live in a shared MaterialModel; a point only holds state.
   *
   * update() always starts from the committed state (t_n), so Newton may call
   * it any number of times; commit() accepts the step, revert() forgets it.
   */
  class MaterialPoint
  {
  public:
    virtual ~MaterialPoint() = default;

    virtual void update(const MaterialIncrement &increment,
                        MaterialRequest          request,
                        MaterialResponse        &response) = 0;

    /// Accept the last update as the state at t_n+1.
    virtual void commit() = 0;
    /// Forget every update since the last commit (time step cut back).
    virtual void revert() = 0;

    /// Cauchy stress of the last update (committed or not).
    virtual const dealii::SymmetricTensor<2, 3> &stress() const = 0;
    /// Stress at t_n (committed).
    virtual const dealii::SymmetricTensor<2, 3> &committed_stress() const = 0;
    virtual double equivalent_plastic_strain() const { return 0.; }
    /// Equivalent plastic strain at t_n.
    virtual double committed_equivalent_plastic_strain() const
    {
      return equivalent_plastic_strain();
    }

    /// Set the committed stress (initial stress states).
    virtual void set_stress(const dealii::SymmetricTensor<2, 3> &stress) = 0;

    /// State as a flat list of numbers (checkpoints) and back.
    virtual std::vector<double> save_state() const = 0;
    virtual void                load_state(const std::vector<double> &state) = 0;
  };

  /**
   * @p n points of type Point (constructed from @p args) in one array, each
   * handed out as a shared_ptr that shares the array's ownership (aliasing
   * constructor): 8 points per hexahedron made 8 heap objects and 8 control
   * blocks, ~50 B of allocator overhead per point (doc/performance.md).
   */
  template <class Point, class... Args>
  std::vector<std::shared_ptr<MaterialPoint>> contiguous_points(const std::size_t n,
                                                                const Args &...args)
  {
    auto block = std::make_shared<std::vector<Point>>();
    block->reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      block->emplace_back(args...);
    std::vector<std::shared_ptr<MaterialPoint>> points(n);
    for (std::size_t i = 0; i < n; ++i)
      points[i] = std::shared_ptr<MaterialPoint>(block, &(*block)[i]);
    return points;
  }

  /**
   * Why a model has no strength at a state (empty `location`: it has): the
   * entry responsible, "file:line: '<path>'", and what it does there
   * ("makes the yield stress vanish at T >= 313 K (T_ref + 1/omega = ...)").
   */
  struct StrengthLoss
  {
    std::string location, reason;
    explicit operator bool() const { return !location.empty(); }
  };

  /**
   * A material law with its parameters: declared and parsed from one
   * subsection, shared by the points of one body.
   */
  class Scene;

  class MaterialModel
  {
  public:
    virtual ~MaterialModel() = default;

    /// The model's own subsections and entries, inside `subsection Material`
    /// (none by default). Models that share a subsection (Elasticity,
    /// Hardening) declare it with the same function, so it is declared the same way.
    static void declare_parameters(dealii::ParameterHandler &) {}

    /**
     * Reads and checks the model's parameters, subsection Material entered;
     * @p path (e.g. "Bodies/bar/Material") names it in errors (Scene::fail).
     */
    virtual void parse_parameters(dealii::ParameterHandler &prm,
                                  const Scene              &scene,
                                  const std::string        &path) = 0;

    virtual std::unique_ptr<MaterialPoint> create_point() const = 0;
    /**
     * @p n points at once. The default makes one heap object each; a law
     * whose points are of one type returns contiguous_points(): one block,
     * no per-point allocation or reference count.
     */
    virtual std::vector<std::shared_ptr<MaterialPoint>> create_points(const std::size_t n) const
    {
      std::vector<std::shared_ptr<MaterialPoint>> points(n);
      for (auto &p : points)
        p = create_point();
      return points;
    }

    /// Small-strain elastic moduli (for the tangent's scale, stable time steps, AMG).
    virtual double bulk_modulus() const  = 0;
    virtual double shear_modulus() const = 0;
    virtual double density() const      = 0;
    /// Specific heat c, mm²/(s² K).
    virtual double heat_capacity() const { return 0; }
    virtual std::string name() const     = 0;

    /// Whether the yield stress is gone at temperature @p T (K) and
    /// equivalent plastic strain @p eps: checked on converged states and on
    /// the scene's initial temperatures, never on trial iterates (issue 17).
    virtual StrengthLoss strength_lost(double /*T*/, double /*eps*/) const { return {}; }
  };

  /// A material point that cannot be updated (e.g. the yield stress vanished
  /// at a temperature). The mechanics adds where the point is and cuts back.
  class MaterialPointError : public std::runtime_error
  {
  public:
    explicit MaterialPointError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * Material models register by name (ANVIL_REGISTER_MATERIAL_MODEL, one file
   * per model under source/material/models/); `Material/Model` is a
   * Patterns::Selection of the registered names.
   */
  using MaterialModelRegistry = Registry<MaterialModel>;

  /**
   * The factory: `subsection Material` with `set Model = <a registered name>`
   * and the subsections of the models. Declares every registered model's
   * parameters; create() builds the selected one and checks its ranges
   * (errors via scene.fail with the entry's full path).
   */
  namespace MaterialFactory
  {
    void declare_parameters(dealii::ParameterHandler &prm);

    /// @p path_prefix is the subsection path of this material, e.g. "Bodies/upper/Material".
    std::shared_ptr<const MaterialModel> create(dealii::ParameterHandler &prm,
                                                const Scene              &scene,
                                                const std::string        &path_prefix);

    /// A model from the text of a `subsection Material` body (.prm syntax),
    /// for programs and tests that need a law without a scene.
    std::shared_ptr<const MaterialModel> create_from_text(const std::string &settings);
  } // namespace MaterialFactory
} // namespace anvil

/**
 * Registers material model @p classname (default constructible, derived from
 * anvil::MaterialModel, with a static declare_parameters(ParameterHandler &)
 * declaring its subsections inside `subsection Material`) under @p name with
 * @p documentation (it becomes part of the help of `Material/Model`). At
 * namespace scope of one .cc file, in the library or in a program linked
 * against it.
 */
#define ANVIL_REGISTER_MATERIAL_MODEL(classname, name, documentation)                             \
  namespace                                                                                      \
  {                                                                                              \
    const bool ANVIL_REGISTRY_UNIQUE(anvil_material_model_) =                                    \
      ::anvil::MaterialModelRegistry::instance().add(                                            \
        name, documentation,                                                                     \
        []() -> std::unique_ptr<::anvil::MaterialModel> { return std::make_unique<classname>(); }, \
        [](dealii::ParameterHandler &prm) { classname::declare_parameters(prm); });              \
  }
