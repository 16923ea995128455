// The mechanical residual and its exact linearisation: the cell loop on the
// threads of this process (WorkStream), the kernels of assembly_kernels.h
// per cell, the contact elements after it (doc/mechanics.md, "Assembly").
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/work_stream.h>
#include <deal.II/grid/filtered_iterator.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>
#include <anvil/material/j2_plasticity.h>
#include <anvil/mechanics/assembly_kernels.h>
#include <anvil/mechanics/assembly_mapping.h>
#include <anvil/mechanics/cell_scatter.h>
#include <anvil/mechanics/mechanical_problem.h>

#include "off_process_rows.h"

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    using namespace MechanicsAssembly;

    // The ghosted vectors' values of a cell's dofs, read by local index in
    // their one map (checked): one look-up per dof and mesh, not one per
    // value and assembly.
    template <int dim>
    struct GhostedValues
    {
      GhostedValues(const AssemblyMapping<dim> &mapping, const unsigned int n_dofs,
                    const TrilinosWrappers::MPI::Vector &u,
                    const TrilinosWrappers::MPI::Vector &u_old,
                    const TrilinosWrappers::MPI::Vector *v_old,
                    const TrilinosWrappers::MPI::Vector *a_old)
        : mapping(mapping)
        , n_dofs(n_dofs)
        , map(u.trilinos_vector().Map())
        , u(u.trilinos_vector()[0])
        , u_old(u_old.trilinos_vector()[0])
        , v_old(v_old ? v_old->trilinos_vector()[0] : nullptr)
        , a_old(a_old ? a_old->trilinos_vector()[0] : nullptr)
      {
        const auto same = [&](const TrilinosWrappers::MPI::Vector *v) {
          return v && same_local_map(v->trilinos_vector().Map(), map);
        };
        AssertThrow(same(&u_old) && (v_old == nullptr) == (a_old == nullptr) &&
                      (!v_old || (same(v_old) && same(a_old))),
                    ExcInternalError());
        mapping.reserve_vector_indices(n_dofs);
      }

      // On any thread: each fills and reads only its own cell's indices.
      // @p dofs gives the cell's dof indices, asked for only the first time.
      template <typename DofIndices>
      void gather(const unsigned int cell_index, const DofIndices &dofs,
                  ScratchData<dim> &scratch) const
      {
        int *const lids = mapping.vector_indices(cell_index, n_dofs);
        if (lids[0] == -2)
          {
            const std::vector<types::global_dof_index> &dof_indices = dofs();
            for (unsigned int i = 0; i < n_dofs; ++i)
              {
                lids[i] = map.LID(static_cast<TrilinosWrappers::types::int_type>(dof_indices[i]));
                AssertThrow(lids[i] >= 0, ExcInternalError()); // a cell's dofs are relevant
              }
          }
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            scratch.local_u[i]     = u[lids[i]];
            scratch.local_u_old[i] = u_old[lids[i]];
          }
        if (v_old)
          for (unsigned int i = 0; i < n_dofs; ++i)
            {
              scratch.local_v_old[i] = v_old[lids[i]];
              scratch.local_a_old[i] = a_old[lids[i]];
            }
      }

      const AssemblyMapping<dim> &mapping;
      const unsigned int          n_dofs;
      const Epetra_BlockMap      &map;
      const double *const         u, *const u_old, *const v_old, *const a_old;
    };

    // OffProcessRows where the assembly can do without deal.II's compress:
    // several processes, no contact (its elements add through deal.II),
    // contiguous ownership, the vectors on the right-hand side's layout;
    // decided alike on every process (the exchange is collective).
    template <int dim>
    std::unique_ptr<OffProcessRows<dim>>
    make_off_process_rows(const AssemblyMapping<dim> &mapping, const AffineConstraints<double> &constraints,
                          TrilinosWrappers::SparseMatrix *matrix,
                          const std::array<TrilinosWrappers::MPI::Vector *, 4> &v, const IndexSet &owned,
                          const unsigned int n_dofs, const bool dynamic, const bool contact,
                          const MPI_Comm comm, std::shared_ptr<void> &plan)
    {
      if (Utilities::MPI::n_mpi_processes(comm) == 1 || contact)
        return nullptr;
      const Epetra_BlockMap  &map = v[0]->trilinos_vector().Map();
      std::array<double *, 4> values;
      for (unsigned int k = 0; k < 4; ++k)
        values[k] = same_local_map(v[k]->trilinos_vector().Map(), map) ? v[k]->trilinos_vector()[0] : nullptr;
      const bool ok = owned.is_contiguous() && values[0] && values[1] && values[2] && (!dynamic || values[3]);
      if (Utilities::MPI::min(ok ? 1 : 0, comm) == 0)
        return nullptr;
      if (!plan)
        plan = std::make_shared<OffProcessPlan>();
      return std::make_unique<OffProcessRows<dim>>(
        mapping, constraints,
        matrix ? const_cast<Epetra_CrsMatrix *>(&matrix->trilinos_matrix()) : nullptr, values, map,
        n_dofs, dynamic, comm, *static_cast<OffProcessPlan *>(plan.get()));
    }
  } // namespace

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
    // (Null where no coupling reads them: keep_heat_sources().)
    c.heat_sources          = heat_sources.empty() ? nullptr : &heat_sources;
    c.thermoelastic_sources = thermoelastic_sources.empty() ? nullptr : &thermoelastic_sources;
    c.plastic_work_rates    = &plastic_work_rates;
    c.node_masses           = &node_masses;
    c.step_start            = &step_start;
    c.material_temperature  = &material_temperature;
    c.material_temperature_old = &material_temperature_old;
    return c;
  }

  template <int dim>
  bool MechanicalProblem<dim>::assemble(const bool with_matrix, const double time,
                                        const bool with_audit)
  {
    using namespace MechanicsAssembly;
    TimerOutput::Scope t(timer, with_matrix ? "Mechanics: assembly" : "Mechanics: residual");
    const auto start = std::chrono::steady_clock::now();
    // Any evaluation moves the points' last update: sums kept before are
    // then stale (audit_from_kept() compares the count).
    ++n_evaluations;
    if (with_audit)
      {
        kept_audit.evaluation = 0;
        kept_audit.sums.fill(0.);
      }

    // Several processes and no contact: the cells with rows owned elsewhere
    // (or constrained) add through OffProcessRows, the rest by CellScatter's
    // raw paths, so that nothing enters the matrix through deal.II and it
    // needs no compress() (nor the one deal.II's operator=(0) makes).
    const std::unique_ptr<OffProcessRows<dim>> off_process = make_off_process_rows(
      *assembly_mapping, *active_constraints, with_matrix ? &system_matrix : nullptr,
      {{&system_rhs, &internal_force, &external_force, &inertia_force}}, locally_owned_dofs,
      fe.n_dofs_per_cell(), parameters.dynamic, static_cast<bool>(contact), mpi_communicator,
      off_process_plan);
    if (with_matrix && off_process)
      const_cast<Epetra_CrsMatrix &>(system_matrix.trilinos_matrix()).PutScalar(0.);
    else if (with_matrix)
      system_matrix = 0;
    system_rhs     = 0;
    internal_force = 0;
    external_force = 0;
    contact_force  = 0;
    inertia_force  = 0;

    Context<dim> context = assembly_context(with_matrix, time);
    context.audit        = with_audit;
    const bool dynamic   = context.dynamic;
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

    const unsigned int       n_dofs_per_cell = fe.n_dofs_per_cell();
    const GhostedValues<dim> ghosted(*assembly_mapping, n_dofs_per_cell, solution, old_solution,
                                     dynamic ? &velocity_old_ghosted : nullptr,
                                     dynamic ? &acceleration_old_ghosted : nullptr);

    // One cell on any thread: its dof values, then the terms in a fixed
    // order (each term's sums run in the order of the serial loop).
    auto worker = [&](const CellIterator<dim> &cell, ScratchData<dim> &scratch, CopyData &copy) {
      copy.failed = false;
      copy.failure.clear();
      copy.max_plastic_increment = 0;
      scratch.reinit(cell, reference, formulation->component, centre, axisymmetric);
      cell->get_dof_indices(copy.dof_indices);
      copy.cell_index = cell->active_cell_index();
      ghosted.gather(
        copy.cell_index, [&]() -> const auto & { return copy.dof_indices; }, scratch);
      if (with_matrix)
        copy.matrix = 0;
      // Plain fills: deal.II's Vector::operator=(0) checks and dispatches
      // (~80 instructions for 8 entries, twice per cell).
      std::fill(copy.internal.begin(), copy.internal.end(), 0.);
      std::fill(copy.external.begin(), copy.external.end(), 0.);
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
    CellScatter<dim> scatter(*assembly_mapping, *active_constraints,
                             {with_matrix ? &system_matrix : nullptr, system_rhs, internal_force,
                              external_force, inertia_force},
                             n_dofs_per_cell, dynamic);
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
      // The audit's sums point by point in cell order: compute_step_audit()'s additions.
      if (with_audit)
        for (const auto &terms : copy.audit)
          for (unsigned int k = 0; k < n_audit_terms; ++k)
            kept_audit.sums[k] += terms[k];
      if (off_process && off_process->takes(copy))
        off_process->add(copy);
      else
        scatter.add(copy);
    };

    const UpdateFlags flags =
      update_gradients | update_JxW_values |
      (axisymmetric ? update_values | update_quadrature_points : update_default) |
      (dynamic || context.body_force ? update_values : update_default);
    ScratchData<dim> &scratch = kept_scratch_data(flags);
    if (MultithreadInfo::n_threads() == 1)
      {
        // WorkStream's sequential loop, on the kept work space (it would
        // build a sample and a copy of it: two FEValues triples per call).
        // Each cell's worker fills what it reads, as from one cell to the
        // next within a pass.
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              worker(cell, scratch, *kept_copy);
              copier(*kept_copy);
            }
      }
    else
      {
        using CellFilter = FilteredIterator<typename DoFHandler<dim>::active_cell_iterator>;
        WorkStream::run(CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.begin_active()),
                        CellFilter(IteratorFilters::LocallyOwnedCell(), dof_handler.end()),
                        worker, copier, scratch, *kept_copy);
      }

    if (contact && !assemble_contact(with_matrix))
      {
        // A slave met a master face outside the matrix's pattern: grow it, again.
        if (with_matrix)
          system_matrix.compress(VectorOperation::add);
        for (auto *v : {&system_rhs, &internal_force, &external_force, &inertia_force, &contact_force})
          v->compress(VectorOperation::add);
        setup_matrix();
        return assemble(with_matrix, time, with_audit);
      }

    if (off_process)
      off_process->exchange();
    else if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    // Nothing owned elsewhere is left in the vectors: their compress() only
    // resets deal.II's record of the last operation (a few collectives).
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
    const bool ok = Utilities::MPI::max(failed ? 1 : 0, mpi_communicator) == 0;
    if (with_audit && ok)
      {
        // What the sums belong to (audit_from_kept()): this evaluation, its
        // step and the dof values its cells read.
        const Epetra_MultiVector &u = solution.trilinos_vector();
        kept_audit.solution.assign(u[0], u[0] + u.MyLength());
        kept_audit.time_step  = current_time_step;
        kept_audit.evaluation = n_evaluations;
      }
    return ok;
  }

  template <int dim>
  MechanicsAssembly::ScratchData<dim> &
  MechanicalProblem<dim>::kept_scratch_data(const UpdateFlags flags)
  {
    // The update flags are the scene's (axisymmetry, dynamics, gravity):
    // one work space per problem in practice.
    if (!kept_scratch || kept_scratch->cell_flags != flags)
      kept_scratch = std::make_shared<MechanicsAssembly::ScratchData<dim>>(
        *assembly_mapping, fe, quadrature, face_quadrature, flags);
    if (!kept_copy)
      kept_copy = std::make_shared<MechanicsAssembly::CopyData>(fe.n_dofs_per_cell(),
                                                                quadrature.size());
    return *kept_scratch;
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
    // The assembly's kept work space where it computes at least what this
    // pass reads (it may add the values of dynamics or gravity: computed
    // beside, they change nothing here).
    const UpdateFlags audit_flags =
      update_gradients | update_JxW_values |
      (axisymmetric ? update_values | update_quadrature_points : update_default);
    std::unique_ptr<ScratchData<dim>> own_scratch;
    ScratchData<dim>                 *kept = kept_scratch.get();
    if (!kept || (kept->cell_flags & audit_flags) != audit_flags)
      kept = (own_scratch = std::make_unique<ScratchData<dim>>(*assembly_mapping, fe, quadrature,
                                                               face_quadrature, audit_flags))
               .get();
    ScratchData<dim>  &scratch         = *kept;
    const unsigned int n_dofs_per_cell = fe.n_dofs_per_cell();
    if (!kept_copy)
      kept_copy = std::make_shared<CopyData>(n_dofs_per_cell, quadrature.size());
    CopyData &copy = *kept_copy;
    // The dof values by local index, as the assembly reads them (its look-ups, kept per mesh).
    const GhostedValues<dim> ghosted(*assembly_mapping, n_dofs_per_cell, solution, old_solution,
                                     nullptr, nullptr);
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
          const auto dof_indices = [&]() -> const auto & {
            cell->get_dof_indices(copy.dof_indices);
            return copy.dof_indices;
          };
          ghosted.gather(cell->active_cell_index(), dof_indices, scratch);
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

  template <int dim>
  bool MechanicalProblem<dim>::audit_from_kept()
  {
    // The kept sums are the pass's when its inputs are those the evaluation
    // read: the points' last update (no assembly since), u (bit for bit),
    // the step (Δt of Ẇirr Δt); u_n and the committed states change only at
    // commit and revert, which forget the kept sums. ANVIL_AUDIT_STALE (test
    // only) takes the sums of the attempt's last audited evaluation whatever
    // came after it: tests/energy_audit_kept.py shows ANVIL_AUDIT_CHECK then fails.
    static_assert(std::tuple_size<decltype(kept_audit.sums)>::value == MechanicsAssembly::n_audit_terms,
                  "kept_audit holds every AuditTerm");
    static const bool stale = std::getenv("ANVIL_AUDIT_STALE") != nullptr;
    const Epetra_MultiVector &u = solution.trilinos_vector();
    const bool                here =
      kept_audit.evaluation != 0 &&
      (stale ||
       (kept_audit.evaluation == n_evaluations && kept_audit.time_step == current_time_step &&
        kept_audit.solution.size() == static_cast<std::size_t>(u.MyLength()) &&
        std::memcmp(kept_audit.solution.data(), u[0], u.MyLength() * sizeof(double)) == 0));
    if (Utilities::MPI::min(here ? 1 : 0, mpi_communicator) == 0)
      return false;
    // The same sum over the processes as compute_step_audit()'s.
    std::vector<double> sums(kept_audit.sums.begin(), kept_audit.sums.end());
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    std::copy(sums.begin(), sums.begin() + step_audit.size(), step_audit.begin());
    energy_audit.elastic_energy = sums[MechanicsAssembly::audit_elastic_energy];
    return true;
  }

#define INSTANTIATE(dim)                                                                         \
  template bool MechanicalProblem<dim>::assemble(bool, double, bool);                           \
  template bool MechanicalProblem<dim>::audit_from_kept();                                      \
  template MechanicsAssembly::Context<dim> MechanicalProblem<dim>::assembly_context(bool, double); \
  template MechanicsAssembly::ScratchData<dim> &MechanicalProblem<dim>::kept_scratch_data(     \
    UpdateFlags);                                                                                \
  template void MechanicalProblem<dim>::compute_step_audit();
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
