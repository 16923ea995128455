// The monolithic scheme's Jacobian (doc/monolithic.md): its structure (the
// cells and contact links of the distance-2 colouring, the sparsity of both
// fields), the coloured forward differences of the cross blocks beside the
// problems' own tangents, and the tangent check against central differences.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <anvil/core/instantiate.h>

#include "monolithic.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace anvil
{
  using namespace dealii;
  using Vector = TrilinosWrappers::MPI::Vector;

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
   * step's set changes (the contact's search at the start of the step, and a
   * face met outside it during the step).
   */
  template <int dim>
  void Monolithic<dim>::update_contact_links()
  {
    const auto comm = this->problem->mechanics()->get_dof_handler().get_communicator();
    CellDofs   u_columns, T_rows;
    this->problem->contact_problem().heat_links(u_columns, T_rows);
    u_columns = gather_cells(u_columns, comm);
    T_rows    = gather_cells(T_rows, comm);
    if (u_columns == contact_u_columns && T_rows == contact_T_rows)
      return;
    contact_u_columns = u_columns;
    contact_T_rows    = T_rows;
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
    this->problem->log() << "monolithic: " << u_columns.size() << " contact links, "
                         << n_colours_u << " displacement colours" << std::endl;
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
    // With contact heat, central differences: the conductance h₀(p/H)^e A
    // varies on the scale of the penetration, which a stiff penalty makes
    // ~1e-5 mm; a forward step of 1e-7 mm then errs by ~1e-4 of K_Tu
    // (doc/monolithic.md, "Contact"). One more sweep of the u colours.
    const bool central = contact_heat;
    auto       f_at    = [&](const unsigned int c, const double h, Vector &result) {
      Vector du(u);
      du = 0;
      for (const auto j : owned_u)
        if (colour_u[j] == c && !c_u.is_constrained(j))
          du(j) = h;
      du.compress(VectorOperation::insert);
      c_u.distribute(du); // hanging nodes follow their masters
      du += u;
      mech.set_displacement(du);
      if (!mech.assemble_system(false))
        return false;
      heat.set_configuration(mech.get_dof_handler(), mech.displacement());
      if (contact_heat) // conductance and frictional power at u + h e_c
        this->problem->contact_problem().prepare_heat(dt);
      heat.implicit_residual(t, T, result);
      return true;
    };
    for (unsigned int c = 0; c < n_colours_u; ++c)
      {
        if (!f_at(c, h_u, df_u[c]))
          return false;
        if (central)
          {
            if (!f_at(c, -h_u, f_c))
              return false;
            df_u[c] -= f_c;
            df_u[c] *= 0.5 / h_u;
          }
        else
          {
            df_u[c] -= f;
            df_u[c] *= 1. / h_u;
          }
      }
    mech.set_displacement(u);
    heat.set_configuration(mech.get_dof_handler(), mech.displacement());

    add_difference_blocks(dt, dR_u, df_T, df_u);
    jacobian.compress(VectorOperation::add);
    return true;
  }

  // The differenced blocks into the Jacobian, with the heat block (M + Δt A
  // and the exchange's diagonal) copied in: the AMG preconditions with it.
  template <int dim>
  void Monolithic<dim>::add_difference_blocks(const double dt, const std::vector<Vector> &dR_u,
                                              const std::vector<Vector> &df_T,
                                              const std::vector<Vector> &df_u)
  {
    const auto &c_u = this->problem->mechanics()->update_constraints();
    const auto &c_T = this->problem->heat()->get_constraints();
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
  }

  template <int dim>
  void Monolithic<dim>::print_tangent_check(const double t, const double dt, const Vector &u,
                                            const Vector &T)
  {
    // A fixed direction on the free dofs of both fields, each scaled to its
    // own values: J v against (R(x + v) − R(x − v)) / 2, block row by block row.
    // 1e-7 of the values: a stiff penalty's penetrations are ~1e-6 mm, and a
    // larger v crossed the contact's kinks (false errors of 5e-2 with 1e-6).
    const auto  &c_u = this->problem->mechanics()->update_constraints();
    const auto  &c_T = this->problem->heat()->get_constraints();
    const auto   comm = this->problem->mechanics()->get_dof_handler().get_communicator();
    const double s_u  = 1e-7 * std::max(1.0, u.linfty_norm());
    const double s_T  = 1e-7 * std::max(1.0, T.linfty_norm());
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


#define INSTANTIATE(dim)                                                                          \
  template void Monolithic<dim>::setup_structure();                                               \
  template void Monolithic<dim>::update_contact_links();                                          \
  template void Monolithic<dim>::build_pattern();                                                 \
  template bool Monolithic<dim>::assemble_jacobian(double, double, const Vector &, const Vector &, \
                                                   const Vector &, const Vector &);               \
  template void Monolithic<dim>::print_tangent_check(double, double, const Vector &, const Vector &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
