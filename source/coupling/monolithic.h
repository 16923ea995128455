#pragma once
// The monolithic scheme's class (coupling/monolithic.cc: the Newton loop and
// its evaluations; coupling/monolithic_jacobian.cc: the coloured-difference
// Jacobian, its structure and the tangent check). Private to coupling/.
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/core/scene.h>
#include <anvil/coupling/dof_colouring.h>
#include <anvil/coupling/interface.h>

#include <map>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * Displacement u and temperature T of the step solved together by one
   * Newton loop (the seed's reference system, §2.2, of order (n_dim + 1)
   * n_node): R_u(u, T) = 0 (equilibrium, eq. 12) and backward Euler for the
   * heat equation (eq. 26), R_T = M (T − Tₙ) − Δt f(T, u) = 0, with the
   * Jacobian
   *   [ K_uu  K_uT ] [δu]     [R_u]
   *   [ K_Tu  K_TT ] [δT] = − [R_T].
   * K_uu is the mechanics' consistent tangent, M + Δt ∂(KT − F)/∂T the heat
   * problem's own; the derivatives through the other field — dσ/dT at the
   * points (thermal expansion, softening, temperature-dependent elasticity),
   * the mechanical heat sources with respect to T and to u (eq. 21–25), the
   * conduction and boundary integrals on the current configuration with
   * respect to u — are one-sided finite differences of the assembled
   * residuals, compressed by a distance-2 colouring of the columns (a few
   * dozen residual assemblies per iteration, whatever the mesh size).
   */
  template <int dim>
  class Monolithic : public CouplingScheme<dim>
  {
  public:
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    static void declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Monolithic tolerance", "1e-8", dealii::Patterns::Double(0),
                        "monolithic: Newton stops when both residuals are below this times "
                        "their scale (|f_int| for the mechanics, the heat of the step "
                        "|M (T - T_n)| for the heat equation).");
      prm.declare_entry("Monolithic iterations", "15", dealii::Patterns::Integer(1),
                        "monolithic: Newton iterations before the step is cut back.");
      prm.declare_entry("Monolithic linear solver", "automatic",
                        dealii::Patterns::Selection("automatic|direct|iterative"),
                        "monolithic: KLU on the assembled block matrix (direct), or GMRES "
                        "preconditioned by one AMG per diagonal block (iterative); automatic: "
                        "direct up to Monolithic direct limit unknowns.");
      prm.declare_entry("Monolithic direct limit", "200000", dealii::Patterns::Integer(1),
                        "monolithic: largest number of unknowns (both fields) solved directly "
                        "by the automatic choice.");
      prm.declare_entry("Monolithic check tangent", "false", dealii::Patterns::Bool(),
                        "monolithic: at every iteration compare the coupled tangent with "
                        "central finite differences of the coupled residual in a fixed "
                        "direction, and print the relative error of each block row.");
    }

    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return true; }

    void parse_parameters(dealii::ParameterHandler &prm, const Scene &) override
    {
      prm.enter_subsection("Physics");
      tolerance      = prm.get_double("Monolithic tolerance");
      max_iterations = prm.get_integer("Monolithic iterations");
      linear_solver  = prm.get("Monolithic linear solver");
      direct_limit   = prm.get_integer("Monolithic direct limit");
      check_tangent  = prm.get_bool("Monolithic check tangent");
      prm.leave_subsection();
    }

    void initialize(CoupledProblem<dim> &p) override
    {
      CouplingScheme<dim>::initialize(p);
      p.connect_fields(false);
      setup_structure();
    }

    StepReport<dim> advance(double t_old, double t_new) override;

  private:
    struct State; // residuals of one evaluation
    void setup_structure();
    void update_contact_links();
    bool evaluate(double t, const Vector &u, const Vector &T, Vector &b_u, Vector &f);
    bool assemble_jacobian(double t, double dt, const Vector &u, const Vector &T,
                           const Vector &b_u, const Vector &f);
    void build_pattern();
    void add_difference_blocks(double dt, const std::vector<Vector> &dR_u,
                               const std::vector<Vector> &df_T, const std::vector<Vector> &df_u);
    unsigned int solve(const Vector &b_u, const Vector &b_T, Vector &du, Vector &dT);
    double       heat_residual(const Vector &T, const Vector &f, double dt, Vector &b_T) const;
    void         print_tangent_check(double t, double dt, const Vector &u, const Vector &T);
    double       line_search(double t, double dt, const Vector &u, const Vector &T,
                             const Vector &du, const Vector &dT, double scale_u, double scale_T,
                             double merit_0);

    double       tolerance = 1e-8;
    unsigned int max_iterations = 15, direct_limit = 200000;
    std::string  linear_solver = "automatic";
    bool         check_tangent = false;

    dealii::IndexSet                  owned_u, owned_T, owned;
    dealii::types::global_dof_index   n_u = 0, n_T = 0;
    std::vector<unsigned int> colour_u, colour_T;
    unsigned int              n_colours_u = 0, n_colours_T = 0;
    // Owned rows and the columns of the other field (or the same) they couple to.
    std::map<dealii::types::global_dof_index, DofList> u_to_T, T_to_u, T_to_T;
    // Contact: the mesh's own cells (gathered) and T_to_u of the cells alone,
    // to which the step's contact links are added; the exchange's T columns.
    CellDofs                                   all_u, all_T;
    std::map<dealii::types::global_dof_index, DofList> T_to_u_cells, T_to_T_contact;
    CellDofs                                   contact_u_columns, contact_T_rows; // the links coloured
    std::size_t                                K_nonzeros = 0;
    bool                                       contact_heat    = false;
    double                                     step_length     = 0;
    dealii::TrilinosWrappers::SparseMatrix jacobian, heat_block; // heat_block: K_TT for the AMG
    bool                           pattern_ready = false;
    unsigned int                   last_linear_iterations = 0;
  };
} // namespace anvil
