#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/klu_factorization.h>
#include <anvil/core/named_values.h>
#include <anvil/core/point_data.h>
#include <anvil/material/material_point.h>
#include <anvil/material/objective_rates.h>
#include <anvil/mechanics/boundary_conditions.h>
#include <anvil/mechanics/linear_solver.h>
#include <anvil/mechanics/step_start.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  template <int dim>
  class ContactProblem;

  namespace MechanicsAssembly
  {
    template <int dim>
    class Formulation;
    template <int dim>
    struct Context;
    template <int dim>
    class AssemblyMapping;
    template <int dim>
    struct ScratchData;
    struct CopyData;
  } // namespace MechanicsAssembly

  class Scene;

  /**
   * The mechanical half: quasi-static equilibrium div σ = 0 at finite strain,
   * updated-Lagrangian in its constitutive update (Hughes–Winget increments on
   * the mid-point configuration, see kinematics.h) and solved by Newton–Raphson
   * with the exact tangent of the discrete residual and a backtracking line
   * search. Plane strain for dim = 2, 3D for dim = 3.
   *
   * Integrals over the current configuration ∫ σ : ∇ₓδv dv are evaluated on
   * the reference mesh as ∫ P : ∇_X δv dV (P = Jσ F⁻ᵀ); the mesh does not move,
   * the displacement is the unknown.
   *
   * The assembly runs cell by cell on the threads of the process (deal.II's
   * WorkStream), one kernel per term of the weak form (assembly_kernels.h);
   * the result does not depend on the number of threads.
   */
  template <int dim>
  class MechanicalProblem
  {
  public:
    struct Parameters
    {
      unsigned int polynomial_degree            = 1;
      bool         f_bar                        = true;
      bool         axisymmetric                 = false;
      ObjectiveRate objective_rate              = ObjectiveRate::jaumann;
      bool         check_tangent                = false;
      bool         extrapolate                  = true;
      double       temperature                  = 293;
      // Implicit dynamics (generalized-α, Chung & Hulbert 1993).
      bool         dynamic                      = false;
      double       spectral_radius              = 1;
      bool         lumped_mass                  = false;
      std::string  gravity                      = "";
      std::string  initial_velocity             = "";
      double       maximum_plastic_increment    = 0; // 0: no limit
      unsigned int max_iterations               = 15;
      double       residual_tolerance           = 1e-8;
      double       absolute_residual_tolerance  = 1e-12;
      double       displacement_tolerance       = 1e-8;
      double       absolute_displacement_tolerance = 0;
      bool         line_search                  = true;
      double       line_search_far_bound        = 0.8; // |s(α)| <= it |s(0)| while |R| > 0.1 |R_0|
      std::string  linear_solver                = "automatic";
      double       linear_tolerance             = 1e-10;
      unsigned int linear_max_iterations        = 1000;
      unsigned int gmres_restart                = default_gmres_restart; // Krylov basis before a restart
      std::string  preconditioner               = "automatic"; // automatic | AMG | geometric (linear_solver.cc)
      double       amg_rebuild_growth           = 0;
      // AMG (linear_solver.h): 0 / "automatic" chosen per solve in solve_linear_system().
      unsigned int amg_smoother_degree          = 0;     // Chebyshev degree
      double       amg_chebyshev_ratio          = 0;     // Chebyshev's λ_max / λ_min
      std::string  amg_isochoric_modes          = "automatic"; // near-null space += u = G (x − c)
      double       amg_aggregation_threshold    = 0.02;
      unsigned int amg_coarse_size              = 2000;
      std::string  amg_cycle                    = "automatic"; // automatic | V | W (linear_solver.cc)
      bool         amg_plain_aggregation        = false; // "AMG prolongator = plain"
      std::string  amg_package                  = "ML";  // ML | MueLu (the module libanvil-muelu.so)
      unsigned int direct_solver_limit          = 200000;
      std::string  direct_solver                = "auto"; // auto | klu | band

      static void declare_parameters(dealii::ParameterHandler &prm);
      void        parse_parameters(dealii::ParameterHandler &prm, const Scene &scene);
    };

    /// What one time step's Newton solve did.
    struct StepResult
    {
      bool                converged = false;
      std::string         failure; // why not, one line
      unsigned int        iterations        = 0;
      unsigned int        linear_iterations = 0;
      std::vector<double> residuals;  // |R| per iteration (free dofs), N
      std::vector<double> increments; // |δu| per iteration, mm
      std::vector<double> line_search_steps;
    };

    /// Per-cell fields for output (cell averages over quadrature points),
    /// and each cell's largest and smallest quadrature-point value (the
    /// extrema the quantities of interest report; the average lies inside).
    struct CellFields
    {
      std::vector<std::string>                 names;
      std::vector<dealii::Vector<double>>      values;
      std::vector<dealii::Vector<double>>      max_values, min_values;
    };

    MechanicalProblem(const dealii::parallel::DistributedTriangulationBase<dim>           &triangulation,
                      const Parameters                                                     &parameters,
                      const BoundaryConditions<dim>                                        &boundary_conditions,
                      const std::map<dealii::types::material_id, std::shared_ptr<const MaterialModel>> &materials,
                      dealii::TimerOutput                                                  &timer);

    ~MechanicalProblem();

    void setup();

    /// Solve for the configuration at @p time_new from the committed one at @p time_old.
    /// Solve the step from the committed state; with @p from_last_solution
    /// (the same step again, e.g. at another temperature) Newton starts from
    /// the last solution instead of the predictor.
    StepResult solve_step(double time_old, double time_new, bool from_last_solution = false);

    /// Accept the last solve: material points commit, work and reactions are accumulated.
    void commit_step();
    /// Forget the last solve (time step cut back).
    void revert_step();
    /**
     * After commit_step(), collective: "" if every point keeps a yield
     * stress > 0 at its committed temperature and at the one the next step
     * starts from, else one line naming the hottest point that does not, the
     * time @p time and the entry responsible (strength_check.cc, issue 17).
     */
    std::string strength_lost(double time) const;

    /// Contact pairs to assemble with the bodies (null: none). Set before setup().
    void set_contact(ContactProblem<dim> *c) { contact = c; }

    dealii::types::global_dof_index n_dofs() const { return dof_handler.n_dofs(); }
    const dealii::DoFHandler<dim>   &get_dof_handler() const { return dof_handler; }
    const dealii::TrilinosWrappers::MPI::Vector &displacement() const { return solution; }
    const dealii::Mapping<dim>      &get_mapping() const { return mapping; }

    /// Reaction force on the named boundary (force the support exerts on the body), N.
    dealii::Tensor<1, dim> reaction(dealii::types::boundary_id boundary) const;
    /// The locally owned dofs on a boundary with their components, each once,
    /// in the order of the active cells (found once per mesh: the per-step
    /// histories sum over them).
    const std::vector<std::pair<dealii::types::global_dof_index, unsigned int>> &
    owned_boundary_dofs(dealii::types::boundary_id boundary) const;

    /**
     * The energy audit, accumulated over accepted steps (N·mm), as two
     * balances whose sides are computed by different routes (doc/energy_audit.md):
     *   work:   W_ext + K₀ = K + W_σ + W_contact + D_alg         (nodes vs points)
     *   stress: W_σ = ΔE_el + W_p,flow + W_th − V_hypo + W_F̄     (points, per term)
     */
    struct Energy
    {
      double external_work  = 0; // loads (f_ext) everywhere + supports' reactions at constrained dofs, trapezoidal
      double internal_work  = 0; // ½(f_int,n + f_int,n+1) · Δu (f_int with the contact forces)
      double contact_work   = 0; // ½(f_c,n + f_c,n+1) · Δu: work the bodies do on the contact
      double stress_work    = 0; // ∫ σ̄ : Δε dv½, σ̄ = ½(ΔR σ_n ΔRᵀ + σ_n+1), true kinematics
      double kinetic        = 0; // ½ vᵀ M v
      double initial_kinetic = 0;
      double plastic_work   = 0; // ∫∫ Ẇirr dv dt (eq. 21): the plastic work the heat receives
      double flow_plastic_work = 0; // ∫ σ̄ : Δεᵖ dv½ with Δεᵖ = Δε̄ᵖ (3/2) s/q (flow rule), the audit's
      double elastic_energy = 0; // ∫ ½ σ : H(T)⁻¹ : σ dv, from the stresses (a state function)
      double initial_elastic_energy = 0; // every scene starts unstressed
      double thermal_work   = 0; // ∫ [σ̄ : βΔT I − (W(σ_n, T_n+1) − W(σ_n, T_n))] dv½
      double hypoelastic_volume_work = 0; // ∫ ½(W_n + W_n+1)(J_n+1 − J_n) dV: what ∫W dv gains by volume change alone
      double f_bar_work     = 0; // ∫ σ̄ : (Δε − Δε̄) dv½: F-bar's stress power beyond the material's
      double algorithmic_dissipation = 0; // Σ eq. A3: what generalized-α removes (zero for ρ∞ = 1)
      /// |W_ext + K₀ − K − W_σ − W_contact − D_alg| relative to the largest term.
      double balance_error() const;
      /// |W_σ − (E_el − E_el,0) − W_p,flow − W_th + V_hypo − W_F̄| relative to the largest term.
      double stress_balance_error() const;
    };
    const Energy &energy() const { return energy_audit; }
    /**
     * Temperatures at the quadrature points of a cell, at t_n+1 and t_n, for
     * a coupled scene (without it the uniform Mechanics/Temperature is used).
     * Called from the assembly's threads: it must be reentrant (read only).
     */
    using TemperatureField = std::function<void(const typename dealii::Triangulation<dim>::active_cell_iterator &,
                                                std::vector<double> &T)>;
    /**
     * Temperatures at the quadrature points from the heat equation (T_n).
     * Each point remembers the temperature it ended its last step at, so the
     * increment it sees is ΔT = T_n − T_seen: the thermal phase's change (and
     * with @p adiabatic, the Armero–Simo split, the point adds its own
     * adiabatic heating ΔT_ad of the step, which it then remembers too).
     */
    void set_temperature_field(const TemperatureField &field, bool adiabatic);
    /// The temperature every point starts from (heat scenes), per point in
    /// PointData order (cell by active cell index, then quadrature point).
    void set_initial_point_temperatures(const std::vector<double> &T);
    /**
     * The heat equation reads heat_source() and thermoelastic_source(): the
     * assembly keeps them from now on. Without it (and without a
     * temperature field) the points' heat doubles are not kept at all
     * (point_setup.cc): a scene pays only for the physics it switched on.
     */
    void keep_heat_sources();
    /// Doubles kept per quadrature point beside the points (heat sources,
    /// temperatures, Ẇirr): 5 in a coupled scene, 1 (the audit's Ẇirr) in a
    /// purely mechanical one (a test's figure).
    unsigned int n_point_doubles() const;
    /// χẆirr + Ẇthel of the last assembly at quadrature point q of a cell (MPa/s = mW/mm³).
    double heat_source(const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
                       unsigned int q) const
    {
      return heat_sources(cell, q);
    }
    /// Its thermoelastic part Ẇthel alone (the rest is plastic heat χẆirr).
    double thermoelastic_source(const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
                                unsigned int q) const
    {
      return thermoelastic_sources(cell, q);
    }
    const dealii::Quadrature<dim> &get_quadrature() const { return quadrature; }

    /// Largest increment of equivalent plastic strain at a point in the last solve.
    double largest_plastic_increment() const { return max_plastic_increment; }
    bool   is_dynamic() const { return parameters.dynamic; }
    /// Velocity (ghosted), dynamics only.
    const dealii::TrilinosWrappers::MPI::Vector &velocity() const { return velocity_ghosted; }

    /// Averages per locally owned cell: stress components, von Mises, pressure, J, ε̄ᵖ.
    CellFields cell_fields() const;

    /// Displacement, cell-average stress and equivalent plastic strain at a
    /// point of the reference mesh.
    bool probe(const dealii::Point<dim>      &point,
               dealii::Tensor<1, dim>        &displacement,
               dealii::SymmetricTensor<2, 3> &stress,
               double                        &plastic_strain) const;

    /// |K δu − (R(u + hδu) − R(u − hδu))/2h| / |K δu| for a random δu at the
    /// current iterate: the finite-difference check of the tangent.
    double tangent_error();

    /**
     * Checkpoint: attach the committed state (displacement, velocity,
     * acceleration, force histories, every material point's state) to the
     * triangulation; the caller then calls triangulation.save(). After
     * triangulation.load() and setup(), load_checkpoint() restores it (also
     * on another number of processes).
     */
    void prepare_checkpoint();
    void load_checkpoint();
    /// Scalars of the committed state (energies, last step) and back.
    NamedValues checkpoint_scalars() const;
    void        restore_scalars(const NamedValues &values);

    /// Cells per second of the last full (matrix + residual) assembly on this rank.
    double last_assembly_rate() const { return assembly_rate; }

    /**
     * Assemble the tangent (with @p with_matrix) and −R at the current
     * iterate of the last solve_step(), as Newton does: for tests and
     * benchmarks (thread counts, timings). False if an element inverted.
     */
    bool assemble_system(const bool with_matrix) { return assemble(with_matrix, current_time); }
    const dealii::TrilinosWrappers::SparseMatrix &get_system_matrix() const { return system_matrix; }
    /// −R (constrained entries 0) of the last assembly.
    const dealii::TrilinosWrappers::MPI::Vector &get_system_rhs() const { return system_rhs; }

    /**
     * The pieces of solve_step() for a scheme that runs its own Newton loop
     * over more fields (coupling/monolithic.cc). begin_step(): the contact's
     * step, the predictor and its constraints; true if the boundary values
     * jump. predictor_update(): one Newton update of the mechanics alone with
     * the predictor constraints (carries the jump into the body, as the first
     * iteration of solve_step() does); afterwards the homogeneous constraints
     * apply. False (and failure_message()) if an element inverted.
     */
    bool begin_step(double time_old, double time_new);
    bool predictor_update(unsigned int &linear_iterations);
    /// Set the iterate (owned, constraints already satisfied) and its ghosts.
    void set_displacement(const dealii::TrilinosWrappers::MPI::Vector &u_owned);
    const dealii::TrilinosWrappers::MPI::Vector &owned_displacement() const { return owned_solution; }
    const dealii::TrilinosWrappers::MPI::Vector &owned_old_displacement() const
    {
      return owned_old_solution;
    }
    /// The homogeneous constraints of Newton updates (supports, axis, hanging nodes).
    const dealii::AffineConstraints<double> &update_constraints() const { return constraints; }
    /// Force scale of the residual test: |f_int|, |f_ext|, |M a| of the last assembly.
    double force_scale() const;
    std::string failure_message() const { return material_failure_message(); }
    std::size_t memory_consumption() const;

  private:
    void setup_quadrature_point_data();
    /// Assemble −R into system_rhs (and K if @p with_matrix); false if an element inverted.
    /// With @p with_audit the points' energy audit terms are summed too (kept_audit).
    bool assemble(bool with_matrix, double time, bool with_audit = false);
    /// What the assembly's kernels read (assembly_data.h).
    MechanicsAssembly::Context<dim> assembly_context(bool with_matrix, double time);
    /// kept_scratch for these cell update flags (made anew if they differ), kept_copy.
    MechanicsAssembly::ScratchData<dim> &kept_scratch_data(dealii::UpdateFlags flags);
    /// The contact elements into the system, serially; false if the matrix must grow.
    bool assemble_contact(bool with_matrix);
    /// The first iterate of a step (extrapolated, or the last solution) and
    /// the predictor constraints imposing the step's boundary values; true if
    /// they jump (then the first update is taken whole). With @p assembled,
    /// the check of an extrapolated iterate assembles K too and sets it true.
    bool predict(double time_old, double time_new, bool from_last_solution,
                 bool *assembled = nullptr);
    /// predictor_constraints at the current solution; they become active.
    void build_predictor_constraints(double time_old, double time_new);
    /// Step length α of the Newton update @p du (Crisfield's energy line
    /// search); leaves the solution at u + α du. @p full_step: α = 1.
    /// @p assembled: set true if K and R are left assembled at that solution.
    /// @p bound: α = 1 is kept when |s(1)| <= bound |s(0)|, else searched to it.
    /// @p audit: the full step's evaluation sums the audit's terms (kept_audit).
    double line_search(const dealii::TrilinosWrappers::MPI::Vector &du, bool full_step,
                       double time_new, bool &assembled, double bound, bool audit = false);
    unsigned int solve_linear_system(dealii::TrilinosWrappers::MPI::Vector &du);
    /// Some material point (any process) has a plastic strain: AMG's "automatic" settings.
    bool has_flowed_plastically() const;
    double       residual_norm() const;
    /// The smallest residual the digits of u and of F = I + ∇u can resolve,
    /// 2 ε |diag K ∘ (|u| + h)| over the free dofs (residual_floor.cc);
    /// Newton accepts a residual below it.
    double       residual_floor() const;
    /// 3x3 F from the in-plane gradient (and the hoop stretch if axisymmetric).
    dealii::Tensor<2, 3> deformation_gradient(const dealii::Tensor<2, dim> &grad_u,
                                              double                        radial_displacement,
                                              double                        radius) const;
    std::string  material_failure_message() const;
    void make_axis_constraints(dealii::AffineConstraints<double> &constraints) const;
    void setup_dynamics();
    /// Row sums of the mass matrix (lumped mass), t = ρ ∫ N dV.
    void lumped_mass(dealii::TrilinosWrappers::MPI::Vector &m) const;
    /// M x with the scene's mass (consistent or lumped); x ghosted.
    void mass_product(const dealii::TrilinosWrappers::MPI::Vector &x,
                      dealii::TrilinosWrappers::MPI::Vector       &mx) const;
    /// The step's algorithmic dissipation of generalized-α (eq. A3 of
    /// doc/energy_audit.md), before the old state is overwritten.
    double step_algorithmic_dissipation(const dealii::TrilinosWrappers::MPI::Vector &du,
                                        const dealii::TrilinosWrappers::MPI::Vector &a_new,
                                        const dealii::TrilinosWrappers::MPI::Vector &v_new) const;
    /// ½ vᵀ M v with the scene's mass (consistent or lumped).
    double kinetic_energy(const dealii::TrilinosWrappers::MPI::Vector &v) const;
    /// ∫ ½ (p²/K(T) + s:s/2G(T)) dv over the committed stresses and temperatures.
    double elastic_strain_energy() const;
    /// a_{n+1} from u_{n+1} by Newmark: (u − uₙ − Δt vₙ)/(βΔt²) − (½ − β)/β aₙ.
    double newmark_acceleration(double u, double u_old, double v_old, double a_old) const;

    MPI_Comm                                                 mpi_communicator;
    const dealii::parallel::DistributedTriangulationBase<dim> &triangulation;
    const Parameters                                         parameters;
    const BoundaryConditions<dim>                           &boundary_conditions;
    std::map<dealii::types::material_id, std::shared_ptr<const MaterialModel>> materials;
    dealii::TimerOutput                                     &timer;

    const bool                axisymmetric, f_bar;
    dealii::FESystem<dim>     fe;
    std::unique_ptr<const MechanicsAssembly::Formulation<dim>> formulation;
    dealii::MappingQ<dim>     mapping;
    /// The same Q1 mapping for the threaded assembly: its values do not
    /// depend on the order of the cells (assembly_mapping.h).
    std::unique_ptr<MechanicsAssembly::AssemblyMapping<dim>> assembly_mapping;
    dealii::DoFHandler<dim>   dof_handler;
    dealii::QGauss<dim>       quadrature;
    dealii::QGauss<dim - 1>   face_quadrature;
    dealii::IndexSet          locally_owned_dofs, locally_relevant_dofs;
    dealii::AffineConstraints<double> constraints;           // homogeneous: Newton updates
    dealii::AffineConstraints<double> predictor_constraints; // first iteration: the BC jump
    /// What build_predictor_constraints() keeps per dof numbering (newton.cc;
    /// setup() empties it): the prescribed dofs and their points, which of
    /// them are lines, and whether the lines stay the same from step to step.
    struct KeptPredictor
    {
      bool                                     found = false; // points and flags below
      typename BoundaryConditions<dim>::Points points;
      std::vector<unsigned char>               displacement_line, velocity_line;
      /// No line has entries: close() changes no inhomogeneity, so the
      /// closed lines of the last build take the step's values in place.
      bool                                     lines_kept = false;
      std::vector<double>                      values, increments; // work space
    };
    KeptPredictor kept_predictor;
    const dealii::AffineConstraints<double> *active_constraints = &constraints;

    dealii::TrilinosWrappers::SparseMatrix system_matrix;
    /// KLU of system_matrix, its symbolic analysis and pivots kept while the
    /// pattern is (klu_refactor, checked: klu_factorization.h).
    KluFactorization direct_solver{true};
    /// GMRES + AMG, the hierarchy kept across Newton iterations and steps.
    ReusedAMG amg;
    dealii::TrilinosWrappers::MPI::Vector  system_rhs;          // −R, constrained entries 0
    dealii::TrilinosWrappers::MPI::Vector  internal_force;      // f_int, all entries
    dealii::TrilinosWrappers::MPI::Vector  internal_force_old;
    dealii::TrilinosWrappers::MPI::Vector  external_force;      // f_ext (pressures)
    dealii::TrilinosWrappers::MPI::Vector  solution, old_solution;       // ghosted
    dealii::TrilinosWrappers::MPI::Vector  owned_solution, owned_old_solution;

    // One material point per quadrature point of each locally owned cell,
    // in the blocks of its body (MaterialModel::create_points()), which
    // point_blocks own.
    PointData<MaterialPoint *>         points;
    std::vector<std::shared_ptr<void>> point_blocks;
    PointOptions                       point_options; // what the points were made for
    /// The points of every locally owned cell for @p options, with the
    /// committed state of the points they replace (if any).
    void make_points(const PointOptions &options);
    ContactProblem<dim>                        *contact = nullptr;
    dealii::IndexSet                            constraint_lines; // relevant + contact surface dofs
    /// The matrix and its sparsity: the cells' couplings and the contact's.
    void setup_matrix();
    /// The cells' couplings (make_sparsity_pattern's columns of each locally
    /// relevant row, in order), kept for setup_matrix() until the dofs or
    /// the constraints change (emptied where they are made); with contact
    /// only: without, no other pattern follows and they are freed.
    std::vector<std::vector<dealii::types::global_dof_index>> cell_pattern;
    /// Lines for contact-surface dofs that this process does not see but their owner constrains.
    void add_remote_constraints(dealii::AffineConstraints<double> &c) const;
    /// Per point, last assembly; empty unless keep_heat_sources().
    PointData<double>                           heat_sources;
    PointData<double>                           thermoelastic_sources;
    PointData<double>                           plastic_work_rates; // Ẇirr per point, last assembly
    PointData<double>                           node_masses; // dynamics: per cell (Context::node_masses)
    MechanicsAssembly::StepStart                step_start; // F_n, F̄_n per point (Context::step_start)
    TemperatureField                            temperature_field;
    bool                                        adiabatic_split = false;
    bool                                        heat_sources_kept = false; // keep_heat_sources()
    // The temperature each point ended its last update at (current and
    // committed); empty without a temperature field (the uniform one is read).
    PointData<double>                           material_temperature, material_temperature_old;
    double max_plastic_increment = 0;
    /// The step's audit sums over the points (MechanicsAssembly::CopyData::audit).
    std::array<double, 6> step_audit{}; // MechanicsAssembly::n_audit_terms
    /// step_audit and the state's elastic energy by a pass of their own over
    /// the cells at the state of the last assembly (commit_step(), where no
    /// evaluation kept them: kept_audit).
    void compute_step_audit();
    /**
     * The audit's sums (every AuditTerm, this process's points in cell order)
     * as an evaluation asked for them left them (assemble(..., true)), and
     * what makes them the committed state's: no assembly since (the points'
     * stresses, Ẇirr and temperatures are that evaluation's), the same u to
     * the bit, the same step. commit_step() sums them (audit_from_kept())
     * instead of compute_step_audit()'s pass; anything else falls back to it.
     */
    struct KeptAudit
    {
      std::array<double, 7> sums{};      // MechanicsAssembly::n_audit_terms
      unsigned long         evaluation = 0; // n_evaluations at that assembly (0: none kept)
      double                time_step  = 0;
      std::vector<double>   solution;       // the ghosted u's local values it read
    };
    KeptAudit     kept_audit;
    unsigned long n_evaluations = 0; // assemble() calls, failed ones too
    /// Collective: step_audit and the elastic energy from kept_audit if it is
    /// the committed state's on every process (true), else nothing (false).
    bool audit_from_kept();
    /// Test only (ANVIL_AUDIT_OMIT=term): 1 + the AuditTerm left out of the sums, 0 none.
    unsigned int audit_omission = 0;
    Energy energy_audit;
    dealii::TrilinosWrappers::MPI::Vector external_force_old, reaction_force, reaction_force_old;
    /// Contact forces alone (also in internal_force), for the contact's work.
    dealii::TrilinosWrappers::MPI::Vector contact_force, contact_force_old;

    // Dynamics: generalized-α parameters, mass and the state at t_n.
    double alpha_m = 0, alpha_f = 0, newmark_beta = 0.25, newmark_gamma = 0.5;
    dealii::TrilinosWrappers::MPI::Vector velocity_old, acceleration_old; // owned
    dealii::TrilinosWrappers::MPI::Vector velocity_ghosted, velocity_old_ghosted,
      acceleration_old_ghosted;
    dealii::TrilinosWrappers::MPI::Vector static_residual_old; // f_int,n − f_ext,n
    dealii::TrilinosWrappers::MPI::Vector inertia_force;       // M a_{n+1}
    dealii::Tensor<1, dim> gravity; // mm/s², body force ρ g
    double assembly_rate = 0;
    double current_time_step = 1, current_time = 0, previous_time_step = 0, mesh_diameter = 1;
    /// The largest locally owned cell's diameter over all processes, mm
    /// (residual_floor()): set with the dofs (the mesh does not move).
    double largest_cell_diameter = 0;
    dealii::TrilinosWrappers::MPI::Vector previous_increment; // Δu of the last accepted step
    unsigned int last_step_iterations = 0; // Newton iterations of the last converged solve_step
    /// Wrong predictions of convergence of the last solve_step and of the one
    /// before, bit k: the residual's contraction at iteration k predicted the
    /// next test would pass and it did not. Where both were wrong, the next
    /// step does not act on the prediction at k (newton.cc, predict_next_test()).
    unsigned int mispredicted = 0, mispredicted_before = 0;
    // Checkpoint transfer (alive between prepare and the triangulation's save).
    std::unique_ptr<dealii::parallel::distributed::SolutionTransfer<dim, dealii::TrilinosWrappers::MPI::Vector>>
                                                       checkpoint_transfer;
    std::vector<dealii::TrilinosWrappers::MPI::Vector> checkpoint_vectors;
    unsigned int                                       checkpoint_handle = 0;
    std::vector<dealii::TrilinosWrappers::MPI::Vector *> checkpoint_targets();
    std::string material_failure; // this rank's, from the last assembly
    /// Per locally owned cell (loop order), its n x n mass matrix (mass_product:
    /// the mass does not change, the mesh being the reference one); empty
    /// until first used.
    mutable std::vector<double> cell_masses;
    mutable std::map<dealii::types::boundary_id,
                     std::vector<std::pair<dealii::types::global_dof_index, unsigned int>>>
      boundary_dofs; // owned_boundary_dofs()
    /// boundary_dofs holds every boundary this process sees (built once per numbering).
    mutable bool boundary_dofs_listed = false;
    /// The assembly's work space, kept from one assembly to the next (its
    /// FEValues cost ~120 000 instructions to build; assembly.cc). Declared
    /// after the mapping and the element it points to, so destroyed first.
    std::shared_ptr<MechanicsAssembly::ScratchData<dim>> kept_scratch;
    std::shared_ptr<MechanicsAssembly::CopyData>         kept_copy;
    /// What OffProcessRows keeps per matrix pattern (off_process_rows.h):
    /// where each value sent lands in its owner's rows. Reset with the matrix.
    std::shared_ptr<void>                                off_process_plan;
    /// Work vectors of the owned layout kept between steps (a Trilinos vector
    /// constructed as a copy costs ~47 000 instructions on the tube: its
    /// Epetra_FEVector and map): Newton's increment, the line search's start,
    /// the commit's sums. owned_work() gives one the layout of system_rhs.
    dealii::TrilinosWrappers::MPI::Vector work_increment, work_start, work_sum;
    dealii::TrilinosWrappers::MPI::Vector &owned_work(dealii::TrilinosWrappers::MPI::Vector &v);
  };
} // namespace anvil
