#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/base/geometry_info.h>

#include <anvil/postprocess/field_output.h>
#include <anvil/postprocess/vtu_writer.h>

#include <algorithm>
#include <functional>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// The fields that get a nodal (recovered) twin beside their cell values.
    bool recovered(const std::string &name)
    {
      return name.rfind("stress_", 0) == 0 || name == "von_mises" || name == "pressure" ||
             name == "equivalent_plastic_strain";
    }
  } // namespace

  /**
   * solution.pvd and fields/solution_*.pvtu: displacement (and velocity in
   * dynamics), temperature, the cell fields of the mechanics (stress,
   * von Mises, pressure, J, equivalent plastic strain), body and rank — what
   * a user opens in ParaView.
   */
  template <int dim>
  class Fields : public ScheduledFieldOutput<dim>
  {
  public:
    Fields()
      : ScheduledFieldOutput<dim>("fields.pvd")
    {}
    static void declare_parameters(ParameterHandler &prm) { FieldSchedule::declare_parameters(prm); }

  private:
    using NodalVector = LinearAlgebra::distributed::Vector<double>;

    void write(const SimulationState<dim> &s) override
    {
      write_fields(s);
      // The mesh's arrays (points, cells, vertex dofs, the nodal numbering)
      // are kept for the next write when writes come every Field interval
      // steps (made again at each write they cost two_blocks 0.5 % of its
      // instructions), not when the next is the last (Field interval = 0):
      // held through the run they were ~0.2 KB/DoF of the 3D plastic
      // block's peak (doc/memory.md, session 21). Made again, they are the same.
      if (!this->schedule.periodic())
        release_mesh_arrays();
    }

    void release_mesh_arrays()
    {
      raw_mesh  = nullptr;
      raw_cells = 0;
      piece     = VtuPiece();
      std::vector<unsigned int>().swap(cell_index);
      std::vector<types::global_dof_index>().swap(vertex_dofs);
      std::vector<types::global_dof_index>().swap(heat_dofs);
      std::vector<unsigned int>().swap(nodal_vertex);
      vertex_lids = LocalIndices();
      heat_lids   = LocalIndices();
      nodal_mesh  = nullptr;
      nodal_cells = 0;
      std::vector<NodalVector>().swap(nodal_values);
      std::vector<unsigned int>().swap(nodal_cell_dofs);
      std::vector<double>().swap(nodal_cell_volume);
      std::vector<unsigned int>().swap(nodal_cell_index);
      patch_volume.reinit(0);
      nodal_partitioner.reset();
      nodal_dofs.clear();
    }

    void write_fields(const SimulationState<dim> &s)
    {
      const auto  *mechanical = s.physics.mechanics();
      const auto  *thermal    = s.physics.heat();
      if (mechanical && this->schedule.raw_vtu())
        return write_raw(s);
      DataOut<dim> data_out;
      Vector<double> prescribed_temperature;
      if (mechanical)
        {
          data_out.attach_dof_handler(mechanical->get_dof_handler());
          std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
            dim, DataComponentInterpretation::component_is_part_of_vector);
          data_out.add_data_vector(mechanical->displacement(),
                                   std::vector<std::string>(dim, "displacement"),
                                   DataOut<dim>::type_dof_data, interpretation);
          if (mechanical->is_dynamic())
            data_out.add_data_vector(mechanical->velocity(),
                                     std::vector<std::string>(dim, "velocity"),
                                     DataOut<dim>::type_dof_data, interpretation);
          if (thermal)
            data_out.add_data_vector(thermal->get_dof_handler(), thermal->temperature(),
                                     "temperature");
          else if (s.physics.has_temperature())
            {
              prescribed_temperature = s.physics.cell_temperature();
              data_out.add_data_vector(prescribed_temperature, "temperature",
                                       DataOut<dim>::type_cell_data);
            }
          cell_fields = mechanical->cell_fields();
          for (unsigned int i = 0; i < cell_fields.names.size(); ++i)
            data_out.add_data_vector(cell_fields.values[i], cell_fields.names[i],
                                     DataOut<dim>::type_cell_data);
          recover(s, cell_fields);
          for (unsigned int i = 0; i < nodal_names.size(); ++i)
            data_out.add_data_vector(nodal_dofs, nodal_values[i], nodal_names[i]);
        }
      else
        {
          data_out.attach_dof_handler(thermal->get_dof_handler());
          data_out.add_data_vector(thermal->temperature(), "temperature");
        }
      Vector<float> rank(s.triangulation.n_active_cells());
      rank = Utilities::MPI::this_mpi_process(s.communicator);
      data_out.add_data_vector(rank, "rank", DataOut<dim>::type_cell_data);
      data_out.build_patches(mechanical ? mechanical->get_mapping() : thermal->get_mapping());
      // best_compression costs several seconds per write at 10⁵ cells.
      DataOutBase::VtkFlags flags;
      flags.compression_level = DataOutBase::VtkFlags::best_speed;
      data_out.set_flags(flags);
      const std::string name = data_out.write_vtu_with_pvtu_record(
        s.output_directory + "/fields/", "solution", s.step, s.communicator, 5);
      this->schedule.record(s.time, "fields/" + name, s.output_directory + "/solution.pvd", s.is_root());
    }

    typename MechanicalProblem<dim>::CellFields cell_fields; // alive while data_out writes

    // Output/VTU encoding = raw: the arrays DataOut would write, each cell a
    // patch of its own vertices (n_subdivisions 1: a vertex's value is its
    // vertex dof's, a cell value at each of its vertices), in DataOut's order
    // (dof data, then cell data) and types (Float32), without building
    // patches: the points, cells and vertex dofs depend on the mesh only and
    // are kept while it is the same.
    const Triangulation<dim>            *raw_mesh  = nullptr;
    unsigned int                         raw_cells = 0;
    VtuPiece                             piece;
    std::vector<unsigned int>            cell_index;   // per piece cell, its active cell index
    std::vector<types::global_dof_index> vertex_dofs;  // per piece point, the dim displacement dofs
    std::vector<types::global_dof_index> heat_dofs;    // per piece point (heat field)
    std::vector<unsigned int>            nodal_vertex; // per piece point, its nodal vector's local index

    void prepare_raw(const SimulationState<dim> &s)
    {
      const auto *mechanical = s.physics.mechanics();
      const auto *thermal    = s.physics.heat();
      if (raw_mesh == &s.triangulation && raw_cells == s.triangulation.n_active_cells() &&
          heat_dofs.empty() == !thermal)
        return;
      constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;
      // deal.II numbers a cell's vertices lexicographically; VTK goes around.
      const unsigned int vtk_order[8] = {0, 1, 3, 2, 4, 5, 7, 6};
      piece = VtuPiece();
      cell_index.clear();
      vertex_dofs.clear();
      heat_dofs.clear();
      nodal_vertex.clear();
      for (const auto &cell : mechanical->get_dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto first = static_cast<std::int32_t>(piece.n_points());
            for (unsigned int v = 0; v < n_vertices; ++v)
              {
                for (unsigned int d = 0; d < 3; ++d)
                  piece.points.push_back(d < dim ? static_cast<float>(cell->vertex(v)[d]) : 0.f);
                for (unsigned int c = 0; c < dim; ++c)
                  vertex_dofs.push_back(cell->vertex_dof_index(v, c));
                nodal_vertex.push_back(nodal_partitioner->global_to_local(
                  typename DoFHandler<dim>::active_cell_iterator(&s.triangulation, cell->level(),
                                                                 cell->index(), &nodal_dofs)
                    ->vertex_dof_index(v, 0)));
                if (thermal)
                  heat_dofs.push_back(typename DoFHandler<dim>::active_cell_iterator(
                                        &s.triangulation, cell->level(), cell->index(),
                                        &thermal->get_dof_handler())
                                        ->vertex_dof_index(v, 0));
                piece.connectivity.push_back(first + static_cast<std::int32_t>(vtk_order[v]));
              }
            piece.offsets.push_back(static_cast<std::int32_t>(piece.connectivity.size()));
            piece.types.push_back(dim == 2 ? 9 : 12); // VTK_QUAD, VTK_HEXAHEDRON
            cell_index.push_back(cell->active_cell_index());
          }
      raw_mesh  = &s.triangulation;
      raw_cells = s.triangulation.n_active_cells();
    }

    /// Local indices of a dof list in one Epetra map: kept while the map's
    /// data is the same (one map per layout: every write but the first reads
    /// them instead of ~35 instructions of Epetra_BlockMap::LID per value).
    struct LocalIndices
    {
      const Epetra_BlockMapData *map = nullptr;
      std::vector<int>           lids;
    };
    LocalIndices vertex_lids, heat_lids;

    const std::vector<int> &local_indices(LocalIndices &kept, const Epetra_BlockMap &map,
                                          const std::vector<types::global_dof_index> &dofs)
    {
      if (kept.map != map.DataPtr() || kept.lids.size() != dofs.size())
        {
          kept.lids.resize(dofs.size());
          for (std::size_t i = 0; i < dofs.size(); ++i)
            {
              kept.lids[i] = map.LID(static_cast<TrilinosWrappers::types::int_type>(dofs[i]));
              AssertThrow(kept.lids[i] >= 0, ExcMessage("Fields: a vertex value is not on this process"));
            }
          kept.map = map.DataPtr();
        }
      return kept.lids;
    }

    /// @p components values per point (@p width in all, zeros after them)
    /// from the ghosted vector @p v at @p dofs (components per point).
    void dof_array(std::vector<float> &a, const TrilinosWrappers::MPI::Vector &v,
                   const std::vector<types::global_dof_index> &dofs, LocalIndices &kept,
                   const unsigned int components, const unsigned int width)
    {
      a.assign(piece.n_points() * width, 0.f);
      const std::vector<int> &lids   = local_indices(kept, v.trilinos_vector().Map(), dofs);
      const double *const     values = v.trilinos_vector()[0];
      for (std::size_t p = 0; p < piece.n_points(); ++p)
        for (unsigned int c = 0; c < components; ++c)
          a[p * width + c] = static_cast<float>(values[lids[p * components + c]]);
    }

    /// A point array from the ghosted nodal vector @p v at the local indices @p local.
    void nodal_array(std::vector<float> &a, const NodalVector &v, const std::vector<unsigned int> &local)
    {
      a.resize(local.size());
      for (std::size_t p = 0; p < local.size(); ++p)
        a[p] = static_cast<float>(v.local_element(local[p]));
    }

    /// A cell array: each cell's value at each of its vertices.
    template <typename VectorType>
    void cell_array(std::vector<float> &a, const VectorType &cell_values)
    {
      constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;
      a.resize(cell_index.size() * n_vertices);
      for (std::size_t c = 0; c < cell_index.size(); ++c)
        std::fill_n(a.begin() + c * n_vertices, n_vertices, static_cast<float>(cell_values[cell_index[c]]));
    }

    void write_raw(const SimulationState<dim> &s)
    {
      const auto *mechanical = s.physics.mechanics();
      const auto *thermal    = s.physics.heat();
      cell_fields            = mechanical->cell_fields();
      recover(s, cell_fields); // before prepare_raw: it makes nodal_dofs
      prepare_raw(s);
      // DataOut's arrays in its order (dof data, then cell data), each made
      // when written: all at once they were ~0.25 KB/DoF of a 3D write
      // (21 Float32 arrays and a vector at 8 points per cell; doc/memory.md,
      // session 23).
      using Fill = std::function<void(std::vector<float> &)>;
      std::vector<VtuArray> arrays;
      std::vector<Fill>     fills;
      const auto add = [&](const std::string &name, const unsigned int components, Fill fill) {
        arrays.push_back({name, components});
        fills.push_back(std::move(fill));
      };
      add("displacement", 3, [&](std::vector<float> &a) {
        dof_array(a, mechanical->displacement(), vertex_dofs, vertex_lids, dim, 3);
      });
      if (mechanical->is_dynamic())
        add("velocity", 3, [&](std::vector<float> &a) {
          dof_array(a, mechanical->velocity(), vertex_dofs, vertex_lids, dim, 3);
        });
      if (thermal)
        add("temperature", 1, [&](std::vector<float> &a) {
          dof_array(a, thermal->temperature(), heat_dofs, heat_lids, 1, 1);
        });
      for (unsigned int i = 0; i < nodal_names.size(); ++i)
        add(nodal_names[i], 1,
            [this, i](std::vector<float> &a) { nodal_array(a, nodal_values[i], nodal_vertex); });
      if (!thermal && s.physics.has_temperature())
        add("temperature", 1,
            [&](std::vector<float> &a) { cell_array(a, s.physics.cell_temperature()); });
      for (unsigned int i = 0; i < cell_fields.names.size(); ++i)
        add(cell_fields.names[i], 1,
            [this, i](std::vector<float> &a) { cell_array(a, cell_fields.values[i]); });
      const float rank = Utilities::MPI::this_mpi_process(s.communicator);
      add("rank", 1, [&](std::vector<float> &a) { a.assign(piece.n_points(), rank); });

      // The names write_vtu_with_pvtu_record gives (one file per process).
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(s.communicator);
      const unsigned int digits  = Utilities::needed_digits(n_ranks - 1);
      const std::string  stem    = "solution_" + Utilities::int_to_string(s.step, 5);
      const auto piece_name      = [&](const unsigned int r) {
        return stem + "." + Utilities::int_to_string(r, digits) + ".vtu";
      };
      write_vtu_raw<float>(
        piece, arrays, [&](const std::size_t i, std::vector<float> &a) { fills[i](a); },
        s.output_directory + "/fields/" + piece_name(Utilities::MPI::this_mpi_process(s.communicator)));
      if (s.is_root())
        {
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece_name(r));
          write_pvtu_record<float>(arrays, pieces, s.output_directory + "/fields/" + stem + ".pvtu");
        }
      this->schedule.record(s.time, "fields/" + stem + ".pvtu", s.output_directory + "/solution.pvd",
                            s.is_root());
      cell_fields = typename MechanicalProblem<dim>::CellFields();
    }

    // Nodal twins "<field>_nodal" of the cell fields (smooth pictures):
    // patch averaging, each vertex gets the volume-weighted mean of the cell
    // values of the cells around it, on every process the same (the sums
    // over cells of other processes arrive through compress(add)). Across a
    // material interface the average smears what the cell values keep sharp.
    DoFHandler<dim>          nodal_dofs;
    FE_Q<dim>                nodal_fe{1};
    std::vector<std::string> nodal_names;
    std::vector<NodalVector> nodal_values; // ghosted

    // The nodal numbering, its partitioner, each owned cell's vertex dofs (as
    // local indices) and volume and each vertex's patch volume depend on the
    // mesh only (the volumes are the reference cells'), so they are made at
    // the first write and kept while the mesh is the same; so are the
    // vectors. (Trilinos vectors built per write and field cost ~11 M
    // instructions each on two processes, their maps and imports made anew:
    // ~0.9 G per process for the contact strip's two writes.)
    const Triangulation<dim>                             *nodal_mesh  = nullptr;
    unsigned int                                          nodal_cells = 0;
    std::shared_ptr<const Utilities::MPI::Partitioner>    nodal_partitioner;
    std::vector<unsigned int>                             nodal_cell_dofs; // per owned cell, its vertices' local indices
    std::vector<double>                                   nodal_cell_volume; // per owned cell
    std::vector<unsigned int>                             nodal_cell_index;  // per owned cell, its active cell index
    NodalVector                                           patch_volume; // Σ of the cell volumes around each vertex

    void prepare_nodal_dofs(const SimulationState<dim> &s)
    {
      if (nodal_mesh == &s.triangulation && nodal_cells == s.triangulation.n_active_cells())
        return;
      nodal_values.clear(); // their layout was the old mesh's
      nodal_dofs.reinit(s.triangulation);
      nodal_dofs.distribute_dofs(nodal_fe);
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(nodal_dofs, relevant);
      nodal_partitioner = std::make_shared<Utilities::MPI::Partitioner>(nodal_dofs.locally_owned_dofs(),
                                                                        relevant, s.communicator);
      patch_volume.reinit(nodal_partitioner);
      nodal_cell_dofs.clear();
      nodal_cell_volume.clear();
      nodal_cell_index.clear();
      std::vector<types::global_dof_index> dofs(nodal_fe.n_dofs_per_cell());
      for (const auto &cell : nodal_dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(dofs);
            const double volume = cell->measure();
            nodal_cell_volume.push_back(volume);
            nodal_cell_index.push_back(cell->active_cell_index());
            for (const auto d : dofs)
              {
                nodal_cell_dofs.push_back(nodal_partitioner->global_to_local(d));
                patch_volume.local_element(nodal_cell_dofs.back()) += volume;
              }
          }
      patch_volume.compress(VectorOperation::add);
      nodal_mesh  = &s.triangulation;
      nodal_cells = s.triangulation.n_active_cells();
    }

    void recover(const SimulationState<dim>                        &s,
                 const typename MechanicalProblem<dim>::CellFields &fields)
    {
      prepare_nodal_dofs(s);
      std::vector<unsigned int> which;
      nodal_names.clear();
      for (unsigned int i = 0; i < fields.names.size(); ++i)
        if (recovered(fields.names[i]))
          {
            which.push_back(i);
            nodal_names.push_back(fields.names[i] + "_nodal");
          }
      nodal_values.resize(which.size());
      const unsigned int n_vertices = nodal_fe.n_dofs_per_cell();
      const unsigned int n_owned    = nodal_partitioner->locally_owned_size();
      for (unsigned int k = 0; k < which.size(); ++k)
        {
          // Sums of cell contributions (ghost entries included), compress(add),
          // then the owned means, then the ghosts' values from their owners.
          NodalVector &v = nodal_values[k];
          if (v.size() == 0)
            v.reinit(nodal_partitioner);
          else
            v = 0.;
          const auto &values = fields.values[which[k]];
          for (std::size_t c = 0; c < nodal_cell_index.size(); ++c)
            {
              const double contribution = nodal_cell_volume[c] * values[nodal_cell_index[c]];
              for (unsigned int j = 0; j < n_vertices; ++j)
                v.local_element(nodal_cell_dofs[c * n_vertices + j]) += contribution;
            }
          v.compress(VectorOperation::add);
          for (unsigned int i = 0; i < n_owned; ++i)
            v.local_element(i) = v.local_element(i) / patch_volume.local_element(i);
          v.update_ghost_values();
        }
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Fields, "fields",
                               "solution.pvd: displacement, velocity, temperature, Cauchy "
                               "stress, von Mises, pressure, J, equivalent plastic strain, body, "
                               "rank (VTU, every Field interval steps); the stresses and the "
                               "plastic strain also as nodal fields <name>_nodal (patch "
                               "averages of the cell values).")
} // namespace anvil
