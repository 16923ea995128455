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
    /// With request_tangent: the caller takes the tangent in factored form
    /// (MaterialResponse::factored) where the law gives one, whose dense
    /// `tangent` and `rotated_stress_sensitivity` are then not written.
    request_factored_tangent = 16,
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
   * The consistent tangent of a radial return in factored form (seed §1.3:
   * the algorithmic modulus of the radial return, Simo & Hughes 1998 box 3.2),
   * on raw storage (00, 11, 22, 01, 02, 12):
   *   C = bulk δ⊗δ + deviatoric I_dev + normal n⊗n  [+ u⊗v],
   *   S = I_sym − sensitivity_deviatoric I_dev + sensitivity_normal n⊗n  [+ u⊗w]
   * (S unless MaterialResponse::sensitivity_is_identity), the bracketed
   * rank-one terms if `rank_one` (the adiabatic update: u = ∂σ/∂T, v, w the
   * amplified ∂ΔT_ad/∂Δε and ∂ΔT_ad/∂σ̃ₙ). C : d then costs a trace, a
   * deviator and one or two dot products instead of a 6x6 product.
   */
  struct FactoredTangent
  {
    bool   active   = false; // set by the law (request_factored_tangent), else the dense form
    bool   rank_one = false;
    double bulk = 0, deviatoric = 0, normal = 0;
    double sensitivity_deviatoric = 0, sensitivity_normal = 0;
    double n[6] = {}, u[6] = {}, v[6] = {}, w[6] = {};

    /// a : d of raw symmetric tensors (the shear components count twice).
    static double dot(const double *a, const double *d)
    {
      return a[0] * d[0] + a[1] * d[1] + a[2] * d[2] + 2 * (a[3] * d[3] + a[4] * d[4] + a[5] * d[5]);
    }
    /// s[0..N) += (C : d)[0..N) = α d + β δ + γ n + (v : d) u, α = c_d,
    /// β = K tr d − c_d tr d/3, γ = c_n n : d.
    template <unsigned int N = 6>
    void add_tangent(const double *d, double *s) const
    {
      const double tr = d[0] + d[1] + d[2];
      add<N>(d, deviatoric, bulk * tr - deviatoric * (tr / 3), normal * dot(n, d),
             rank_one ? dot(v, d) : 0., s);
    }
    /// s[0..N) += (S : e)[0..N): α = 1 − a, β = a tr e/3, γ = (a − b) n : e.
    template <unsigned int N = 6>
    void add_sensitivity(const double *e, double *s) const
    {
      const double a = sensitivity_deviatoric;
      add<N>(e, 1 - a, a * ((e[0] + e[1] + e[2]) / 3), sensitivity_normal * dot(n, e),
             rank_one ? dot(w, e) : 0., s);
    }
    /// s[0..N) += α d + β δ + γ n + ρ u.
    template <unsigned int N = 6>
    void add(const double *d, const double alpha, const double beta, const double gamma,
             const double rho, double *s) const
    {
      for (unsigned int p = 0; p < N; ++p)
        s[p] += alpha * d[p] + (p < 3 ? beta : 0.) + gamma * n[p] + (rank_one ? rho * u[p] : 0.);
    }
    /// The dense C and S (raw storage; S only if @p sensitivity).
    void expand(dealii::SymmetricTensor<4, 3> &C, dealii::SymmetricTensor<4, 3> *S) const
    {
      double *c = C.begin_raw(), *t = S ? S->begin_raw() : nullptr;
      for (unsigned int p = 0; p < 6; ++p)
        for (unsigned int q = 0; q < 6; ++q)
          {
            const double dev = p == q ? (p < 3 ? 2. / 3 : 0.5) : (p < 3 && q < 3 ? -1. / 3 : 0.);
            c[6 * p + q] = (p < 3 && q < 3 ? bulk : 0.) + deviatoric * dev + normal * n[p] * n[q] +
                           (rank_one ? u[p] * v[q] : 0.);
            if (t)
              t[6 * p + q] = (p == q ? (p < 3 ? 1. : 0.5) : 0.) - sensitivity_deviatoric * dev +
                             sensitivity_normal * n[p] * n[q] + (rank_one ? u[p] * w[q] : 0.);
          }
    }
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
    /// `tangent` and `rotated_stress_sensitivity` in factored form, if
    /// factored.active (request_factored_tangent and a law that gives it).
    FactoredTangent factored;
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
   * What the points of a body must hold beyond the law's state, known when
   * they are made (MaterialModel::create_points()): a law may then choose a
   * point type that carries exactly that in the body's block.
   */
  struct PointOptions
  {
    /// The points will be updated with MaterialIncrement::adiabatic (the
    /// Armero–Simo split): they keep the adiabatic iteration's state inline.
    bool adiabatic = false;
  };

  /**
   * The points of one body: `points` point into storage that `owner` keeps
   * alive (one block for a law whose points are of one type). The point
   * table keeps the pointers, the body the owner: no reference count per
   * point (a shared_ptr per point was 16 B and an atomic per copy).
   */
  struct PointBlock
  {
    std::shared_ptr<void>        owner;
    std::vector<MaterialPoint *> points;
  };

  /**
   * @p n points of type Point (constructed from @p args) in one array: 8
   * points per hexahedron made 8 heap objects and 8 control blocks, ~50 B of
   * allocator overhead per point (doc/performance.md).
   */
  template <class Point, class... Args>
  PointBlock contiguous_points(const std::size_t n, const Args &...args)
  {
    auto block = std::make_shared<std::vector<Point>>();
    block->reserve(n);
    for (std::size_t i = 0; i < n; ++i)
      block->emplace_back(args...);
    PointBlock points;
    points.points.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      points.points[i] = &(*block)[i];
    points.owner = std::move(block);
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

    /// One point (@p options: what it must hold, as for create_points()).
    virtual std::unique_ptr<MaterialPoint> create_point(const PointOptions &options = {}) const = 0;
    /**
     * @p n points at once. The default makes one heap object each; a law
     * whose points are of one type returns contiguous_points(): one block,
     * no per-point allocation.
     */
    virtual PointBlock create_points(const std::size_t n, const PointOptions &options = {}) const
    {
      auto owned = std::make_shared<std::vector<std::unique_ptr<MaterialPoint>>>(n);
      PointBlock block;
      block.points.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        block.points[i] = ((*owned)[i] = create_point(options)).get();
      block.owner = std::move(owned);
      return block;
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
    /// Whether strength_lost() can ever report at any (T, ε̄ ≥ 0); false lets
    /// the strength check skip the body's points (the same on every process).
    virtual bool may_lose_strength() const { return true; }

    /// The elastic moduli at temperature @p T (K), MPa (the energy audit's
    /// elastic energy, the dynamics' strain energy); constant by default.
    virtual double bulk_modulus_at(double /*T*/) const { return bulk_modulus(); }
    virtual double shear_modulus_at(double /*T*/) const { return shear_modulus(); }
    /// The thermal strain of a step from T − @p dT to @p T (per direction; none by default).
    virtual double thermal_strain(double /*T*/, double /*dT*/) const { return 0; }

    /**
     * Whether the points keep what the energy audit needs of their last
     * update (last_step()), so the audit need not recompute the material's
     * kinematics: σ̄ = ½(ΔR σₙ ΔRᵀ + σ) and Δε.
     */
    virtual bool keeps_last_step() const { return false; }
    /// σ̄ and Δε of the last update of @p point (a point of this model; only
    /// if keeps_last_step()), valid until the thread's next call.
    virtual void last_step(const MaterialPoint & /*point*/,
                           const dealii::SymmetricTensor<2, 3> *& /*mean_stress*/,
                           const dealii::SymmetricTensor<2, 3> *& /*strain_increment*/) const
    {}
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
