// The mechanical residual and its exact linearisation: the cell loop on the
// threads of this process (WorkStream), the kernels of assembly_kernels.h
// per cell, the contact elements after it (doc/mechanics.md, "Assembly").
#include <deal.II/base/mpi.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/grid/filtered_iterator.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>
#include <anvil/material/j2_plasticity.h>
#include <anvil/mechanics/assembly_kernels.h>
#include <anvil/mechanics/assembly_mapping.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>
#include <array>
#include <chrono>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  MechanicsAssembly::Context<dim> MechanicalProblem<dim>::assembly_context(const bool   with_matrix,
                                                                          const double time)
  {
    MechanicsAssembly::Context<dim> c;
    c.formulation           = formulation.get();
    c.with_matrix           = with_matrix;
    c.time                  = time;
    c.request               = with_matrix ? (request_stress | request_tangent) : request_stress;
    c.time_step             = current_time_step;
    c.reference_temperature = parameters.temperature;
    c.solution              = &solution;
    c.boundary_conditions   = &boundary_conditions;
    c.temperature_field     = &temperature_field;
    c.adiabatic_split       = adiabatic_split;
    c.dynamic               = parameters.dynamic;
    c.lumped_mass           = parameters.lumped_mass;
    c.alpha_m               = alpha_m;
    c.alpha_f               = alpha_f;
    c.newmark_beta          = newmark_beta;
    c.gravity               = gravity;
    c.body_force            = gravity.norm() > 0;
    c.materials             = &materials;
    c.points                = &points;
    c.heat_sources          = &heat_sources;
    c.thermoelastic_sources = &thermoelastic_sources;
    c.plastic_work_rates    = &plastic_work_rates;
    c.node_masses           = &node_masses;
    c.step_start            = &step_start;
    c.material_temperature  = &material_temperature;
    c.material_temperature_old = &material_temperature_old;
    return c;
  }

  template <int dim>
  bool MechanicalProblem<dim>::assemble(const bool with_matrix, const double time)
  {
    using namespace MechanicsAssembly;
    TimerOutput::Scope t(timer, with_matrix ? "Mechanics: assembly" : "Mechanics: residual");
    const auto start = std::chrono::steady_clock::now();

    if (with_matrix)
      system_matrix = 0;
    system_rhs     = 0;
    internal_force = 0;
    external_force = 0;
    contact_force  = 0;
    inertia_force  = 0;

    const Context<dim> context = assembly_context(with_matrix, time);
    const bool         dynamic = context.dynamic;
    // The loads' time, here: the threads only evaluate them.
    for (const auto &load : boundary_conditions.pressures())
      load.value->set_time(time);

    const MaterialPointUpdate<dim> material_update(context);
    const StressDivergence<dim>    stress_divergence(context);
    const BodyForce<dim>           body_force(context);
    const FollowerPressure<dim>    follower_pressure(context);
    const Inertia<dim>             inertia(context);
    // Shape functions, JxW and radii on the reference mesh: computed once per mesh.
    const ReferenceValues<dim> *reference = assembly_mapping->reference_values(
      fe, quadrature, formulation->component, axisymmetric);
    const bool centre = formulation->f_bar;

    // The ghosted vectors share one map (checked): their local values.
    const unsigned int    n_dofs_per_cell = fe.n_dofs_per_cell();
    const Epetra_BlockMap &vector_map     = solution.trilinos_vector().Map();
    // (Epetra's SameAs() is collective; this is the local part of it.)
    const auto same_map = [&](const TrilinosWrappers::MPI::Vector &v) {
      const Epetra_BlockMap &m = v.trilinos_vector().Map();
      return m.DataPtr() == vector_map.DataPtr() ||
             (m.NumMyElements() == vector_map.NumMyElements() &&
              std::equal(m.MyGlobalElements(), m.MyGlobalElements() + m.NumMyElements(),
                         vector_map.MyGlobalElements()));
    };
    AssertThrow(same_map(old_solution) &&
                  (!dynamic || (same_map(velocity_old_ghosted) && same_map(acceleration_old_ghosted))),
                ExcInternalError());
    const double *const u_values     = solution.trilinos_vector()[0];
    const double *const u_old_values = old_solution.trilinos_vector()[0];
    const double *const v_old_values = dynamic ? velocity_old_ghosted.trilinos_vector()[0] : nullptr;
    const double *const a_old_values =
      dynamic ? acceleration_old_ghosted.trilinos_vector()[0] : nullptr;
    assembly_mapping->reserve_vector_indices(n_dofs_per_cell);

    // One cell on any thread: its dof values, then the terms in a fixed
    // order (each term's sums run in the order of the serial loop).
    auto worker = [&](const CellIterator<dim> &cell, ScratchData<dim> &scratch, CopyData &copy) {
      copy.failed = false;
      copy.failure.clear();
      copy.max_plastic_increment = 0;
      scratch.reinit(cell, reference, formulation->component, centre, axisymmetric);
      cell->get_dof_indices(copy.dof_indices);
      copy.cell_index = cell->active_cell_index();
      // The dof values by local index in the ghosted vectors' map (one
      // look-up per dof and mesh, not one per value and assembly).
      int *const lids = assembly_mapping->vector_indices(copy.cell_index, n_dofs_per_cell);
      if (lids[0] == -2)
        for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
          {
            lids[i] = vector_map.LID(static_cast<TrilinosWrappers::types::int_type>(copy.dof_indices[i]));
            AssertThrow(lids[i] >= 0, ExcInternalError()); // a cell's dofs are relevant
          }
      for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
        {
          scratch.local_u[i]     = u_values[lids[i]];
          scratch.local_u_old[i] = u_old_values[lids[i]];
        }
      if (with_matrix)
        copy.matrix = 0;
      copy.internal = 0;
      copy.external = 0;
      if (dynamic)
        for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
          {
            scratch.local_v_old[i] = v_old_values[lids[i]];
            scratch.local_a_old[i] = a_old_values[lids[i]];
          }
      scratch.rho =
        (dynamic || context.body_force) ? materials.at(cell->material_id())->density() : 0;
      if (context.has_temperature_field())
        temperature_field(cell, scratch.T_new);

      if (!material_update.update(cell, scratch, copy))
        return;
      stress_divergence.assemble(scratch, copy);
      if (context.body_force)
        body_force.assemble(scratch, copy);
      if (dynamic)
        inertia.mass(cell, scratch);
      if (boundary_conditions.has_pressure())
        follower_pressure.assemble(cell, scratch, copy);
      for (unsigned int i = 0; i < copy.rhs.size(); ++i)
        copy.rhs(i) = copy.external(i) - copy.internal(i);
      if (dynamic)
        inertia.assemble(scratch, copy);
    };

    // Serially and in cell order (WorkStream's copier): the global sums are
    // the serial loop's, bit for bit, on any number of threads. After the
    // first cell that failed nothing more is added (the step is cut back).
    bool         failed  = false;
    unsigned int n_cells = 0;
    max_plastic_increment = 0;
    material_failure.clear();
    // A cell with no constrained dof and only owned rows and columns adds
    // its matrix straight into Epetra's CRS value array, at the positions of
    // its entries found once per cell and matrix pattern
    // (AssemblyMapping::matrix_positions), and its vectors by owned local
    // index (owned_vector_indices): no search of a row, no global-to-local
    // look-up. Each entry gets the one addition SumIntoMyValues and
    // Vector::add would make, in the same cell order: the same bits.
    // Otherwise local row and column numbers (local_indices) or, with
    // constraints, AffineConstraints.
    // deal.II 9.4 gives only const access to the Epetra matrix; ours is not const.
    const unsigned int n_dofs = fe.n_dofs_per_cell();
    auto &matrix = const_cast<Epetra_CrsMatrix &>(system_matrix.trilinos_matrix());
    int    *row_start = nullptr, *row_columns = nullptr;
    double *matrix_values = nullptr;
    if (with_matrix && matrix.ExtractCrsDataPointers(row_start, row_columns, matrix_values) != 0)
      matrix_values = nullptr; // storage not optimised: add by local indices
    const Epetra_BlockMap &owned_map = system_rhs.trilinos_vector().Map();
    const auto owned_values = [&](TrilinosWrappers::MPI::Vector &v) -> double * {
      const Epetra_BlockMap &m = v.trilinos_vector().Map();
      const bool same = m.DataPtr() == owned_map.DataPtr() ||
                        (m.NumMyElements() == owned_map.NumMyElements() &&
                         std::equal(m.MyGlobalElements(), m.MyGlobalElements() + m.NumMyElements(),
                                    owned_map.MyGlobalElements()));
      return same ? v.trilinos_vector()[0] : nullptr;
    };
    double *const rhs_values      = owned_values(system_rhs);
    double *const internal_values = owned_values(internal_force);
    double *const external_values = owned_values(external_force);
    double *const inertia_values  = owned_values(inertia_force);
    // The cell's dofs in the owned vectors (null if one is owned elsewhere).
    const auto owned_indices = [&](const CopyData &copy) -> const int * {
      int *const own = assembly_mapping->owned_vector_indices(copy.cell_index, n_dofs);
      if (own[0] == -2)
        for (unsigned int i = 0; i < n_dofs; ++i)
          own[i] = owned_map.LID(static_cast<TrilinosWrappers::types::int_type>(copy.dof_indices[i]));
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (own[i] < 0)
          return nullptr;
      return own;
    };
    const auto add_owned = [&](double *values, const int *own, const Vector<double> &local) {
      for (unsigned int i = 0; i < n_dofs; ++i)
        values[own[i]] += local(i);
    };
    // The positions of the cell's matrix entries (null: add otherwise).
    const auto matrix_positions = [&](const CopyData &copy) -> const int * {
      if (!matrix_values)
        return nullptr;
      int *const pos = assembly_mapping->matrix_positions(copy.cell_index, n_dofs);
      if (!pos)
        return nullptr;
      if (pos[0] == -2)
        {
          const auto find_all = [&] {
            // The cell's local column numbers once, in increasing order, then
            // each row walked once beside them (FillComplete sorts a row's
            // columns; an entry the walk passed is searched for). Found anew
            // for every cell at each of the tube's ~180 new patterns: a
            // search per entry cost 5400 instructions per cell, this ~1500.
            std::array<std::pair<int, unsigned int>, 64> column;
            AssertIndexRange(n_dofs, column.size() + 1);
            for (unsigned int j = 0; j < n_dofs; ++j)
              if ((column[j] = {matrix.LCID(static_cast<TrilinosWrappers::types::int_type>(
                                  copy.dof_indices[j])),
                                j})
                    .first < 0)
                return false;
            std::sort(column.begin(), column.begin() + n_dofs);
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                const int row =
                  matrix.LRID(static_cast<TrilinosWrappers::types::int_type>(copy.dof_indices[i]));
                if (row < 0)
                  return false;
                const int *const begin = row_columns + row_start[row];
                const int *const end   = row_columns + row_start[row + 1];
                const int       *at    = begin;
                for (unsigned int j = 0; j < n_dofs; ++j)
                  {
                    while (at != end && *at < column[j].first)
                      ++at;
                    if (at == end || *at != column[j].first)
                      at = std::find(begin, end, column[j].first);
                    if (at == end)
                      return false;
                    pos[i * n_dofs + column[j].second] = at - row_columns;
                  }
              }
            return true;
          };
          if (!find_all())
            pos[0] = -1;
        }
      return pos[0] >= 0 ? pos : nullptr;
    };
    auto add_by_local_indices = [&](const CopyData &copy) {
      int *const local_rows = assembly_mapping->local_indices(copy.cell_index, n_dofs);
      int *const local_cols = local_rows + n_dofs;
      if (local_rows[0] == -2)
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            const auto g = static_cast<TrilinosWrappers::types::int_type>(copy.dof_indices[i]);
            local_rows[i] = matrix.LRID(g);
            local_cols[i] = matrix.LCID(g);
          }
      for (unsigned int i = 0; i < n_dofs; ++i)
        if (local_rows[i] < 0 || local_cols[i] < 0)
          return false;
      for (unsigned int i = 0; i < n_dofs; ++i)
        {
          const int ierr =
            matrix.SumIntoMyValues(local_rows[i], n_dofs, &copy.matrix(i, 0), local_cols);
          AssertThrow(ierr == 0, ExcTrilinosError(ierr));
        }
      system_rhs.add(copy.dof_indices, copy.rhs);
      return true;
    };
    // The cell's K and −R where no constraint is involved; false: not added.
    // Whether a cell has a constrained dof, once per set of constrained dofs
    // (the predictor's and the iterations' alternate: both kept).
    signed char *const constrained_cells =
      assembly_mapping->constrained_cells(active_constraints->get_lines());
    auto add_unconstrained = [&](const CopyData &copy, const int *own) {
      signed char &constrained = constrained_cells[copy.cell_index];
      if (constrained < 0)
        {
          constrained = 0;
          for (unsigned int i = 0; i < n_dofs; ++i)
            if (active_constraints->is_constrained(copy.dof_indices[i]))
              constrained = 1;
        }
      if (constrained)
        return false;
      if (!with_matrix)
        {
          if (!own || !rhs_values)
            return false;
          add_owned(rhs_values, own, copy.rhs);
          return true;
        }
      if (const int *pos = own && rhs_values ? matrix_positions(copy) : nullptr)
        {
          const double *K = &copy.matrix(0, 0);
          for (unsigned int k = 0; k < n_dofs * n_dofs; ++k)
            matrix_values[pos[k]] += K[k];
          add_owned(rhs_values, own, copy.rhs);
          return true;
        }
      return add_by_local_indices(copy);
    };
    // A force vector: by owned local index, or deal.II's add.
    const auto add_force = [&](TrilinosWrappers::MPI::Vector &v, double *values, const int *own,
                               const CopyData &copy, const Vector<double> &local) {
      if (own && values)
        add_owned(values, own, local);
      else
        v.add(copy.dof_indices, local);
    };
    auto copier = [&](const CopyData &copy) {
      if (failed)
        return;
      ++n_cells;
      if (copy.failed)
        {
          failed           = true;
          material_failure = copy.failure;
          return;
        }
      max_plastic_increment = std::max(max_plastic_increment, copy.max_plastic_increment);
      const int *const own = owned_indices(copy);
      if (dynamic)
        add_force(inertia_force, inertia_values, own, copy, copy.inertia);
      if (!add_unconstrained(copy, own))
        {
          if (with_matrix)
            active_constraints->distribute_local_to_global(copy.matrix, copy.rhs, copy.dof_indices,
                                                           system_matrix, system_rhs);
          else
            active_constraints->distribute_local_to_global(copy.rhs, copy.dof_indices, system_rhs);
        }
      add_force(internal_force, internal_values, own, copy, copy.internal);
      add_force(external_force, external_values, own, copy, copy.external);
    };

    const UpdateFlags flags =
      update_gradients | update_JxW_values |
      (axisymmetric ? update_values | update_quadrature_points : update_default) |
      (dynamic || context.body_force ? update_values : update_default);
    using CellFilter = FilteredIterator<typename DoFHandler<dim>::active_cell_iterator>;
    WorkStream::run(CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.begin_active()),
                    CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.end()), worker,
                    copier,
                    ScratchData<dim>(*assembly_mapping, fe, quadrature, face_quadrature, flags),
                    CopyData(fe.n_dofs_per_cell(), quadrature.size()));

    if (contact && !assemble_contact(with_matrix))
      {
        // A slave met a master face outside the matrix's pattern: grow it, again.
        if (with_matrix)
          system_matrix.compress(VectorOperation::add);
        for (auto *v : {&system_rhs, &internal_force, &external_force, &inertia_force, &contact_force})
          v->compress(VectorOperation::add);
        setup_matrix();
        return assemble(with_matrix, time);
      }

    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    internal_force.compress(VectorOperation::add);
    external_force.compress(VectorOperation::add);
    inertia_force.compress(VectorOperation::add);
    contact_force.compress(VectorOperation::add);
    if (dynamic)
      {
        // − α_f R(u_n) on the free dofs.
        TrilinosWrappers::MPI::Vector old_part(static_residual_old);
        active_constraints->set_zero(old_part);
        system_rhs.add(-alpha_f, old_part);
      }
    max_plastic_increment = Utilities::MPI::max(max_plastic_increment, mpi_communicator);

    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (with_matrix && seconds > 0)
      assembly_rate = n_cells / seconds;
    return Utilities::MPI::max(failed ? 1 : 0, mpi_communicator) == 0;
  }

  template <int dim>
  void MechanicalProblem<dim>::compute_step_audit()
  {
    // The cells in the assembly's order, the points' terms summed as its
    // copier did: the sums of an audit computed at every evaluation.
    using namespace MechanicsAssembly;
    const Context<dim>             context = assembly_context(false, current_time);
    const MaterialPointUpdate<dim> material_update(context);
    const ReferenceValues<dim>    *reference = assembly_mapping->reference_values(
      fe, quadrature, formulation->component, axisymmetric);
    ScratchData<dim> scratch(*assembly_mapping, fe, quadrature, face_quadrature,
                             update_gradients | update_JxW_values |
                               (axisymmetric ? update_values | update_quadrature_points :
                                               update_default));
    const unsigned int n_dofs_per_cell = fe.n_dofs_per_cell();
    CopyData           copy(n_dofs_per_cell, quadrature.size());
    // The dof values by local index, as the assembly reads them (its look-ups, kept per mesh).
    const Epetra_BlockMap &vector_map   = solution.trilinos_vector().Map();
    const double *const    u_values     = solution.trilinos_vector()[0];
    const double *const    u_old_values = old_solution.trilinos_vector()[0];
    const Epetra_BlockMap &old_map      = old_solution.trilinos_vector().Map();
    AssertThrow(old_map.DataPtr() == vector_map.DataPtr() ||
                  (old_map.NumMyElements() == vector_map.NumMyElements() &&
                   std::equal(old_map.MyGlobalElements(),
                              old_map.MyGlobalElements() + old_map.NumMyElements(),
                              vector_map.MyGlobalElements())),
                ExcInternalError());
    assembly_mapping->reserve_vector_indices(n_dofs_per_cell);
    static_assert(n_audit_terms == 7 && audit_elastic_energy == 6,
                  "step_audit holds every AuditTerm but the state's elastic energy");
    step_audit.fill(0.);
    // The state's elastic energy ∫ W dv, W = p²/2K(T) + s:s/4G(T), at the points'
    // stresses and temperatures and J = det F of their u (doc/energy_audit.md):
    // the stress balance's state route, from the stresses alone, not from the
    // step's work sums (audit() evaluates it beside the step's terms).
    double elastic_energy = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          scratch.reinit(cell, reference, formulation->component, formulation->f_bar, axisymmetric);
          int *const lids = assembly_mapping->vector_indices(cell->active_cell_index(), n_dofs_per_cell);
          if (lids[0] == -2)
            {
              cell->get_dof_indices(copy.dof_indices);
              for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
                {
                  lids[i] = vector_map.LID(
                    static_cast<TrilinosWrappers::types::int_type>(copy.dof_indices[i]));
                  AssertThrow(lids[i] >= 0, ExcInternalError());
                }
            }
          for (unsigned int i = 0; i < n_dofs_per_cell; ++i)
            {
              scratch.local_u[i]     = u_values[lids[i]];
              scratch.local_u_old[i] = u_old_values[lids[i]];
            }
          material_update.audit(cell, scratch, copy);
          for (const auto &terms : copy.audit)
            {
              for (unsigned int k = 0; k < step_audit.size(); ++k)
                step_audit[k] += terms[k];
              elastic_energy += terms[audit_elastic_energy];
            }
        }
    std::vector<double> sums(step_audit.begin(), step_audit.end());
    sums.push_back(elastic_energy);
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    std::copy(sums.begin(), sums.begin() + step_audit.size(), step_audit.begin());
    energy_audit.elastic_energy = sums.back();
  }

#define INSTANTIATE(dim)                                                                         \
  template bool MechanicalProblem<dim>::assemble(bool, double);                                 \
  template MechanicsAssembly::Context<dim> MechanicalProblem<dim>::assembly_context(bool, double); \
  template void MechanicalProblem<dim>::compute_step_audit();
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
