// Assembly of the mechanical residual and its exact linearisation for the
// element formulations of MechanicalProblem: plane strain, axisymmetric and
// 3D, each standard or F-bar (doc/mechanics.md).
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/material/kinematics.h>
#include <anvil/contact/contact_problem.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <chrono>
#include <cmath>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // Index of the component (i, J) of a 3x3 tensor in the direction list, or -1.
    struct ComponentIndex
    {
      int index[3][3];
      explicit ComponentIndex(const TangentDirections &d)
      {
        for (auto &row : index)
          for (int &x : row)
            x = -1;
        for (unsigned int k = 0; k < d.n; ++k)
          index[d.kl[k].first][d.kl[k].second] = k;
      }
    };
  } // namespace

  template <int dim>
  Tensor<2, 3> MechanicalProblem<dim>::deformation_gradient(const Tensor<2, dim> &grad_u,
                                                            const double          radial_displacement,
                                                            const double          radius) const
  {
    // Plane strain: F₃₃ = 1. Axisymmetric: the hoop stretch F₃₃ = 1 + u_r/R.
    const double hoop = axisymmetric ? 1 + radial_displacement / radius : 1.;
    return embed<dim>(unit_symmetric_tensor<dim>() + grad_u, hoop);
  }

  template <int dim>
  bool MechanicalProblem<dim>::assemble(const bool with_matrix, const double time)
  {
    TimerOutput::Scope t(timer, with_matrix ? "Mechanics: assembly" : "Mechanics: residual");
    const auto start = std::chrono::steady_clock::now();

    if (with_matrix)
      system_matrix = 0;
    system_rhs     = 0;
    internal_force = 0;
    external_force = 0;
    inertia_force  = 0;

    const UpdateFlags flags = update_gradients | update_JxW_values |
                              (axisymmetric ? update_values | update_quadrature_points : update_default) |
                              (parameters.dynamic || gravity.norm() > 0 ? update_values : update_default);
    FEValues<dim> fe_values(mapping, fe, quadrature, flags);
    FEValues<dim> fe_center(mapping, fe, QMidpoint<dim>(),
                            update_gradients | update_values | update_quadrature_points);
    FEFaceValues<dim> fe_face_values(mapping, fe, face_quadrature,
                                     update_values | update_gradients | update_normal_vectors |
                                       update_JxW_values | update_quadrature_points);

    const unsigned int n_dofs = fe.n_dofs_per_cell();
    const unsigned int n_q    = quadrature.size();
    FullMatrix<double> cell_matrix(n_dofs, n_dofs);
    Vector<double>     cell_internal(n_dofs), cell_external(n_dofs), cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<double>                  local_u(n_dofs), local_u_old(n_dofs);
    std::vector<double>                  T_new(quadrature.size(), parameters.temperature);
    std::vector<double>                  local_v_old(n_dofs), local_a_old(n_dofs), local_a(n_dofs);
    Vector<double>                       cell_inertia(n_dofs);
    FullMatrix<double>                   cell_mass(n_dofs, n_dofs);
    const bool dynamic = parameters.dynamic;
    const bool body_force = gravity.norm() > 0;
    // ∂a_{n+1}/∂u_{n+1} of Newmark, scaled by (1 − α_m) of the generalized-α balance.
    const double mass_factor = dynamic ? (1 - alpha_m) / (newmark_beta * current_time_step *
                                                          current_time_step) : 0;
    std::vector<Tensor<2, dim>>          face_grad_u(face_quadrature.size());
    std::vector<Tensor<1, dim>>          face_u(face_quadrature.size());
    std::vector<unsigned int>            component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe.system_to_component_index(i).first;

    // The directions of δF this formulation needs and where each lives.
    const TangentDirections directions = dim == 3 ? TangentDirections::in_plane(3, false) :
                                                    TangentDirections::in_plane(2, axisymmetric);
    const ComponentIndex    where(directions);
    const unsigned int      n_dir = directions.n;
    // G_a = ∂F/∂u_a at a point: entries (direction index, value), at most dim + 1.
    struct Gradient
    {
      unsigned int n = 0;
      int          c[4];
      double       v[4];
    };
    std::vector<Gradient>                      G(n_dofs);
    std::vector<double>                        center_trace(n_dofs); // tr(F₀⁻¹ ∂F₀/∂u_a)
    std::array<SymmetricTensor<2, 3>, 9>       dsigma;
    std::array<std::array<double, 9>, 9>       A;  // ∂P_c/∂F_d at the point
    std::array<double, 9>                      T0; // ∂P_c/∂tr(F₀⁻¹δF₀) (F-bar)
    std::vector<std::array<double, 9>>         AG(n_dofs); // A : G_b, T0-free part

    // F-bar exponent: the dilatation is replaced by the cell centre's,
    // F̄ = (J₀/J)^α F on the active block (α = 1/2 in-plane for plane strain).
    const double alpha = (dim == 2 && !axisymmetric) ? 0.5 : 1. / 3.;

    const FEValuesExtractors::Vector displacements(0);
    IncrementalKinematics            kin;
    MaterialIncrement                increment;
    MaterialResponse                 response;
    const MaterialRequest request = with_matrix ? (request_stress | request_tangent) : request_stress;

    bool         inverted = false;
    unsigned int n_cells  = 0;
    step_internal_work    = 0;
    step_plastic_work     = 0;
    max_plastic_increment = 0;
    material_failure.clear();

    // F (3x3) from local values at point q of @p v (radius R for the hoop term).
    auto gradient_at = [&](const FEValues<dim> &v, const unsigned int q,
                           const std::vector<double> &values, const double R) {
      Tensor<2, dim> grad;
      double         u_r = 0;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const Tensor<1, dim> g = v.shape_grad_component(i, q, component[i]);
          for (unsigned int d = 0; d < dim; ++d)
            grad[component[i]][d] += values[i] * g[d];
          if (axisymmetric && component[i] == 0)
            u_r += values[i] * v.shape_value_component(i, q, 0);
        }
      return deformation_gradient(grad, u_r, R);
    };
    // F-bar on the active block: in plane strain F₃₃ stays 1.
    auto bar = [&](const Tensor<2, 3> &F, const double beta) {
      Tensor<2, 3> Fb = beta * F;
      if (dim == 2 && !axisymmetric)
        Fb[2][2] = 1;
      return Fb;
    };
    auto active_det = [&](const Tensor<2, 3> &F) {
      return (dim == 2 && !axisymmetric) ? F[0][0] * F[1][1] - F[0][1] * F[1][0] : determinant(F);
    };

    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        ++n_cells;
        fe_values.reinit(cell);
        cell->get_dof_indices(dof_indices);
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            local_u[i]     = solution(dof_indices[i]);
            local_u_old[i] = old_solution(dof_indices[i]);
          }
        if (with_matrix)
          cell_matrix = 0;
        cell_internal = 0;
        cell_external = 0;
        if (dynamic)
          {
            cell_mass = 0;
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                local_v_old[i] = velocity_old_ghosted(dof_indices[i]);
                local_a_old[i] = acceleration_old_ghosted(dof_indices[i]);
                local_a[i] = newmark_acceleration(local_u[i], local_u_old[i], local_v_old[i],
                                                  local_a_old[i]);
              }
          }
        const double rho = (dynamic || body_force) ? materials.at(cell->material_id())->density() : 0;
        if (temperature_field)
          temperature_field(cell, T_new);

        // Cell centre: J₀ and ∂J₀ for F-bar.
        double       J0 = 1, J0_old = 1;
        Tensor<2, 3> F0_inv;
        if (f_bar)
          {
            fe_center.reinit(cell);
            const double R0 = axisymmetric ? fe_center.quadrature_point(0)[0] : 1.;
            const Tensor<2, 3> F0     = gradient_at(fe_center, 0, local_u, R0);
            const Tensor<2, 3> F0_old = gradient_at(fe_center, 0, local_u_old, R0);
            J0     = active_det(F0);
            J0_old = active_det(F0_old);
            F0_inv = invert(F0);
            for (unsigned int b = 0; b < n_dofs; ++b)
              {
                const Tensor<1, dim> g = fe_center.shape_grad_component(b, 0, component[b]);
                double               tr = 0;
                for (unsigned int L = 0; L < dim; ++L)
                  tr += F0_inv[L][component[b]] * g[L];
                if (axisymmetric && component[b] == 0)
                  tr += F0_inv[2][2] * fe_center.shape_value_component(b, 0, 0) / R0;
                center_trace[b] = tr;
              }
          }

        for (unsigned int q = 0; q < n_q; ++q)
          {
            const double R = axisymmetric ? fe_values.quadrature_point(q)[0] : 1.;
            const Tensor<2, 3> F     = gradient_at(fe_values, q, local_u, R);
            const Tensor<2, 3> F_old = gradient_at(fe_values, q, local_u_old, R);
            const double       J     = determinant(F);
            if (!(J > 0) || !(determinant(0.5 * (F + F_old)) > 0) || !(J0 > 0))
              {
                inverted = true;
                break;
              }
            double       beta = 1;
            Tensor<2, 3> F_mat = F, F_mat_old = F_old; // what the material sees
            if (f_bar)
              {
                beta      = std::pow(J0 / active_det(F), alpha);
                F_mat     = bar(F, beta);
                F_mat_old = bar(F_old, std::pow(J0_old / active_det(F_old), alpha));
              }
            kin.reinit(F_mat, F_mat_old);
            increment.strain_increment      = kin.strain_increment;
            increment.rotation_increment    = kin.rotation_increment;
            const unsigned int point_index = cell->active_cell_index() * n_q + q;
            increment.temperature           = temperature_field ? T_new[q] : parameters.temperature;
            increment.temperature_increment =
              temperature_field ? T_new[q] - material_temperature_old[point_index] : 0.;
            increment.adiabatic = temperature_field && adiabatic_split;
            increment.time_step             = current_time_step;
            increment.volume_ratio          = J;
            MaterialPoint &point = *points[cell->active_cell_index() * n_q + q];
            try
              {
                point.update(increment, request, response);
              }
            catch (const MaterialPointError &e)
              {
                // Say where; the step is cut back (all ranks learn it below).
                std::ostringstream where_text;
                where_text << e.what() << " (material point " << q << " of the cell at "
                           << cell->center() << ", body id " << cell->material_id() << ")";
                material_failure = where_text.str();
                inverted         = true;
                break;
              }

            // P = J σ F⁻ᵀ with the true J and F: ∫ σ : ∇ₓδv dv on the current volume.
            const Tensor<2, 3> F_inv     = invert(F);
            const Tensor<2, 3> F_inv_T   = transpose(F_inv);
            const Tensor<2, 3> sigma_FiT = Tensor<2, 3>(response.stress) * F_inv_T;
            const Tensor<2, 3> P         = J * sigma_FiT;
            const double w = fe_values.JxW(q) * (axisymmetric ? 2 * numbers::PI * R : 1.);
            step_internal_work += 0.5 * ((response.stress + point.committed_stress()) *
                                         kin.strain_increment) *
                                  determinant(0.5 * (F + F_old)) * w;
            step_plastic_work += response.plastic_work_rate * current_time_step * J * w;
            heat_sources[point_index] =
              response.plastic_dissipation_rate + response.thermoelastic_heating_rate;
            thermoelastic_sources[point_index] = response.thermoelastic_heating_rate;
            if (temperature_field)
              material_temperature[point_index] =
                increment.temperature +
                (increment.adiabatic ? response.adiabatic_temperature_increment : 0.);
            max_plastic_increment =
              std::max(max_plastic_increment,
                       response.equivalent_plastic_strain - point.committed_equivalent_plastic_strain());

            // Mass (reference configuration: ρ₀ dV is conserved) and body force.
            if (dynamic || body_force)
              for (unsigned int a = 0; a < n_dofs; ++a)
                {
                  const double Na = fe_values.shape_value_component(a, q, component[a]);
                  if (body_force)
                    cell_external(a) += rho * gravity[component[a]] * Na * w;
                  if (dynamic)
                    for (unsigned int b = 0; b < n_dofs; ++b)
                      if (component[a] == component[b])
                        cell_mass(a, b) +=
                          rho * Na * fe_values.shape_value_component(b, q, component[b]) * w;
                }

            for (unsigned int a = 0; a < n_dofs; ++a)
              {
                Gradient            &g  = G[a];
                const unsigned int   ca = component[a];
                const Tensor<1, dim> gr = fe_values.shape_grad_component(a, q, ca);
                g.n                     = 0;
                for (unsigned int J_ = 0; J_ < dim; ++J_)
                  {
                    g.c[g.n]   = where.index[ca][J_];
                    g.v[g.n++] = gr[J_];
                  }
                if (axisymmetric && ca == 0)
                  {
                    g.c[g.n]   = where.index[2][2];
                    g.v[g.n++] = fe_values.shape_value_component(a, q, 0) / R;
                  }
                double f = 0;
                for (unsigned int e = 0; e < g.n; ++e)
                  {
                    const auto &kl = directions.kl[g.c[e]];
                    f += P[kl.first][kl.second] * g.v[e];
                  }
                cell_internal(a) += f * w;
              }

            if (!with_matrix)
              continue;

            cauchy_tangent(kin, point.committed_stress(), response, directions, dsigma.data());
            SymmetricTensor<2, 3> dsigma_Fbar; // δσ in the direction F̄ (F-bar)
            if (f_bar)
              for (unsigned int d = 0; d < n_dir; ++d)
                dsigma_Fbar += F_mat[directions.kl[d].first][directions.kl[d].second] * dsigma[d];

            for (unsigned int d = 0; d < n_dir; ++d)
              {
                const unsigned int    k = directions.kl[d].first, L = directions.kl[d].second;
                SymmetricTensor<2, 3> ds = dsigma[d];
                if (f_bar)
                  ds = beta * dsigma[d] - alpha * F_inv[L][k] * dsigma_Fbar;
                if (increment.adiabatic) // ΔT_ad ∝ J: δ ln J = tr(δF F⁻¹) of the true F
                  ds += F_inv[L][k] * response.volume_ratio_sensitivity;
                for (unsigned int c = 0; c < n_dir; ++c)
                  {
                    const unsigned int i = directions.kl[c].first, J_ = directions.kl[c].second;
                    double             ds_FiT = 0;
                    for (unsigned int m = 0; m < 3; ++m)
                      ds_FiT += ds[i][m] * F_inv_T[m][J_];
                    // δP = J [tr(δF F⁻¹) σF⁻ᵀ + δσ F⁻ᵀ − σF⁻ᵀ δFᵀ F⁻ᵀ]
                    A[c][d] = J * (F_inv[L][k] * sigma_FiT[i][J_] + ds_FiT -
                                   sigma_FiT[i][L] * F_inv_T[k][J_]);
                  }
              }
            if (f_bar)
              for (unsigned int c = 0; c < n_dir; ++c)
                {
                  const unsigned int i = directions.kl[c].first, J_ = directions.kl[c].second;
                  double             v = 0;
                  for (unsigned int m = 0; m < 3; ++m)
                    v += dsigma_Fbar[i][m] * F_inv_T[m][J_];
                  T0[c] = J * alpha * v;
                }

            for (unsigned int b = 0; b < n_dofs; ++b)
              {
                auto &ag = AG[b];
                for (unsigned int c = 0; c < n_dir; ++c)
                  {
                    double s = 0;
                    for (unsigned int e = 0; e < G[b].n; ++e)
                      s += A[c][G[b].c[e]] * G[b].v[e];
                    if (f_bar)
                      s += T0[c] * center_trace[b];
                    ag[c] = s * w;
                  }
              }
            for (unsigned int a = 0; a < n_dofs; ++a)
              for (unsigned int b = 0; b < n_dofs; ++b)
                {
                  double s = 0;
                  for (unsigned int e = 0; e < G[a].n; ++e)
                    s += G[a].v[e] * AG[b][G[a].c[e]];
                  cell_matrix(a, b) += s;
                }
          }
        if (inverted)
          break;

        // Follower pressure: f_ext = −∫ p n da N, n da = J F⁻ᵀ N dA (Nanson); in
        // the axisymmetric case per radian of the current radius r = R + u_r.
        if (boundary_conditions.has_pressure())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              for (const auto &load : boundary_conditions.pressures())
                if (face->boundary_id() == load.boundary)
                  {
                    fe_face_values.reinit(cell, face);
                    fe_face_values[displacements].get_function_gradients(solution, face_grad_u);
                    fe_face_values[displacements].get_function_values(solution, face_u);
                    load.value->set_time(time);
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      {
                        const double p = load.value->value(fe_face_values.quadrature_point(q));
                        const Tensor<2, dim> F     = unit_symmetric_tensor<dim>() + face_grad_u[q];
                        const double         J     = determinant(F);
                        const Tensor<2, dim> F_inv = invert(F);
                        const Tensor<1, dim> FiT_N = transpose(F_inv) * fe_face_values.normal_vector(q);
                        const double r   = axisymmetric ? 2 * numbers::PI *
                                                          (fe_face_values.quadrature_point(q)[0] + face_u[q][0]) :
                                                        1.;
                        const double JxW = fe_face_values.JxW(q);
                        for (unsigned int i = 0; i < n_dofs; ++i)
                          {
                            const unsigned int ci = component[i];
                            const double       Ni = fe_face_values.shape_value(i, q);
                            cell_external(i) -= p * r * J * FiT_N[ci] * Ni * JxW;
                            if (with_matrix)
                              for (unsigned int j = 0; j < n_dofs; ++j)
                                {
                                  const unsigned int   cj = component[j];
                                  const Tensor<1, dim> g =
                                    fe_face_values.shape_grad_component(j, q, cj);
                                  double tr = 0; // tr(F⁻¹ δF) with δF = e_cj ⊗ g
                                  for (unsigned int m = 0; m < dim; ++m)
                                    tr += F_inv[m][cj] * g[m];
                                  const Tensor<1, dim> FiT_g = transpose(F_inv) * g;
                                  double d_nda = r * J * (tr * FiT_N[ci] - FiT_g[ci] * FiT_N[cj]);
                                  if (axisymmetric && cj == 0) // δr = N_j
                                    d_nda += 2 * numbers::PI * fe_face_values.shape_value(j, q) * J *
                                             FiT_N[ci];
                                  // K = ∂f_int/∂u − ∂f_ext/∂u
                                  cell_matrix(i, j) += p * d_nda * Ni * JxW;
                                }
                          }
                      }
                  }

        for (unsigned int i = 0; i < n_dofs; ++i)
          cell_rhs(i) = cell_external(i) - cell_internal(i);
        if (dynamic)
          {
            // Generalized α: M ã + (1 − α_f) R(u_{n+1}) + α_f R(u_n) = 0 with
            // ã = (1 − α_m) a_{n+1} + α_m a_n; α_f R(u_n) is added globally below.
            if (parameters.lumped_mass)
              for (unsigned int a = 0; a < n_dofs; ++a)
                {
                  double m = 0;
                  for (unsigned int b = 0; b < n_dofs; ++b)
                    m += cell_mass(a, b);
                  for (unsigned int b = 0; b < n_dofs; ++b)
                    cell_mass(a, b) = (a == b) ? m : 0.;
                }
            cell_rhs *= (1 - alpha_f);
            if (with_matrix)
              cell_matrix *= (1 - alpha_f);
            for (unsigned int a = 0; a < n_dofs; ++a)
              {
                double ma = 0, ma_tilde = 0;
                for (unsigned int b = 0; b < n_dofs; ++b)
                  {
                    ma += cell_mass(a, b) * local_a[b];
                    ma_tilde += cell_mass(a, b) * ((1 - alpha_m) * local_a[b] + alpha_m * local_a_old[b]);
                    if (with_matrix)
                      cell_matrix(a, b) += mass_factor * cell_mass(a, b);
                  }
                cell_inertia(a) = ma;
                cell_rhs(a) -= ma_tilde;
              }
            inertia_force.add(dof_indices, cell_inertia);
          }
        if (with_matrix)
          active_constraints->distribute_local_to_global(cell_matrix, cell_rhs, dof_indices,
                                                         system_matrix, system_rhs);
        else
          active_constraints->distribute_local_to_global(cell_rhs, dof_indices, system_rhs);
        internal_force.add(dof_indices, cell_internal);
        external_force.add(dof_indices, cell_external);
      }

    if (contact)
      {
        // Contact elements (seed eq. 27–29): r is an internal force.
        const double factor   = dynamic ? 1 - alpha_f : 1.;
        const bool   complete = contact->assemble(
          solution, with_matrix,
          [&](const std::vector<types::global_dof_index> &dofs, const dealii::Vector<double> &r,
              const FullMatrix<double> *K) {
            dealii::Vector<double> rhs(r);
            rhs *= -factor;
            if (with_matrix && K)
              {
                FullMatrix<double> matrix(*K);
                matrix *= factor;
                active_constraints->distribute_local_to_global(matrix, rhs, dofs, system_matrix,
                                                               system_rhs);
              }
            else
              active_constraints->distribute_local_to_global(rhs, dofs, system_rhs);
            internal_force.add(dofs, r); // reactions include the contact forces
          });
        if (!complete)
          {
            // A slave met a master face outside the matrix's pattern: grow it, again.
            if (with_matrix)
              system_matrix.compress(VectorOperation::add);
            for (auto *v : {&system_rhs, &internal_force, &external_force, &inertia_force})
              v->compress(VectorOperation::add);
            setup_matrix();
            return assemble(with_matrix, time);
          }
      }

    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    inertia_force.compress(VectorOperation::add);
    if (dynamic)
      {
        // − α_f R(u_n) on the free dofs.
        TrilinosWrappers::MPI::Vector old_part(static_residual_old);
        active_constraints->set_zero(old_part);
        system_rhs.add(-alpha_f, old_part);
      }
    step_internal_work    = Utilities::MPI::sum(step_internal_work, mpi_communicator);
    step_plastic_work     = Utilities::MPI::sum(step_plastic_work, mpi_communicator);
    max_plastic_increment = Utilities::MPI::max(max_plastic_increment, mpi_communicator);

    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (with_matrix && seconds > 0)
      assembly_rate = n_cells / seconds;
    return Utilities::MPI::max(inverted ? 1 : 0, mpi_communicator) == 0;
  }

  template <int dim>
  void MechanicalProblem<dim>::lumped_mass(TrilinosWrappers::MPI::Vector &m) const
  {
    FEValues<dim> fe_values(mapping, fe, quadrature, update_values | update_JxW_values |
                                                       update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    Vector<double>                       local(fe.n_dofs_per_cell());
    m = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          const double rho = materials.at(cell->material_id())->density();
          local            = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double w = fe_values.JxW(q) *
                               (axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
              for (unsigned int a = 0; a < dofs.size(); ++a)
                local(a) += rho *
                            fe_values.shape_value_component(a, q, fe.system_to_component_index(a).first) * w;
            }
          m.add(dofs, local);
        }
    m.compress(VectorOperation::add);
  }

  template <int dim>
  double MechanicalProblem<dim>::kinetic_energy(const TrilinosWrappers::MPI::Vector &v) const
  {
    FEValues<dim> fe_values(mapping, fe, quadrature, update_values | update_JxW_values |
                                                       update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<double>                  local(n), lumped(n);
    double                               energy = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          for (unsigned int a = 0; a < n; ++a)
            local[a] = v(dofs[a]);
          const double rho = materials.at(cell->material_id())->density();
          std::fill(lumped.begin(), lumped.end(), 0.);
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double w = fe_values.JxW(q) *
                               (axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
              Tensor<1, dim> vq;
              for (unsigned int a = 0; a < n; ++a)
                {
                  const unsigned int c  = fe.system_to_component_index(a).first;
                  const double       Na = fe_values.shape_value_component(a, q, c);
                  vq[c] += local[a] * Na;
                  lumped[a] += rho * Na * w;
                }
              if (!parameters.lumped_mass)
                energy += 0.5 * rho * (vq * vq) * w;
            }
          if (parameters.lumped_mass)
            for (unsigned int a = 0; a < n; ++a)
              energy += 0.5 * lumped[a] * local[a] * local[a];
        }
    return Utilities::MPI::sum(energy, mpi_communicator);
  }

  template bool MechanicalProblem<2>::assemble(bool, double);
  template bool MechanicalProblem<3>::assemble(bool, double);
  template Tensor<2, 3> MechanicalProblem<2>::deformation_gradient(const Tensor<2, 2> &, double, double) const;
  template Tensor<2, 3> MechanicalProblem<3>::deformation_gradient(const Tensor<2, 3> &, double, double) const;
  template void MechanicalProblem<2>::lumped_mass(TrilinosWrappers::MPI::Vector &) const;
  template void MechanicalProblem<3>::lumped_mass(TrilinosWrappers::MPI::Vector &) const;
  template double MechanicalProblem<2>::kinetic_energy(const TrilinosWrappers::MPI::Vector &) const;
  template double MechanicalProblem<3>::kinetic_energy(const TrilinosWrappers::MPI::Vector &) const;
} // namespace anvil
