// The monolithic thermo-mechanical Newton: displacement and temperature solved
// together in every step (doc/monolithic.md). The column colouring of its
// coloured differences is in dof_colouring.cc, the block solve in
// block_solve.cc: both generic.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <anvil/core/scene.h>
#include <anvil/coupling/block_solve.h>
#include <anvil/coupling/dof_colouring.h>
#include <anvil/coupling/interface.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <tuple>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    using Vector = TrilinosWrappers::MPI::Vector;
  } // namespace

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
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Monolithic tolerance", "1e-8", Patterns::Double(0),
                        "monolithic: Newton stops when both residuals are below this times "
                        "their scale (|f_int| for the mechanics, the heat of the step "
                        "|M (T - T_n)| for the heat equation).");
      prm.declare_entry("Monolithic iterations", "15", Patterns::Integer(1),
                        "monolithic: Newton iterations before the step is cut back.");
      prm.declare_entry("Monolithic linear solver", "automatic",
                        Patterns::Selection("automatic|direct|iterative"),
                        "monolithic: KLU on the assembled block matrix (direct), or GMRES "
                        "preconditioned by one AMG per diagonal block (iterative); automatic: "
                        "direct up to Monolithic direct limit unknowns.");
      prm.declare_entry("Monolithic direct limit", "200000", Patterns::Integer(1),
                        "monolithic: largest number of unknowns (both fields) solved directly "
                        "by the automatic choice.");
      prm.declare_entry("Monolithic check tangent", "false", Patterns::Bool(),
                        "monolithic: at every iteration compare the coupled tangent with "
                        "central finite differences of the coupled residual in a fixed "
                        "direction, and print the relative error of each block row.");
    }

    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return true; }

    void parse_parameters(ParameterHandler &prm, const Scene &scene) override
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

    IndexSet                  owned_u, owned_T, owned;
    types::global_dof_index   n_u = 0, n_T = 0;
    std::vector<unsigned int> colour_u, colour_T;
    unsigned int              n_colours_u = 0, n_colours_T = 0;
    // Owned rows and the columns of the other field (or the same) they couple to.
    std::map<types::global_dof_index, DofList> u_to_T, T_to_u, T_to_T;
    // Contact: the mesh's own cells (gathered) and T_to_u of the cells alone,
    // to which the step's contact links are added; the exchange's T columns.
    CellDofs                                   all_u, all_T;
    std::map<types::global_dof_index, DofList> T_to_u_cells, T_to_T_contact;
    std::size_t                                n_contact_links = 0, K_nonzeros = 0;
    bool                                       contact_heat    = false;
    double                                     step_length     = 0;
    TrilinosWrappers::SparseMatrix jacobian, heat_block; // heat_block: K_TT for the AMG
    bool                           pattern_ready = false;
    unsigned int                   last_linear_iterations = 0;
  };

  template <int dim>
  void Monolithic<dim>::setup_structure()
  {
    auto      &mech = *this->problem->mechanics();
    auto      &heat = *this->problem->heat();
    const auto comm = mech.get_dof_handler().get_communicator();
    n_u             = mech.n_dofs();
    n_T             = heat.n_dofs();
    owned_u         = mech.get_dof_handler().locally_owned_dofs();
    owned_T         = heat.get_dof_handler().locally_owned_dofs();
    owned           = IndexSet(n_u + n_T);
    owned.add_indices(owned_u);
    owned.add_indices(owned_T, n_u);
    owned.compress();

    // Both DoFHandlers live on one triangulation: their cells run in step.
    CellDofs local_u, local_T;
    DofList  du(mech.get_dof_handler().get_fe().n_dofs_per_cell());
    DofList  dT(heat.get_dof_handler().get_fe().n_dofs_per_cell());
    auto     cell_T = heat.get_dof_handler().begin_active();
    for (const auto &cell_u : mech.get_dof_handler().active_cell_iterators())
      {
        if (cell_u->is_locally_owned() || cell_u->is_ghost())
          {
            cell_u->get_dof_indices(du);
            cell_T->get_dof_indices(dT);
            for (const auto i : du)
              if (owned_u.is_element(i))
                {
                  auto &row = u_to_T[i];
                  row.insert(row.end(), dT.begin(), dT.end());
                }
            for (const auto i : dT)
              if (owned_T.is_element(i))
                {
                  auto &row_u = T_to_u[i];
                  row_u.insert(row_u.end(), du.begin(), du.end());
                  auto &row_T = T_to_T[i];
                  row_T.insert(row_T.end(), dT.begin(), dT.end());
                }
            if (cell_u->is_locally_owned())
              {
                local_u.push_back(du);
                local_T.push_back(dT);
              }
          }
        ++cell_T;
      }
    for (auto *rows : {&u_to_T, &T_to_u, &T_to_T})
      for (auto &[i, columns] : *rows)
        {
          std::sort(columns.begin(), columns.end());
          columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
        }
    all_u        = gather_cells(local_u, comm);
    all_T        = gather_cells(local_T, comm);
    T_to_u_cells = T_to_u;
    auto &contact = this->problem->contact_problem();
    contact_heat  = !contact.empty() && contact.has_heat();
    colour_T = colour_columns(all_T, all_T, n_T, n_T, n_colours_T);
    colour_u = colour_columns(all_u, all_T, n_u, n_T, n_colours_u);
    this->problem->log() << "monolithic: " << n_u + n_T << " unknowns; the cross blocks by "
                         << n_colours_T << " + " << n_colours_u
                         << " coloured finite differences per iteration" << std::endl;
  }

  /**
   * Contact couples nodes that share no cell: a slave node's heat exchange
   * (eq. 30–34) depends on the displacements of the node, of the master face
   * below it and of its surface neighbours, and writes the temperature rows
   * of the node and the face. Each slave node–master face pair that may touch
   * in the step enters the colouring as one more "cell"; recoloured when the
   * set grows (the contact's own search enlarges it, never shrinks it).
   */
  template <int dim>
  void Monolithic<dim>::update_contact_links()
  {
    const auto comm = this->problem->mechanics()->get_dof_handler().get_communicator();
    CellDofs   u_columns, T_rows;
    this->problem->contact_problem().heat_links(u_columns, T_rows);
    u_columns = gather_cells(u_columns, comm);
    T_rows    = gather_cells(T_rows, comm);
    if (u_columns.size() == n_contact_links)
      return;
    n_contact_links = u_columns.size();
    CellDofs columns(all_u), links(all_T);
    columns.insert(columns.end(), u_columns.begin(), u_columns.end());
    links.insert(links.end(), T_rows.begin(), T_rows.end());
    colour_u       = colour_columns(columns, links, n_u, n_T, n_colours_u);
    T_to_u         = T_to_u_cells;
    T_to_T_contact.clear();
    for (std::size_t k = 0; k < T_rows.size(); ++k)
      for (const auto i : T_rows[k])
        if (owned_T.is_element(i))
          {
            T_to_u[i].insert(T_to_u[i].end(), u_columns[k].begin(), u_columns[k].end());
            T_to_T_contact[i].insert(T_to_T_contact[i].end(), T_rows[k].begin(), T_rows[k].end());
          }
    for (auto *rows : {&T_to_u, &T_to_T_contact})
      for (auto &[i, columns] : *rows)
        {
          std::sort(columns.begin(), columns.end());
          columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
        }
    pattern_ready = false;
    this->problem->log() << "monolithic: " << n_contact_links << " contact links, "
                         << n_colours_u << " displacement colours" << std::endl;
  }

  /// b_u = −R_u and f(T, u) at (u, T): mechanics assembled with the points at T.
  template <int dim>
  bool Monolithic<dim>::evaluate(const double t, const Vector &u, const Vector &T, Vector &b_u,
                                 Vector &f)
  {
    auto &mech = *this->problem->mechanics();
    auto &heat = *this->problem->heat();
    mech.set_displacement(u);
    heat.set_temperature(T);
    this->problem->point_temperatures_from_heat_field();
    if (!mech.assemble_system(false))
      return false;
    b_u = mech.get_system_rhs();
    heat.set_configuration(mech.get_dof_handler(), mech.displacement());
    if (contact_heat) // the exchange at this contact state (eq. 30–34)
      this->problem->contact_problem().prepare_heat(step_length);
    heat.implicit_residual(t, T, f);
    return true;
  }

  /// b_T = −R_T = Δt f − M (T − Tₙ) (eq. 26 by backward Euler), constrained rows 0; returns |M (T − Tₙ)|.
  template <int dim>
  double Monolithic<dim>::heat_residual(const Vector &T, const Vector &f, const double dt,
                                        Vector &b_T) const
  {
    const auto &heat = *this->problem->heat();
    Vector      change(T), M_change(T);
    change -= heat.owned_old_temperature();
    heat.mass_vmult(M_change, change);
    b_T = f;
    b_T *= dt;
    b_T -= M_change;
    for (const auto i : owned_T)
      if (heat.get_constraints().is_constrained(i))
        {
          b_T(i)      = 0;
          M_change(i) = 0;
        }
    b_T.compress(VectorOperation::insert);
    M_change.compress(VectorOperation::insert);
    return M_change.l2_norm();
  }

  template <int dim>
  void Monolithic<dim>::build_pattern()
  {
    const auto                       &mech = *this->problem->mechanics();
    const auto                       &heat = *this->problem->heat();
    const auto                        comm = mech.get_dof_handler().get_communicator();
    TrilinosWrappers::SparsityPattern sp(owned, comm);
    const auto                       &K = mech.get_system_matrix();
    for (const auto i : owned_u)
      for (auto e = K.begin(i); e != K.end(i); ++e)
        sp.add(i, e->column());
    for (const auto &[i, columns] : u_to_T)
      for (const auto j : columns)
        sp.add(i, n_u + j);
    const auto &M = heat.get_mass_matrix();
    for (const auto i : owned_T)
      for (auto e = M.begin(i); e != M.end(i); ++e)
        sp.add(n_u + i, n_u + e->column());
    for (const auto *rows : {&T_to_T, &T_to_T_contact})
      for (const auto &[i, columns] : *rows)
        for (const auto j : columns)
          sp.add(n_u + i, n_u + j);
    for (const auto &[i, columns] : T_to_u)
      for (const auto j : columns)
        sp.add(n_u + i, j);
    sp.compress();
    jacobian.reinit(sp);
    K_nonzeros = K.n_nonzero_elements();
    pattern_ready = true;
  }

  template <int dim>
  bool Monolithic<dim>::assemble_jacobian(const double t, const double dt, const Vector &u,
                                          const Vector &T, const Vector &b_u, const Vector &f)
  {
    auto &mech = *this->problem->mechanics();
    auto &heat = *this->problem->heat();
    // The diagonal blocks at (u, T): the mechanics' tangent, M + Δt A.
    heat.set_temperature(T);
    this->problem->point_temperatures_from_heat_field();
    mech.set_displacement(u);
    if (!mech.assemble_system(true))
      return false;
    heat.set_configuration(mech.get_dof_handler(), mech.displacement());
    const auto &c_u = mech.update_constraints();
    const auto &c_T = heat.get_constraints();
    // The contact exchange's ∂f/∂T at (u, T) (eq. 30, analytic): collected
    // before the differences below move the contact state.
    std::vector<std::tuple<types::global_dof_index, types::global_dof_index, double>> exchange;
    if (contact_heat)
      {
        auto &contact = this->problem->contact_problem();
        update_contact_links();
        contact.prepare_heat(dt);
        contact.exchange_tangent(
          [&](const types::global_dof_index i) { return c_T.is_constrained(i); },
          [&](const types::global_dof_index i, const types::global_dof_index j, const double d) {
            if (!c_T.is_constrained(j))
              exchange.emplace_back(i, j, d);
          });
      }
    // The mechanics' pattern grows when contact finds new candidates.
    if (!pattern_ready || mech.get_system_matrix().n_nonzero_elements() != K_nonzeros)
      build_pattern();
    heat_block.reinit(heat.get_mass_matrix());
    if (heat.uses_lumped_mass())
      {
        heat_block = 0;
        for (const auto i : owned_T)
          heat_block.set(i, i, heat.lumped_mass_vector()(i));
        heat_block.compress(VectorOperation::insert);
      }
    else
      heat_block.copy_from(heat.get_mass_matrix());
    heat_block.add(dt, heat.implicit_tangent(t, T));
    jacobian = 0;
    const auto &K = mech.get_system_matrix();
    for (const auto i : owned_u)
      for (auto e = K.begin(i); e != K.end(i); ++e)
        jacobian.add(i, e->column(), e->value());

    // R_T = M (T − Tₙ) − Δt f. The diagonal through K_TT (the AMG's block,
    // copied into the Jacobian below), the slave–master couplings directly.
    for (const auto &[i, j, d] : exchange)
      if (i == j)
        heat_block.add(i, i, -dt * d);
      else
        jacobian.add(n_u + i, n_u + j, -dt * d);

    // Forward differences, one colour of columns at a time; steps at the
    // square root of the round-off of each field's values.
    const double h_T = 1e-7 * std::max(1.0, T.linfty_norm());
    const double h_u = 1e-7 * std::max(1.0, u.linfty_norm());
    std::vector<Vector> dR_u(n_colours_T), df_T(n_colours_T), df_u(n_colours_u);
    Vector              b_c(b_u), f_c(f);
    for (unsigned int c = 0; c < n_colours_T; ++c)
      {
        Vector Tc(T);
        for (const auto j : owned_T)
          if (colour_T[j] == c && !c_T.is_constrained(j))
            Tc(j) += h_T;
        Tc.compress(VectorOperation::insert);
        // The mechanics at T + h e_c; its heat sources into f at T (the
        // conduction's own T-dependence is in A).
        heat.set_temperature(Tc);
        this->problem->point_temperatures_from_heat_field();
        if (!mech.assemble_system(false))
          return false;
        dR_u[c] = mech.get_system_rhs();
        dR_u[c] -= b_u;
        dR_u[c] *= -1. / h_T; // ∂R_u/∂T (b = −R)
        if (contact_heat) // unchanged by T: the same exchange as in f
          this->problem->contact_problem().prepare_heat(dt);
        heat.implicit_residual(t, T, f_c);
        df_T[c] = f_c;
        df_T[c] -= f;
        df_T[c] *= 1. / h_T;
      }
    heat.set_temperature(T);
    this->problem->point_temperatures_from_heat_field();
    for (unsigned int c = 0; c < n_colours_u; ++c)
      {
        Vector du(u);
        du = 0;
        for (const auto j : owned_u)
          if (colour_u[j] == c && !c_u.is_constrained(j))
            du(j) = h_u;
        du.compress(VectorOperation::insert);
        c_u.distribute(du); // hanging nodes follow their masters
        du += u;
        mech.set_displacement(du);
        if (!mech.assemble_system(false))
          return false;
        heat.set_configuration(mech.get_dof_handler(), mech.displacement());
        if (contact_heat) // conductance and frictional power at u + h e_c
          this->problem->contact_problem().prepare_heat(dt);
        heat.implicit_residual(t, T, f_c);
        df_u[c] = f_c;
        df_u[c] -= f;
        df_u[c] *= 1. / h_u;
      }
    mech.set_displacement(u);
    heat.set_configuration(mech.get_dof_handler(), mech.displacement());

    // R_T = M (T − Tₙ) − Δt f: ∂R_T/∂x = −Δt ∂f/∂x.
    for (const auto &[i, columns] : T_to_T)
      if (!c_T.is_constrained(i))
        for (const auto j : columns)
          if (!c_T.is_constrained(j))
            heat_block.add(i, j, -dt * df_T[colour_T[j]](i));
    heat_block.compress(VectorOperation::add);
    for (const auto i : owned_T)
      for (auto e = heat_block.begin(i); e != heat_block.end(i); ++e)
        jacobian.add(n_u + i, n_u + e->column(), e->value());
    for (const auto &[i, columns] : u_to_T)
      if (!c_u.is_constrained(i))
        for (const auto j : columns)
          if (!c_T.is_constrained(j))
            jacobian.add(i, n_u + j, dR_u[colour_T[j]](i));
    for (const auto &[i, columns] : T_to_u)
      if (!c_T.is_constrained(i))
        for (const auto j : columns)
          if (!c_u.is_constrained(j))
            jacobian.add(n_u + i, j, -dt * df_u[colour_u[j]](i));
    jacobian.compress(VectorOperation::add);
    return true;
  }

  template <int dim>
  unsigned int Monolithic<dim>::solve(const Vector &b_u, const Vector &b_T, Vector &du, Vector &dT)
  {
    const bool direct =
      linear_solver == "direct" || (linear_solver == "automatic" && n_u + n_T <= direct_limit);
    const TwoFieldSystem system{jacobian, this->problem->mechanics()->get_system_matrix(),
                                heat_block, owned_u, owned_T, owned, n_u};
    const unsigned int   iterations = solve_two_field(system, b_u, b_T, du, dT, direct);
    this->problem->mechanics()->update_constraints().distribute(du);
    this->problem->heat()->get_constraints().distribute(dT);
    return iterations;
  }

  template <int dim>
  void Monolithic<dim>::print_tangent_check(const double t, const double dt, const Vector &u,
                                            const Vector &T)
  {
    // A fixed direction on the free dofs of both fields, each scaled to its
    // own values: J v against (R(x + v) − R(x − v)) / 2, block row by block row.
    const auto  &c_u = this->problem->mechanics()->update_constraints();
    const auto  &c_T = this->problem->heat()->get_constraints();
    const auto   comm = this->problem->mechanics()->get_dof_handler().get_communicator();
    const double s_u  = 1e-6 * std::max(1.0, u.linfty_norm());
    const double s_T  = 1e-6 * std::max(1.0, T.linfty_norm());
    Vector       v_u(u), v_T(T), v(owned, comm), Jv(owned, comm);
    for (const auto i : owned_u)
      v_u(i) = c_u.is_constrained(i) ? 0. : s_u * std::sin(1.0 + 7.3 * i);
    for (const auto i : owned_T)
      v_T(i) = c_T.is_constrained(i) ? 0. : s_T * std::sin(2.0 + 3.1 * i);
    v_u.compress(VectorOperation::insert);
    v_T.compress(VectorOperation::insert);
    for (const auto i : owned_u)
      v(i) = v_u(i);
    for (const auto i : owned_T)
      v(n_u + i) = v_T(i);
    v.compress(VectorOperation::insert);
    jacobian.vmult(Jv, v);
    Vector Jv_u(u), Jv_T(T);
    for (const auto i : owned_u)
      Jv_u(i) = Jv(i);
    for (const auto i : owned_T)
      Jv_T(i) = Jv(n_u + i);
    Jv_u.compress(VectorOperation::insert);
    Jv_T.compress(VectorOperation::insert);

    Vector r_u[2], r_T[2], f(T);
    for (const int side : {0, 1})
      {
        Vector us(u), Ts(T);
        us.add(side == 0 ? 1. : -1., v_u);
        Ts.add(side == 0 ? 1. : -1., v_T);
        r_u[side] = u;
        r_T[side] = T;
        if (!evaluate(t, us, Ts, r_u[side], f))
          {
            this->problem->log() << "    coupled tangent check: an element inverted" << std::endl;
            return;
          }
        heat_residual(Ts, f, dt, r_T[side]);
      }
    // b = −R: (R(x + v) − R(x − v)) / 2 = (b(x − v) − b(x + v)) / 2.
    r_u[1] -= r_u[0];
    r_u[1] *= 0.5;
    r_T[1] -= r_T[0];
    r_T[1] *= 0.5;
    // The cross blocks' share of J v: what the check would miss without them.
    Vector Kv_u(u), Kv_T(T);
    this->problem->mechanics()->get_system_matrix().vmult(Kv_u, v_u);
    heat_block.vmult(Kv_T, v_T);
    Kv_u -= Jv_u;
    Kv_T -= Jv_T;
    for (const auto i : owned_u)
      if (c_u.is_constrained(i))
        Kv_u(i) = 0;
    Kv_u.compress(VectorOperation::insert);
    const double share_u = Kv_u.l2_norm() / std::max(Jv_u.l2_norm(), 1e-300);
    const double share_T = Kv_T.l2_norm() / std::max(Jv_T.l2_norm(), 1e-300);
    const double n_u_fd = r_u[1].l2_norm(), n_T_fd = r_T[1].l2_norm();
    r_u[1] -= Jv_u;
    r_T[1] -= Jv_T;
    const double e_u = r_u[1].l2_norm() / std::max(n_u_fd, 1e-300);
    const double e_T = r_T[1].l2_norm() / std::max(n_T_fd, 1e-300);
    this->problem->log() << "    coupled tangent check: |J v - FD| / |FD| = "
                         << std::max(e_u, e_T) << " (displacement rows " << e_u
                         << ", temperature rows " << e_T << "); cross-block share of J v: "
                         << share_u << " (displacement rows), " << share_T << " (temperature rows)"
                         << std::endl;
  }

  template <int dim>
  double Monolithic<dim>::line_search(const double t, const double dt, const Vector &u,
                                      const Vector &T, const Vector &du, const Vector &dT,
                                      const double scale_u, const double scale_T,
                                      const double merit_0)
  {
    // Backtracking on the normalised residual max(|R_u|/scale_u, |R_T|/scale_T)
    // (the convergence test's measure): halve until it decreases, at most 6
    // times. Not the mechanics' energy line search: from the first iterate
    // (the mechanics converged at Tₙ) δu · R_u is zero. Past the load maximum
    // the full coupled step can overshoot the neck.
    double alpha = 1;
    Vector ut(u), Tt(T), b(u), f(T), b_T(T);
    for (unsigned int ls = 0; ls < 6; ++ls, alpha *= 0.5)
      {
        ut = u;
        ut.add(alpha, du);
        Tt = T;
        Tt.add(alpha, dT);
        if (!evaluate(t, ut, Tt, b, f))
          continue;
        heat_residual(Tt, f, dt, b_T);
        const double merit = std::max(b.l2_norm() / scale_u, b_T.l2_norm() / scale_T);
        if (std::isfinite(merit) && merit < merit_0)
          break;
      }
    return std::max(alpha, 1. / 64);
  }

  template <int dim>
  StepReport<dim> Monolithic<dim>::advance(const double t_old, const double t_new)
  {
    auto                                       &p    = *this->problem;
    auto                                       &mech = *p.mechanics();
    auto                                       &heat = *p.heat();
    StepReport<dim>                             r;
    typename MechanicalProblem<dim>::StepResult m;
    const double                                dt    = t_new - t_old;
    const double                                start = MPI_Wtime();
    auto                                        fail  = [&](const std::string &why) {
      m.failure = why;
      r.mechanical_solves.push_back(m);
      r.mechanical_wall = MPI_Wtime() - start;
      p.revert();
      return r.fail(why);
    };

    heat.begin_step(t_old, t_new);
    step_length = dt;
    Vector T(heat.owned_old_temperature());
    heat.apply_dirichlet_values(t_new, T);
    // The first iterate: the mechanics converged alone at Tₙ (the isothermal
    // split's mechanical phase, with its line search): past the load maximum
    // the coupled Newton from the bare predictor needs many damped steps.
    // If that fails, the predictor with the boundary values' jump carried
    // into the body (the first iteration of the mechanics' own Newton).
    if (!p.solve_mechanics(t_old, t_new, false, r))
      {
        mech.revert_step();
        const bool has_jump = mech.begin_step(t_old, t_new);
        if (has_jump && !mech.predictor_update(m.linear_iterations))
          return fail(mech.failure_message());
      }
    heat.set_temperature(T);
    p.point_temperatures_from_heat_field();
    Vector              u(mech.owned_displacement()), b_u(u), du(u), f(T), b_T(T), dT(T);
    std::vector<double> error;
    double              r_u0 = 0, r_T0 = 0, heat_floor = 0;
    du = 0;
    dT = 0;
    for (unsigned int it = 0;; ++it)
      {
        if (!evaluate(t_new, u, T, b_u, f))
          return fail(mech.failure_message());
        const double r_u    = b_u.l2_norm();
        const double change = heat_residual(T, f, dt, b_T);
        const double r_T    = b_T.l2_norm();
        if (!std::isfinite(r_u) || !std::isfinite(r_T))
          return fail("the residual is not a number");
        if (it == 0)
          {
            r_u0 = r_u;
            r_T0 = r_T;
          }
        // Scales: the forces of the step; the heat the step stores (or, at
        // the first iterate, the heat that arrives in it).
        // Below 1e-12 of the heat content |M T| the heat residual is round-off
        // (a step that stores almost no heat cannot be measured against itself).
        if (it == 0)
          {
            Vector MT(T);
            heat.mass_vmult(MT, T);
            heat_floor = 1e-12 * MT.l2_norm();
          }
        const double scale_u = std::max(mech.force_scale(), r_u0);
        const double scale_T = std::max(change, r_T0);
        const double e_u     = r_u / std::max(scale_u, 1e-300);
        const double e_T     = r_T / std::max(scale_T, 1e-300);
        error.push_back(std::max(e_u, e_T));
        std::ostringstream line;
        line << "    monolithic " << std::setw(2) << it << ": |R_u| " << std::scientific
             << std::setprecision(2) << r_u << " N (" << e_u << " of " << scale_u << "), |R_T| "
             << r_T << " mJ (" << e_T << " of " << scale_T << ")";
        // Contraction order log(e_k/e_k-1)/log(e_k-1/e_k-2), and e_k/e_k-1²,
        // bounded when the convergence is quadratic.
        const std::size_t k = error.size() - 1;
        if (k >= 1)
          line << ", e/e_prev^2 " << error[k] / (error[k - 1] * error[k - 1]);
        if (k >= 2 && error[k] < error[k - 1] && error[k - 1] < error[k - 2])
          line << ", order " << std::fixed << std::setprecision(2)
               << std::log(error[k] / error[k - 1]) / std::log(error[k - 1] / error[k - 2]);
        m.residuals.push_back(r_u);
        r.thermal_residuals.push_back(r_T);
        // Updates at the round-off of the values: the residuals sit on their floor.
        const bool stagnated = it > 0 && error.back() <= 1e3 * tolerance &&
                               du.linfty_norm() <= 1e-12 * std::max(1.0, u.linfty_norm()) &&
                               dT.linfty_norm() <= 1e-12 * T.linfty_norm();
        const bool converged =
          ((e_u <= tolerance || r_u <= p.mechanics_parameters().absolute_residual_tolerance) &&
           (e_T <= tolerance || r_T <= heat_floor)) ||
          stagnated;
        line << (converged ? "  converged" : "");
        p.log() << line.str() << std::endl;
        if (converged)
          break;
        if (it >= max_iterations)
          return fail("the monolithic Newton did not converge in " + std::to_string(it) +
                      " iterations (|R_u| = " + Utilities::to_string(r_u, 3) +
                      " N, |R_T| = " + Utilities::to_string(r_T, 3) + " mJ)");
        if (!assemble_jacobian(t_new, dt, u, T, b_u, f))
          return fail(mech.failure_message());
        if (check_tangent)
          print_tangent_check(t_new, dt, u, T);
        du = 0;
        dT = 0;
        try
          {
            m.linear_iterations += solve(b_u, b_T, du, dT);
          }
        catch (const std::exception &)
          {
            return fail("the linear solver failed on the monolithic system");
          }
        const double alpha = error.back() > 1e-4 ?
                               line_search(t_new, dt, u, T, du, dT, std::max(scale_u, 1e-300),
                                           std::max(scale_T, 1e-300), error.back()) :
                               1.;
        u.add(alpha, du);
        T.add(alpha, dT);
        m.increments.push_back(alpha * du.l2_norm());
        r.thermal_increments.push_back(alpha * dT.linfty_norm());
        m.line_search_steps.push_back(alpha);
        m.iterations = it + 1;
      }
    m.converged = true;
    // The state of the converged iterate is the last evaluation's: points,
    // heat sources, configuration. T becomes the heat problem's solution.
    heat.accept_temperature(T, t_old, t_new);
    r.thermal.converged            = true;
    r.thermal.internal_steps       = 1;
    r.thermal.nonlinear_iterations = m.iterations;
    r.thermal.linear_solves        = m.iterations;
    r.mechanical_solves.push_back(m);
    r.mechanical_wall = MPI_Wtime() - start;
    const auto &contact = p.contact_problem();
    if (!contact.empty() && contact.last_max_penetration() > contact.maximum_penetration())
      return fail("contact penetration " + Utilities::to_string(contact.last_max_penetration(), 3) +
                  " mm exceeds Contact/Maximum penetration = " +
                  Utilities::to_string(contact.maximum_penetration(), 3) + " mm");
    const double limit = p.mechanics_parameters().maximum_plastic_increment;
    if (limit > 0 && mech.largest_plastic_increment() > limit)
      return fail("the plastic strain grew by " +
                  Utilities::to_string(mech.largest_plastic_increment(), 3) +
                  " at a point (limit " + Utilities::to_string(limit) + ")");
    return r;
  }

  ANVIL_REGISTER_COUPLING_SCHEME(
    Monolithic, "monolithic",
    "displacement and temperature solved together by one Newton loop per step, backward Euler "
    "for the heat equation, the full coupled tangent (the seed's reference system, §2.2; "
    "doc/monolithic.md).")
} // namespace anvil
