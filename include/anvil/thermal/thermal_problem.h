#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>

#include <anvil/core/heat_exchange.h>
#include <anvil/core/named_values.h>
#include <anvil/thermal/cell_table.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;
  class KluFactorization;
  template <int dim>
  class Geometry;

  /**
   * Thermal data of one body. ρ and c come from the body's elastic law
   * (ElasticLaw::density, heat_capacity); the conductivity is declared here,
   * in the body's `subsection Thermal`:
   *   k(T) = k₀ (1 + a (T − T_ref))   [N/(s K) = mW/(mm K)].
   */
  struct ThermalMaterial
  {
    double density               = 7.8e-9; // t/mm³
    double heat_capacity         = 4.6e8;  // mm²/(s² K)
    double conductivity          = 50;     // N/(s K)
    double conductivity_slope    = 0;      // a, 1/K
    double reference_temperature = 293;    // K

    double k(const double T) const
    {
      return conductivity * (1 + conductivity_slope * (T - reference_temperature));
    }
    double dk_dT() const { return conductivity * conductivity_slope; }

    /// Declares `subsection Thermal` inside the current subsection.
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Reads `subsection Thermal` of the current subsection; @p path (e.g.
    /// "Bodies/steel/Material") names it in errors. ρ and c are given.
    static ThermalMaterial parse_parameters(dealii::ParameterHandler &prm, const Scene &scene,
                                            const std::string &path, double density,
                                            double heat_capacity);
  };

  /**
   * `subsection Heat / subsection Boundary conditions`. Every entry is a
   * ';'-separated list of 'boundary: values', values being muparser
   * expressions in x, y (, z), t evaluated on the current configuration:
   *  - Temperature = 'left: 293 + 10*t'           (K, Dirichlet)
   *  - Flux        = 'top: 0.5'                   (mW/mm², into the body > 0)
   *  - Convection  = 'right: h, T_inf'            (h in mW/(mm² K), T_inf in K)
   *  - Radiation   = 'right: emissivity, T_inf'   (Stefan–Boltzmann σ = 5.670374e-11 mW/(mm² K⁴))
   * A boundary not named is insulated. Flux, convection and radiation may be
   * combined on one boundary; a Temperature boundary takes nothing else.
   */
  template <int dim>
  class ThermalBoundaryConditions
  {
  public:
    struct Boundary
    {
      std::string                                  name;
      std::shared_ptr<dealii::FunctionParser<dim>> temperature, flux, h, T_convection,
        emissivity, T_radiation;
      /// Whether the Temperature or the convection coefficient h may change in
      /// time (its formula names t; true unless parse_parameters knows better).
      /// Constant ones let a linear problem keep K and skip ġ (linear_residual).
      bool temperature_varies = true, h_varies = true;
      /// Likewise the prescribed flux and the convection's T∞: constant ones
      /// give a load assembled once per configuration.
      bool flux_varies = true, T_convection_varies = true;
    };

    /// Declares `subsection Boundary conditions` inside the current subsection (Heat).
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Reads `Heat/Boundary conditions`; names resolve through @p geometry.
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene,
                          const Geometry<dim> &geometry);

    std::map<dealii::types::boundary_id, Boundary> boundaries;
  };

  /**
   * The thermal half (seed eq. 26): ρc Ṫ = ρr − div q + sources, q = −k(T) ∇T,
   * on the current configuration. Semi-discrete
   *     M Ṫ = f(T, t) = −K(T) T + F(T, t),
   * integrated over [tₙ, tₙ₊₁] by SUNDIALS ARKode (DIRK, see arkode_integrator.h)
   * with our own linear solvers: M + γ∂(KT − F)/∂T by KLU or GMRES + AMG,
   * M by CG + Jacobi (or the lumped diagonal).
   *
   * Dirichlet temperatures: the constrained dofs stay in ARKode's state with
   * the equation Ṫᵢ = ġᵢ(t) (rows and columns of M decoupled, the coupling
   * M_fD ġ_D moved to the free rows' right-hand side); at the end of every
   * step they are set to g(tₙ₊₁) exactly. Hanging-node dofs get Ṫ = 0 and
   * are distributed from their masters wherever T is read.
   *
   * Axisymmetric (dim = 2): x is the radius, every volume and boundary
   * integral carries 2πr with r the current radius; heat flows are per full
   * ring (mW).
   */
  template <int dim>
  class ThermalProblem
  {
  public:
    using Vector = dealii::TrilinosWrappers::MPI::Vector;
    using CellIterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

    struct Parameters
    {
      std::string  initial_temperature = "293";
      std::string  initial_temperature_location; // where the scene sets it, for errors
      std::string  source              = ""; // mW/mm³, expression; empty: none
      unsigned int polynomial_degree   = 1;
      bool         axisymmetric        = false; // set by the caller (Mechanics/Two-dimensional model)
      // Time integration
      unsigned int order                 = 3;
      double       relative_tolerance    = 1e-6;
      double       absolute_tolerance    = 1e-6; // K
      double       fixed_step_size       = 0;    // s, 0: adaptive
      unsigned int max_internal_steps    = 5000;
      unsigned int max_nonlinear_iterations = 10;
      // Steady state (steady_state.cc): Time integration/Method = steady makes
      // every step a steady solve at its end time (thermal only);
      // Initial temperature field = steady starts a scene from the steady
      // field at t = 0 (Initial temperature is then Newton's first guess).
      bool         steady                   = false;
      bool         steady_initial           = false;
      unsigned int steady_max_iterations    = 30;
      double       steady_tolerance         = 1e-8; // K, largest |dT| of the last Newton step
      // Linear algebra
      std::string  linear_solver       = "automatic"; // automatic|direct|iterative
      bool         lumped_mass         = false;
      unsigned int direct_solver_limit = 100000;

      /// Declares `subsection Heat` (with Time integration, Linear solver and Boundary conditions).
      static void declare_parameters(dealii::ParameterHandler &prm);
      void        parse_parameters(dealii::ParameterHandler &prm, const Scene &scene);
    };

    /// What one solve_step did.
    struct Statistics
    {
      bool         converged = false;
      std::string  failure;
      unsigned long internal_steps = 0, attempted_steps = 0, error_test_failures = 0,
                    nonlinear_iterations = 0, nonlinear_failures = 0, linear_setups = 0,
                    linear_solves = 0, linear_iterations = 0, mass_solves = 0,
                    rhs_evaluations = 0;
      double last_internal_step = 0;

      /// Several solves of one step (iterated staggered): counts add up, the
      /// outcome and the last internal step are the latest solve's.
      Statistics &operator+=(const Statistics &s)
      {
        converged = s.converged;
        failure   = s.failure;
        internal_steps += s.internal_steps;
        attempted_steps += s.attempted_steps;
        error_test_failures += s.error_test_failures;
        nonlinear_iterations += s.nonlinear_iterations;
        nonlinear_failures += s.nonlinear_failures;
        linear_setups += s.linear_setups;
        linear_solves += s.linear_solves;
        linear_iterations += s.linear_iterations;
        mass_solves += s.mass_solves;
        rhs_evaluations += s.rhs_evaluations;
        last_internal_step = s.last_internal_step;
        return *this;
      }
    };

    /// Volumetric source per quadrature point of QGauss(p + 1) (p = Polynomial
    /// degree of the temperature; the mechanics' quadrature when the degrees
    /// match), in mW/mm³ = MPa/s, held constant over a step. The assembly
    /// calls it from several threads at once: it must only read.
    using HeatSource = std::function<double(const CellIterator &cell, unsigned int q)>;

    ThermalProblem(const dealii::parallel::DistributedTriangulationBase<dim> &triangulation,
                   const Parameters                                        &parameters,
                   const ThermalBoundaryConditions<dim>                    &boundary_conditions,
                   const std::map<dealii::types::material_id, ThermalMaterial> &materials,
                   dealii::TimerOutput                                     &timer);
    ~ThermalProblem();

    /// Distribute dofs, build the sparsity, set T(t₀) from the initial expression.
    void setup(double start_time = 0);

    /// Use the deformed geometry x = X + u for every integral from now on
    /// (the vector is copied; ghosted, on @p mechanics_dofs, an FESystem of dim FE_Q).
    void set_configuration(const dealii::DoFHandler<dim> &mechanics_dofs,
                           const Vector                  &displacement_ghosted);
    void set_heat_source(const HeatSource &source);

    /// Heat exchanged at nodes outside the cells' coupling (contact, eq. 30–33;
    /// core/heat_exchange.h). Called on the main thread of every process after
    /// the threaded cell loops (the contact's functions communicate). Its
    /// couplings enter the Newton matrix M + γA (pattern and values), so a
    /// KLU of it is ARKode's own matrix: one solve per stage, no GMRES.
    using Exchange = HeatExchange;
    void set_exchange(const Exchange &e) { exchange = e; }
    /// Hanging-node or Temperature constraint on dof @p i (exchange skips those rows).
    bool is_constrained(dealii::types::global_dof_index i) const { return constraints.is_constrained(i); }

    /// The operators of the semi-discrete system, as assemble_system left them.
    struct AssembledSystem
    {
      const dealii::TrilinosWrappers::SparseMatrix &mass, &tangent, &newton;
    };
    /**
     * For tests and benchmarks only (the time integration never calls it):
     * assemble, at the owned temperature @p T and time @p t, the mass matrix
     * M, the tangent A = ∂(K T − F)/∂T and f(T, t) into @p f (reinit'ed);
     * with @p gamma > 0 also the Newton matrix M + γA (and its factorisation
     * or AMG, as the solver would). The references stay valid until the next
     * assembly or solve_step.
     */
    AssembledSystem assemble_system(double t, const Vector &T, double gamma, Vector &f);

    /**
     * For a scheme that solves T inside its own Newton loop with backward
     * Euler, M (T − Tₙ) = Δt f(T, tₙ₊₁) (coupling/monolithic.cc):
     * begin_step() sets the step, implicit_residual() gives f(T, t) with the
     * sources and the configuration as they are now (nothing cached), the
     * mass M stays that of the reference configuration (assemble_mass), and
     * accept_temperature() takes the converged T as this step's solution
     * with its heat balance, as solve_step() would.
     */
    void begin_step(double time_old, double time_new);
    void implicit_residual(double t, const Vector &T, Vector &f);
    /// A = ∂(K T − F)/∂T at @p T (constrained rows empty), as assemble_system.
    const dealii::TrilinosWrappers::SparseMatrix &implicit_tangent(double t, const Vector &T);
    /// M v (lumped if Heat/Linear solver asks for it).
    void mass_vmult(Vector &Mv, const Vector &v) const;
    const dealii::TrilinosWrappers::SparseMatrix &get_mass_matrix() const { return mass_matrix; }
    bool uses_lumped_mass() const { return parameters.lumped_mass; }
    const Vector &lumped_mass_vector() const { return lumped_mass; }
    /// Set the current temperature (owned; hanging nodes are distributed).
    void set_temperature(const Vector &T_owned);
    void accept_temperature(const Vector &T_owned, double time_old, double time_new);
    /// Dirichlet values g(t) into the owned @p y.
    void apply_dirichlet_values(const double t, Vector &y) const { apply_dirichlet(t, y); }
    /// Hanging nodes and Temperature boundaries (homogeneous).
    const dealii::AffineConstraints<double> &get_constraints() const { return constraints; }
    const dealii::AffineConstraints<double> &hanging_constraints() const { return hanging; }
    const Vector &owned_old_temperature() const { return old_solution; }

    /// Advance T from the committed state at @p time_old to @p time_new
    /// (with Method = steady: the steady state at @p time_new, solve_steady).
    Statistics solve_step(double time_old, double time_new);

    /// One steady solve: Newton's residuals |f| (mW, free rows), largest
    /// increments |dT| (K) and line-search step lengths, per iteration.
    struct SteadyReport
    {
      bool                converged = false;
      std::string         failure;
      double              time = 0;
      std::vector<double> residuals, increments, step_lengths;
    };
    /**
     * The steady state f(T, t) = 0 (no capacity term: -K(T) T + F(T, t) = 0,
     * seed eq. 26 without rho c dT/dt) by Newton with the consistent tangent
     * and a backtracking line search, from the current temperature, with the
     * Temperature boundaries at g(t). On success the current temperature is
     * the steady one; on failure it is the last iterate (the caller reverts).
     * doc/thermal.md, "Steady state".
     */
    Statistics solve_steady(double t);
    const SteadyReport &steady_report() const { return last_steady; }
    /// Heat flows into the bodies at the current temperature (mW): through
    /// each Flux/Convection/Radiation boundary, by sources, and through the
    /// Temperature boundaries from the temperature gradient k grad T . n
    /// (not from the residual, so the balance is not closed by construction);
    /// error = |sum| / largest term.
    struct SteadyBalance
    {
      std::map<dealii::types::boundary_id, double> boundary;
      double source = 0, dirichlet = 0, error = 0;
    };
    SteadyBalance steady_balance(double t) const;
    /// Accept the last solve_step (T becomes the committed state, heat flows accumulate).
    void commit();
    /// Forget the last solve_step (cut-back): T returns to the committed state.
    void revert();

    const dealii::DoFHandler<dim> &get_dof_handler() const { return dof_handler; }
    const dealii::Mapping<dim>    &get_mapping() const;
    const dealii::Quadrature<dim> &get_quadrature() const { return quadrature; }
    /// Current (last solved) temperature, ghosted, K.
    const Vector &temperature() const { return temperature_ghosted; }
    /// Committed temperature, ghosted, K.
    const Vector &old_temperature() const { return old_temperature_ghosted; }
    /// Adds "temperature" to @p data_out.
    void attach_output(dealii::DataOut<dim> &data_out) const;

    /// ∫ ρ c T dv over the current configuration (N·mm = mJ).
    double heat_content() const;
    /// ∫ s dv over the current configuration of a per-quadrature-point rate
    /// (mW/mm³ → mW), as the thermal phase integrates its sources.
    double integrate(const HeatSource &s) const;
    /// T at a point of the reference configuration (K; NaN if outside the mesh).
    double temperature_at(const dealii::Point<dim> &point) const;
    /// Mean temperature of each locally owned cell (by active_cell_index; K).
    dealii::Vector<double> cell_mean_temperature() const;
    dealii::types::global_dof_index n_dofs() const { return dof_handler.n_dofs(); }

    /// Checkpoint: attach the committed temperature to the triangulation (call
    /// before Triangulation::save, after the mechanics' own attachments), and
    /// read it back after Triangulation::load in the same order.
    void prepare_checkpoint();
    void load_checkpoint();
    /// Heat-balance accumulators and the last internal step, for state.txt.
    NamedValues checkpoint_scalars() const;
    void        restore_scalars(const NamedValues &values);
    /// Heat that entered through each flux/convection/radiation boundary during
    /// the last solve_step (mJ, trapezoidal in time).
    const std::map<dealii::types::boundary_id, double> &step_boundary_heat() const
    {
      return step_heat_in;
    }
    /// Heat through all Temperature boundaries during the last step, from the
    /// balance ΔH − sources − other boundaries (mJ).
    double step_dirichlet_heat() const { return step_dirichlet_heat_in; }
    /// ∫∫ sources dv dt during the last step (mJ).
    double step_source_heat() const { return step_source; }
    /// Accumulated over committed steps (mJ), per boundary id (Temperature
    /// boundaries together under numbers::invalid_boundary_id) and sources.
    const std::map<dealii::types::boundary_id, double> &boundary_heat_flow() const
    {
      return total_heat_in;
    }
    double source_heat() const { return total_source; }

    /// Whether temperature_at_quadrature_points may read the current and the
    /// committed field by the dof positions of the reference cell table (both
    /// have its layout). O(dofs): ask once per loop over the cells.
    bool point_values_by_table() const;
    /// T at the points of @p quadrature in @p cell (a cell of the shared
    /// triangulation): the current and the committed values; @p by_table is
    /// point_values_by_table() of this loop. Not reentrant (it caches an
    /// FEValues): call it from one thread, as the coupling does when it fills
    /// the per-point temperatures the mechanics reads.
    void temperature_at_quadrature_points(
      const typename dealii::Triangulation<dim>::active_cell_iterator &cell,
      const dealii::Quadrature<dim>                                   &quadrature,
      std::vector<double>                                             &T_new,
      std::vector<double>                                             &T_old,
      bool                                                             by_table) const;

  private:
    struct Ode;
    void   assemble_mass();
    /// r = f(T, t) (if @p rhs) and A = ∂(K T − F)/∂T (if @p tangent), T from the owned @p y.
    void   assemble(double t, const Vector &y, Vector *rhs, dealii::TrilinosWrappers::SparseMatrix *tangent);
    /// assemble()'s last part: the exchange's rhs, the Dirichlet rows (M ġ) and the
    /// constrained rows of the tangent, after the cells' contributions.
    void   finish_assembly(double t, const Vector &y, const std::map<dealii::types::global_dof_index, double> &g_dot,
                           Vector *rhs, dealii::TrilinosWrappers::SparseMatrix *tangent);
    /// F = ∫ s φ dv of the mechanics' sources into step_sources (fast linear path).
    void   assemble_step_sources();
    /// rhs += the prescribed fluxes and the convection loads h T∞ at t (fast linear path).
    void   add_prescribed_fluxes(double t, Vector &rhs);
    /// M_fD (free rows, Dirichlet columns) into dirichlet_mass (fast linear
    /// path with Temperature boundaries; K_fD is in the tangent's columns).
    void   assemble_dirichlet_couplings();
    /// ġ at the Dirichlet dofs at t where it is not zero (central difference).
    std::map<dealii::types::global_dof_index, double> dirichlet_rates(double t) const;
    /// Dirichlet values g(t) at the constrained dofs (locally relevant).
    void   dirichlet_values(double t, std::map<dealii::types::global_dof_index, double> &values) const;
    void   apply_dirichlet(double t, Vector &y) const;
    std::map<dealii::types::boundary_id, double> boundary_flows(double t, const Vector &T_ghosted) const;
    double source_power(double t) const;
    double heat_content(const Vector &T_ghosted) const;
    unsigned int solve_newton(Vector &x, const Vector &b, double tolerance);
    unsigned int solve_mass(Vector &x, const Vector &b, double tolerance);
    /// M + γA (− γ∂q/∂T) and its factorisation; without @p exact one of a
    /// γ within 20 % is kept (a preconditioner of ARKode's GMRES).
    void   setup_newton(double gamma, bool exact = false);
    /// The contact exchange's couplings into the tangent's, the Newton
    /// matrix's and mass_in_pattern's pattern (when new ones appeared).
    void   update_exchange_pattern();
    /// The cells' pattern (hanging and Temperature constraints kept).
    dealii::DynamicSparsityPattern sparsity() const;
    /// cell_pattern with, in the rows owned here, every pair of dofs of each
    /// of @p groups and of the masters' cell neighbours (the faces a sliding
    /// slave reaches next: fewer rebuilds of the pattern).
    void exchange_sparsity(const std::vector<std::vector<dealii::types::global_dof_index>> &groups,
                           dealii::DynamicSparsityPattern &dsp) const;
    /// Whether exchange_pattern has every pair of each of @p groups (all
    /// processes); the groups found covered are remembered (covered_groups).
    bool covers(const std::vector<std::vector<dealii::types::global_dof_index>> &groups);
    /// Boundary, source and Dirichlet heat of the step just solved (trapezoidal in time).
    void   step_balance(double time_old, double time_new);
    /// Steady state: f(T, t) with the Temperature and hanging rows zero (|f| returned).
    double steady_residual(double t, const Vector &T, Vector &f);
    /// Steady state: solve A delta = f, A the tangent with unit Temperature and hanging rows.
    void   steady_linear_solve(double t, const Vector &T, const Vector &f, Vector &delta);
    /// Heat into the bodies through the Temperature boundaries, k grad T . n (mW).
    double dirichlet_heat_flow(const Vector &T_ghosted) const;
    /// The balance loops' per-cell numbers on the reference configuration
    /// (FEValues flags of heat_content), built once per setup().
    const thermal::CellTable &reference_cells() const;
    /// The same on the current configuration (flags of source_power and
    /// integrate) for the cells with mechanical sources, once per
    /// set_configuration(); nullptr without a moving
    /// mapping (the reference MappingQ reuses values between similar cells,
    /// which a loop over other cells would not reproduce bit for bit).
    const thermal::CellTable *current_cells() const;

    MPI_Comm                                                 mpi_communicator;
    const dealii::parallel::DistributedTriangulationBase<dim> &triangulation;
    const Parameters                                         parameters;
    const ThermalBoundaryConditions<dim>                    &boundary_conditions;
    std::map<dealii::types::material_id, ThermalMaterial>    materials;
    dealii::TimerOutput                                     &timer;

    dealii::FE_Q<dim>       fe;
    dealii::MappingQ<dim>   reference_mapping;
    std::unique_ptr<dealii::Mapping<dim>> current_mapping;
    Vector                  configuration; // ghosted displacement behind current_mapping
    /// x = X + u at every vertex of an owned cell (by vertex index) where the
    /// mechanics is Q1, what MappingQ1Eulerian::get_vertices computes per
    /// call: the Q1 conduction kernel's input (thermal_assembly.cc).
    std::vector<dealii::Point<dim>> moved_vertices;
    /// The positions of each vertex's displacement dofs in the ghosted
    /// displacement's local array (by vertex index, −1: no owned cell has
    /// it), for the layout vertex_dofs_map of the numbering of vertex_dofs_of.
    std::vector<std::array<int, dim>>  vertex_dofs;
    std::unique_ptr<Epetra_BlockMap>   vertex_dofs_map;
    const dealii::DoFHandler<dim>     *vertex_dofs_of = nullptr;
    dealii::types::global_dof_index    vertex_dofs_n  = 0;
    /// Where each owned cell's tangent entries sit in Epetra's CRS value
    /// array (active cell index × n_dofs², −1: not found yet, −2: the cell
    /// adds another way), for the value array tangent_positions_values.
    std::vector<int> tangent_positions;
    const double    *tangent_positions_values = nullptr;
    dealii::DoFHandler<dim> dof_handler;
    dealii::QGauss<dim>     quadrature;
    dealii::QGauss<dim - 1> face_quadrature;
    dealii::IndexSet        locally_owned_dofs, locally_relevant_dofs;
    dealii::AffineConstraints<double> constraints; // hanging + Dirichlet, homogeneous
    dealii::AffineConstraints<double> hanging;     // hanging only, for distribute()
    std::vector<dealii::types::global_dof_index> dirichlet_dofs; // owned
    std::vector<bool> is_dirichlet;                // by local index in locally_relevant_dofs

    std::shared_ptr<dealii::FunctionParser<dim>> initial_function, source_function;
    HeatSource heat_source;
    Exchange   exchange;

    dealii::TrilinosWrappers::SparseMatrix mass_matrix, tangent_matrix, newton_matrix;
    /// M (or its lumped diagonal) in the Newton matrix's pattern when the
    /// exchange extends it (mass_matrix keeps the cells' pattern for its solves).
    dealii::TrilinosWrappers::SparseMatrix mass_in_pattern;
    bool mass_in_pattern_current = false;
    Vector lumped_mass, mass_diagonal;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG>    newton_amg;
    /// KLU of M + γA, its symbolic analysis kept while the pattern is (core/klu_factorization.h).
    std::unique_ptr<KluFactorization>                            newton_direct;
    /// KLU of M (reference configuration: factorised once per assemble_mass)
    /// for ARKode's mass solves where the Newton matrix is direct too.
    std::unique_ptr<KluFactorization>                            mass_direct;
    /// tangent_matrix and newton_matrix have the exchange's couplings of its last couplings().
    bool exchange_pattern_current = false;
    /// The exchange's groups exchange_pattern is known to hold: covers()
    /// looks up only the others (the list only grows; two_blocks ends with
    /// 211 groups, of which a step adds a few).
    std::set<std::vector<dealii::types::global_dof_index>> covered_groups;
    dealii::DynamicSparsityPattern cell_pattern, exchange_pattern; // sparsity(), exchange_sparsity()
    dealii::TrilinosWrappers::PreconditionJacobi                  mass_jacobi;
    bool   operators_current = false, use_direct = true, linear = true;
    bool   tangent_current = false, has_convection = false; // tangent assembled for this configuration
    bool   sources_current = false;                         // step_sources assembled for this step
    bool   couplings_current = false;                       // dirichlet_* for this configuration
    bool   loads_current = false, loads_vary = false;      // face_loads for this configuration; some flux(t), T∞(t)
    Vector face_loads;                                      // constant fluxes and h T∞ (fast linear path)
    bool   convection_varies = false, dirichlet_varies = false; // some h(t), some g(t)
    /// The columns of the Dirichlet dofs that the constrained K and M drop:
    /// f_free = −K y − K_fD y_D − M_fD ġ_D + F (the slow path's cell integrals).
    dealii::TrilinosWrappers::SparseMatrix dirichlet_mass;
    Vector step_sources;                                    // ∫ s φ dv of the mechanics' sources
    /// The residual of a linear problem from K and the step's sources (false: not applicable).
    bool   linear_residual(double t, const Vector &y, Vector &rhs);
    double current_gamma = -1;
    double step_length = 1; // of the current solve_step (for ġ)
    double last_internal_step = 0;
    bool   has_dirichlet = false, has_hanging = false;
    unsigned long linear_iterations = 0, mass_solves = 0;
    bool          solving_steady = false; // dirichlet_rates() is zero: no dT/dt anywhere
    SteadyReport  last_steady;

    Vector solution, old_solution;                       // owned
    Vector temperature_ghosted, old_temperature_ghosted; // ghosted
    mutable Vector scratch_ghosted;
    double committed_time = 0;
    /// heat_content() of solution and of old_solution where known (NaN: not
    /// computed since they changed): one cell loop per step, not two.
    double solution_heat_content = 0, old_heat_content = 0;

    std::map<dealii::types::boundary_id, double> step_heat_in, total_heat_in;
    double step_dirichlet_heat_in = 0, step_source = 0, total_source = 0;

    std::unique_ptr<dealii::parallel::distributed::SolutionTransfer<dim, Vector>> checkpoint_transfer;
    Vector checkpoint_vector;
    mutable std::unique_ptr<dealii::FEValues<dim>> point_values;
    mutable std::unique_ptr<dealii::Quadrature<dim>> point_quadrature;
    mutable thermal::CellTable reference_table, current_table;
  };
} // namespace anvil
