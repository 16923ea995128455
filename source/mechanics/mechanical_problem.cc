#include <deal.II/base/utilities.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <anvil/core/input_error.h>
#include <anvil/core/scene.h>
#include <anvil/material/kinematics.h>
#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_mapping.h>
#include <anvil/mechanics/element_formulation.h>
#include <anvil/material/kinematics.h>
#include <anvil/mechanics/mechanical_problem.h>
#include <anvil/mechanics/serial_matrix.h>
#include <anvil/mechanics/sparsity_rows.h>

#include "geometric_coarse_space.h"

#include <algorithm>
#include <cstdint>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  MechanicalProblem<dim>::MechanicalProblem(
    const parallel::DistributedTriangulationBase<dim>                        &triangulation,
    const Parameters                                                        &parameters,
    const BoundaryConditions<dim>                                           &boundary_conditions,
    const std::map<types::material_id, std::shared_ptr<const MaterialModel>> &materials,
    TimerOutput                                                             &timer)
    : mpi_communicator(triangulation.get_communicator())
    , triangulation(triangulation)
    , parameters(parameters)
    , boundary_conditions(boundary_conditions)
    , materials(materials)
    , timer(timer)
    , axisymmetric(parameters.axisymmetric)
    , f_bar(parameters.f_bar)
    , fe(FE_Q<dim>(parameters.polynomial_degree), dim)
    , mapping(1)
    , dof_handler(triangulation)
    , quadrature(parameters.polynomial_degree + 1)
    , face_quadrature(parameters.polynomial_degree + 1)
  {
    formulation =
      std::make_unique<const MechanicsAssembly::Formulation<dim>>(fe, axisymmetric, f_bar,
                                                                  parameters.objective_rate);
    assembly_mapping = std::make_unique<MechanicsAssembly::AssemblyMapping<dim>>();
  }

  template <int dim>
  MechanicalProblem<dim>::~MechanicalProblem() = default;

  template <int dim>
  Tensor<2, 3> MechanicalProblem<dim>::deformation_gradient(const Tensor<2, dim> &grad_u,
                                                            const double          radial_displacement,
                                                            const double          radius) const
  {
    return formulation->deformation_gradient(grad_u, radial_displacement, radius);
  }

  template <int dim>
  void MechanicalProblem<dim>::setup()
  {
    TimerOutput::Scope t(timer, "Mechanics: setup");
    // Test only: leave one term out of the energy audit (tests/energy_audit.py
    // shows that the audit then fails).
    if (const char *omit = std::getenv("ANVIL_AUDIT_OMIT"))
      {
        const std::vector<std::string> terms = {"stress_work", "material_work", "plastic_work",
                                                "thermal_work", "hypoelastic_volume_work",
                                                "heat_plastic_work"};
        const auto it = std::find(terms.begin(), terms.end(), std::string(omit));
        AssertThrow(it != terms.end(), ExcMessage("ANVIL_AUDIT_OMIT: unknown term"));
        audit_omission = 1 + (it - terms.begin());
      }
    dof_handler.distribute_dofs(fe);
    // Refused before any work if the mesh has no nested coarse mesh.
    if (parameters.preconditioner == "geometric" && parameters.linear_solver != "direct")
      check_geometric_coarse_space(dof_handler);
    cell_masses.clear();
    boundary_dofs.clear();
    boundary_dofs_listed = false;
    kept_predictor = KeptPredictor();
    {
      // The assembly's cells in the order of the loop (WorkStream's too).
      std::vector<typename Triangulation<dim>::cell_iterator> cells;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          cells.push_back(cell);
      assembly_mapping->reinit(cells, triangulation.n_active_cells());
    }
    locally_owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

    // The constraints hold lines for the relevant dofs and, with contact, for
    // every contact-surface dof too: a contact element may touch a master node
    // far away, whose constraint only its owner knows (ContactProblem gathers
    // which; add_remote_constraints() makes them lines here, so the element's
    // entries are condensed like any other).
    constraint_lines = locally_relevant_dofs;
    if (contact)
      {
        contact->setup(dof_handler, axisymmetric);
        constraint_lines.add_indices(contact->surface_dofs());
        constraint_lines.compress();
      }
    constraints.clear();
    constraints.reinit(constraint_lines);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    boundary_conditions.make_homogeneous_constraints(dof_handler, constraints);
    make_axis_constraints(constraints);
    if (contact)
      {
        contact->set_constrained([this](const types::global_dof_index i) {
          return locally_owned_dofs.is_element(i) && constraints.is_constrained(i);
        });
        add_remote_constraints(constraints);
      }
    constraints.close();
    cell_pattern.clear();

    if (contact)
      {
        TrilinosWrappers::MPI::Vector zero(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
        contact->begin_step(0, 0, zero);
      }
    setup_matrix();

    previous_time_step = 0;
    {
      // The diagonal of the mesh's bounding box: a length scale for the
      // round-off floor of the Newton test (GridTools::diameter compares all
      // pairs of vertices, O(n²)); and the largest cell's diameter, the
      // residual's (residual_floor(): it was recomputed at every call, 8 M
      // instructions on two_blocks).
      Point<dim> lo, hi;
      for (unsigned int d = 0; d < dim; ++d)
        lo[d] = std::numeric_limits<double>::max(), hi[d] = -std::numeric_limits<double>::max();
      double h = 0;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            h = std::max(h, cell->diameter());
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lo[d] = std::min(lo[d], cell->vertex(v)[d]);
                  hi[d] = std::max(hi[d], cell->vertex(v)[d]);
                }
          }
      largest_cell_diameter = Utilities::MPI::max(h, mpi_communicator);
      double diagonal = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double l = Utilities::MPI::max(hi[d], mpi_communicator) +
                           Utilities::MPI::max(-lo[d], mpi_communicator);
          diagonal += l * l;
        }
      mesh_diameter = std::sqrt(diagonal);
    }
    // One Epetra map per layout, shared by all vectors of that layout
    // (reinit from a vector copies its map, and with it the map's
    // communicator object): deal.II 9.4's operator= copies the local values
    // only between vectors whose maps share the communicator object, and
    // otherwise builds an Epetra_Import for every copy (~65 000 instructions
    // per copy of the tube's 2 900 dofs). Where no process has ghosts (one
    // process), the ghosted vectors take the owned layout itself, so that
    // Newton's u → ghosted u copies are plain copies too.
    system_rhs.reinit(locally_owned_dofs, mpi_communicator);
    for (auto *v : {&internal_force, &internal_force_old, &external_force, &external_force_old,
                    &reaction_force, &reaction_force_old, &owned_solution, &owned_old_solution,
                    &inertia_force, &contact_force, &previous_increment})
      v->reinit(system_rhs);
    // The state of dynamics (v, a, R_n) and the contact's last force only
    // where the scene has them: left empty otherwise (7 vectors, 56 B/DoF
    // of the 3D plastic block's peak; every use is behind the same test).
    for (auto *v : {&velocity_old, &acceleration_old, &static_residual_old})
      if (parameters.dynamic)
        v->reinit(system_rhs);
      else
        v->clear();
    if (contact)
      contact_force_old.reinit(system_rhs);
    else
      contact_force_old.clear();
    const bool ghosts =
      Utilities::MPI::max(locally_relevant_dofs == locally_owned_dofs ? 0 : 1, mpi_communicator) == 1;
    if (ghosts)
      solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
    else
      solution.reinit(system_rhs);
    old_solution.reinit(solution);
    for (auto *v : {&velocity_ghosted, &velocity_old_ghosted, &acceleration_old_ghosted})
      if (parameters.dynamic)
        v->reinit(solution);
      else
        v->clear();

    gravity = Tensor<1, dim>();
    if (!parameters.gravity.empty())
      {
        const auto parts = split_outside_parentheses(parameters.gravity, ',');
        for (unsigned int d = 0; d < dim; ++d)
          gravity[d] = std::stod(parts[d]);
      }

    setup_quadrature_point_data();
    if (parameters.dynamic)
      setup_dynamics();
  }

  template <int dim>
  void MechanicalProblem<dim>::add_remote_constraints(AffineConstraints<double> &c) const
  {
    // Contact surface dofs constrained by their (far away) owner: homogeneous
    // here (the owner applies any prescribed value).
    if (contact)
      for (const auto i : contact->constrained_dofs())
        if (!locally_relevant_dofs.is_element(i) && !c.is_constrained(i))
          c.add_line(i);
  }

  template <int dim>
  void MechanicalProblem<dim>::setup_matrix()
  {
    direct_solver.clear(); // a new pattern: analyse it again
    assembly_mapping->forget_local_indices(); // and new local row and column numbers
    off_process_plan.reset();                 // and where the values sent land
    amg.clear();           // it references the matrix about to be re-created
    // Contact couples dofs of different cells (a slave node with the nodes of
    // the master face below it), possibly owned by other processes: their
    // rows enter the pattern here and go to their owners.
    std::vector<std::vector<types::global_dof_index>> groups;
    if (contact)
      groups = contact->couplings();
    // The cells' couplings change only with the mesh and the constraints;
    // each new contact pattern (the tube's ~180 on its crush) copies them
    // instead of looping over the cells again (~6.6 M instructions there,
    // most of it condensing each cell's dofs through AffineConstraints).
    // Built without a DynamicSparsityPattern (sparsity_rows.h): the owned
    // rows, then the others each led by its dof.
    const auto fill_cell_pattern = [&]() {
      if (cell_pattern.empty())
        make_cell_rows(dof_handler, constraints, locally_owned_dofs, cell_pattern);
    };
    // deal.II's route: a DynamicSparsityPattern, distributed to the rows'
    // owners, then the Epetra graph from it by global indices (owned dofs
    // not contiguous, and ANVIL_PATTERN_CHECK's reference).
    const auto by_dynamic_pattern = [&](TrilinosWrappers::SparseMatrix &matrix) {
      IndexSet rows = locally_relevant_dofs;
      std::vector<types::global_dof_index> extra;
      for (const auto &g : groups)
        extra.insert(extra.end(), g.begin(), g.end());
      std::sort(extra.begin(), extra.end());
      extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
      rows.add_indices(extra.begin(), extra.end());
      rows.compress();
      DynamicSparsityPattern dsp(rows);
      DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
      for (const auto &g : groups)
        constraints.add_entries_local_to_global(g, dsp, false);
      SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator, rows);
      matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
    };
    // Without contact no other pattern follows until setup() clears the
    // cells' rows: they go (~0.38 KB/DoF in 3D held for the run, doc/memory.md).
    const auto release_cell_pattern = [&]() {
      if (!contact)
        std::vector<std::vector<types::global_dof_index>>().swap(cell_pattern);
    };
    // Test only (ANVIL_PATTERN_CHECK): the same graph as deal.II's route?
    const auto check_pattern = [&]() {
      static const bool check = std::getenv("ANVIL_PATTERN_CHECK") != nullptr;
      if (!check)
        return;
      TrilinosWrappers::SparseMatrix reference;
      by_dynamic_pattern(reference);
      const std::string difference = compare_graphs(system_matrix, reference);
      const bool        equal = Utilities::MPI::min(difference.empty() ? 1 : 0, mpi_communicator) == 1;
      AssertThrow(equal, ExcMessage("ANVIL_PATTERN_CHECK: " +
                                    (difference.empty() ? "another process differs" : difference)));
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        std::printf("ANVIL_PATTERN_CHECK: %u rows, %u entries, equal to deal.II's\n",
                    static_cast<unsigned int>(system_matrix.m()),
                    static_cast<unsigned int>(system_matrix.n_nonzero_elements()));
    };
    if (!locally_owned_dofs.is_contiguous())
      {
        by_dynamic_pattern(system_matrix);
        release_cell_pattern();
        return;
      }
    fill_cell_pattern();
    // Several processes: each process's own rows, those owned elsewhere sent
    // to their owners (the DynamicSparsityPattern route cost 589 M
    // instructions per rank on the 48 k-DoF-per-body strip at np 2).
    // One process: the graph straight from the kept cell rows and the
    // contact couplings (serial_matrix.cc): the full tube crush's 177
    // patterns cost 2.9 G instructions by deal.II's route, 2.0 G of it in
    // the DynamicSparsityPattern, the global-index insertion and the sort.
    // Without contact the rows go as they enter the graph (~0.8 KB/DoF in
    // 3D, reserved for a vertex's eight cells: they were held beside the
    // graph and the values, doc/memory.md session 23).
    if (Utilities::MPI::n_mpi_processes(mpi_communicator) > 1)
      make_distributed_matrix(cell_pattern, groups, constraints, locally_owned_dofs, mpi_communicator,
                              system_matrix, !contact);
    else
      make_serial_matrix(cell_pattern, groups, constraints,
                         locally_owned_dofs.make_trilinos_map(mpi_communicator, false), system_matrix,
                         !contact);
    check_pattern();
    release_cell_pattern();
  }

  template <int dim>
  void MechanicalProblem<dim>::make_axis_constraints(AffineConstraints<double> &c) const
  {
    // Axisymmetric: nodes on the axis (x = 0) do not move radially.
    if (!axisymmetric)
      return;
    // Called for every step's predictor constraints: the radial dof at each
    // vertex found once per call, a cell's dofs and size only near the axis.
    std::vector<unsigned int> radial_dof(GeometryInfo<dim>::vertices_per_cell, fe.n_dofs_per_cell());
    if (fe.has_support_points())
      for (const unsigned int v : GeometryInfo<dim>::vertex_indices())
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          if (fe.system_to_component_index(i).first == 0 &&
              fe.get_unit_support_points()[i].distance(GeometryInfo<dim>::unit_cell_vertex(v)) < 1e-12)
            {
              radial_dof[v] = i;
              break;
            }
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        {
          double diameter = -1;
          bool   have_dofs = false;
          for (const unsigned int v : cell->vertex_indices())
            {
              const double x = std::abs(cell->vertex(v)[0]);
              if (x != 0 && diameter < 0)
                diameter = cell->diameter();
              if (radial_dof[v] == fe.n_dofs_per_cell() || !(x == 0 || x < 1e-12 * diameter))
                continue;
              if (!have_dofs)
                cell->get_dof_indices(dofs), have_dofs = true;
              const auto dof = dofs[radial_dof[v]];
              if (!c.is_constrained(dof) && locally_relevant_dofs.is_element(dof))
                c.add_line(dof);
            }
        }
  }

  template <int dim>
  const std::vector<std::pair<types::global_dof_index, unsigned int>> &
  MechanicalProblem<dim>::owned_boundary_dofs(const types::boundary_id boundary) const
  {
    const auto known = boundary_dofs.find(boundary);
    if (known != boundary_dofs.end())
      return known->second;
    // The lists are built once per numbering for every id this process sees,
    // so an id absent here gets its empty list instead of a second build
    // appending to the others.
    if (boundary_dofs_listed)
      return boundary_dofs[boundary];
    boundary_dofs_listed = true;
    // Every boundary's list from one pass over the faces and one over the
    // cells (a pass per boundary cost ~15-30 M instructions per boundary on
    // the 48 k-DoF strip, twelve boundaries: s18-np2). Each list keeps the
    // order of a dof's first appearance in the cell loop, so the reactions'
    // sums are the per-boundary code's bit for bit.
    std::vector<types::boundary_id> ids;
    std::vector<std::uint64_t>      on(locally_owned_dofs.n_elements(), 0); // bit per id
    std::vector<types::global_dof_index> face_dofs(fe.n_dofs_per_face());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial() && cell->at_boundary())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            {
              const auto id = cell->face(f)->boundary_id();
              auto       it = std::find(ids.begin(), ids.end(), id);
              if (it == ids.end())
                {
                  AssertThrow(ids.size() < 64, ExcMessage("more than 64 boundary ids on one process"));
                  it = ids.insert(ids.end(), id);
                }
              const std::uint64_t bit = std::uint64_t(1) << (it - ids.begin());
              cell->face(f)->get_dof_indices(face_dofs, cell->active_fe_index());
              for (const auto g : face_dofs)
                if (locally_owned_dofs.is_element(g))
                  on[locally_owned_dofs.index_within_set(g)] |= bit;
            }
    std::vector<std::vector<std::pair<types::global_dof_index, unsigned int>> *> lists;
    for (const auto id : ids)
      lists.push_back(&boundary_dofs[id]);
    // Component of each boundary dof from the dof's support on a cell.
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    std::vector<std::uint64_t>           listed(on.size(), 0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned() || cell->is_ghost())
        {
          cell->get_dof_indices(cell_dofs);
          for (unsigned int i = 0; i < cell_dofs.size(); ++i)
            {
              const auto g = cell_dofs[i];
              if (!locally_owned_dofs.is_element(g))
                continue;
              const auto k = locally_owned_dofs.index_within_set(g);
              for (std::uint64_t left = on[k] & ~listed[k]; left != 0; left &= left - 1)
                lists[__builtin_ctzll(left)]->emplace_back(g, fe.system_to_component_index(i).first);
              listed[k] = on[k];
            }
        }
    return boundary_dofs[boundary]; // empty for an id absent on this process
  }

  template <int dim>
  Tensor<1, dim> MechanicalProblem<dim>::reaction(const types::boundary_id boundary) const
  {
    Tensor<1, dim> force;
    for (const auto &[g, component] : owned_boundary_dofs(boundary))
      force[component] += internal_force(g) + inertia_force(g) - external_force(g);
    return Utilities::MPI::sum(force, mpi_communicator);
  }

  template <int dim>
  typename MechanicalProblem<dim>::CellFields MechanicalProblem<dim>::cell_fields() const
  {
    CellFields f;
    const char *axes = "xyz";
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        f.names.push_back(std::string("stress_") + axes[i] + axes[j]);
    f.names.insert(f.names.end(), {"von_mises", "pressure", "J", "equivalent_plastic_strain", "body"});
    f.values.assign(f.names.size(), Vector<double>(triangulation.n_active_cells()));
    f.max_values = f.min_values = f.values;

    FEValues<dim> fe_values(mapping, fe, quadrature,
                            update_gradients | update_values | update_quadrature_points);
    const unsigned int n_q = quadrature.size();
    std::vector<Tensor<2, dim>> grad_u(n_q);
    std::vector<Tensor<1, dim>> u_values(n_q);
    const FEValuesExtractors::Vector displacements(0);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements].get_function_gradients(solution, grad_u);
          fe_values[displacements].get_function_values(solution, u_values);
          SymmetricTensor<2, 3> s;
          double J = 0, eqps = 0;
          const unsigned int c = cell->active_cell_index();
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const auto &p = *points(cell, q);
              s += p.stress() / n_q;
              eqps += p.equivalent_plastic_strain() / n_q;
              const double R  = axisymmetric ? fe_values.quadrature_point(q)[0] : 1.;
              const double ur = axisymmetric ? u_values[q][0] : 0.;
              const double Jq = determinant(deformation_gradient(grad_u[q], ur, R));
              J += Jq / n_q;
              // The point's own values, in the order of the names (body aside).
              const auto   dev_q = deviator(p.stress());
              double       at_q[10];
              unsigned int k = 0;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = i; j < 3; ++j)
                  at_q[k++] = p.stress()[i][j];
              at_q[k++] = std::sqrt(1.5 * (dev_q * dev_q));
              at_q[k++] = -trace(p.stress()) / 3.;
              at_q[k++] = Jq;
              at_q[k++] = p.equivalent_plastic_strain();
              for (unsigned int i = 0; i < k; ++i)
                {
                  f.max_values[i][c] = q == 0 ? at_q[i] : std::max(f.max_values[i][c], at_q[i]);
                  f.min_values[i][c] = q == 0 ? at_q[i] : std::min(f.min_values[i][c], at_q[i]);
                }
            }
          unsigned int       k = 0;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              f.values[k++][c] = s[i][j];
          const auto dev   = deviator(s);
          f.values[k++][c] = std::sqrt(1.5 * (dev * dev));
          f.values[k++][c] = -trace(s) / 3.;
          f.values[k++][c] = J;
          f.values[k++][c] = eqps;
          f.values[k][c] = f.max_values[k][c] = f.min_values[k][c] = cell->material_id();
        }
    return f;
  }

  template <int dim>
  bool MechanicalProblem<dim>::probe(const Point<dim>      &point,
                                     Tensor<1, dim>        &u,
                                     SymmetricTensor<2, 3> &stress,
                                     double                &plastic_strain) const
  {
    u              = Tensor<1, dim>();
    stress         = SymmetricTensor<2, 3>();
    plastic_strain = 0;
    double found = 0;
    try
      {
        const auto cell_and_point =
          GridTools::find_active_cell_around_point(mapping, dof_handler, point);
        const auto &cell = cell_and_point.first;
        // On a process that does not hold the point the search returns an
        // invalid iterator (or an artificial cell).
        if (cell.state() == IteratorState::valid && cell->is_locally_owned())
          {
            found = 1;
            const Quadrature<dim> q(GeometryInfo<dim>::project_to_unit_cell(cell_and_point.second));
            FEValues<dim> fe_values(mapping, fe, q, update_values);
            fe_values.reinit(cell);
            std::vector<Tensor<1, dim>> values(1);
            fe_values[FEValuesExtractors::Vector(0)].get_function_values(solution, values);
            u = values[0];
            const unsigned int n_q = quadrature.size();
            for (unsigned int k = 0; k < n_q; ++k)
              {
                stress += points(cell, k)->stress() / n_q;
                plastic_strain += points(cell, k)->equivalent_plastic_strain() / n_q;
              }
          }
      }
    catch (...)
      {
        // not in this rank's part of the mesh
      }
    const double n = Utilities::MPI::sum(found, mpi_communicator);
    u              = Utilities::MPI::sum(u, mpi_communicator);
    stress         = Utilities::MPI::sum(stress, mpi_communicator);
    plastic_strain = Utilities::MPI::sum(plastic_strain, mpi_communicator);
    if (n == 0)
      return false;
    u /= n;
    stress /= n;
    plastic_strain /= n;
    return true;
  }

  template <int dim>
  std::size_t MechanicalProblem<dim>::memory_consumption() const
  {
    return dof_handler.memory_consumption() + system_matrix.memory_consumption() +
           8 * solution.memory_consumption() + constraints.memory_consumption() +
           points.raw().size() *
             (sizeof(MaterialPoint *) + 2 * sizeof(SymmetricTensor<2, 3>) + 16);
  }

  ANVIL_INSTANTIATE_CLASS(MechanicalProblem)
} // namespace anvil
