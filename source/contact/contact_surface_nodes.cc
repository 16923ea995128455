// ContactProblem, the surface nodes between evaluations: which process
// evaluates a node, the nodes' current positions gathered from their owners,
// and a slave node's tributary area (split from contact_problem.cc: the
// parallel share-out and the geometry of one node, not the search).
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/instantiate.h>

#include <cmath>
#include <vector>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void ContactProblem<dim>::share_out_nodes()
  {
    // Every process has every surface position, so a node is evaluated by
    // one process whatever the partition of the cells (a long strip may lie
    // on one process); the element's rows go to their owners through
    // Trilinos. The k-th node of each surface (numbered by reference
    // coordinates: partition-independent) goes to process k mod P, so that
    // contact in one small region (a fold) is still shared out. Not the node
    // number mod P over all surfaces: where two surfaces lie face to face
    // their nodes interleave in that numbering, and one process got every
    // slave (10000 of 10001 on the contact benchmark's strip).
    const unsigned int P    = Utilities::MPI::n_mpi_processes(mpi_communicator);
    const unsigned int rank = Utilities::MPI::this_mpi_process(mpi_communicator);
    std::vector<int>   owner(node_reference.size(), -1);
    for (const auto &[b, surface] : surfaces)
      for (std::size_t k = 0; k < surface.nodes.size(); ++k)
        if (owner[surface.nodes[k]] < 0)
          owner[surface.nodes[k]] = static_cast<int>(k % P);
    // Where the owners of the nodes' rows share out every surface evenly (a
    // partition that cuts each body into slabs, Geometry/Partition = per
    // body), the owner evaluates: the element's slave rows are then its own
    // and most master rows too, where k mod P sent half of every process's
    // rows to the other (np 2 strip per body, 48 k DoFs, per rank: contact
    // 430 -> 284 M instructions, matrix compress 114 -> 0 M, np 1 518 M).
    // Even: on every surface no process owns more than 1.25 n / P + 1 nodes.
    if (P > 1)
      {
        std::vector<unsigned int> counts, sizes;
        for (const auto &[b, surface] : surfaces)
          {
            unsigned int c = 0;
            for (const unsigned int n : surface.nodes)
              c += node_owned[n] ? 1 : 0;
            counts.push_back(c);
            sizes.push_back(surface.nodes.size());
          }
        std::vector<unsigned int> most(counts.size());
        const int ierr = MPI_Allreduce(counts.data(), most.data(), static_cast<int>(counts.size()),
                                       MPI_UNSIGNED, MPI_MAX, mpi_communicator);
        AssertThrowMPI(ierr);
        bool       even = true;
        for (std::size_t i = 0; i < sizes.size(); ++i)
          even = even && most[i] <= 1.25 * sizes[i] / P + 1;
        if (even)
          {
            node_mine = node_owned;
            return;
          }
      }
    node_mine.assign(node_reference.size(), false);
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      node_mine[n] = owner[n] == static_cast<int>(rank);
  }

  template <int dim>
  void ContactProblem<dim>::gather_positions(const Vector &u, std::vector<Point<dim>> &x) const
  {
    std::vector<double> values(node_reference.size() * dim, 0.);
    const IndexSet     &owned = u.locally_owned_elements();
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      for (unsigned int c = 0; c < dim; ++c)
        if (owned.is_element(node_dofs[n][c]))
          values[n * dim + c] = u(node_dofs[n][c]);
    Utilities::MPI::sum(values, mpi_communicator, values);
    x.resize(node_reference.size());
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      for (unsigned int c = 0; c < dim; ++c)
        x[n][c] = node_reference[n][c] + values[n * dim + c];
  }

  template <int dim>
  double ContactProblem<dim>::tributary_area(const unsigned int node, const Surface &surface,
                                             const std::vector<Point<dim>> &x) const
  {
    // 2D: half of each adjacent segment; axisymmetric: the node's share of
    // the ring each segment sweeps, the integral of its shape function,
    // 2 pi L (2 r_node + r_other) / 6 — the share a uniform pressure's
    // nodal forces have, so a uniform pressure gives a uniform penetration.
    // Inside a uniform face that is 2 pi r L as before; the node on the axis
    // gets pi L^2 / 3, not 2 pi r L/2 = 0 (no force: it sank through the tool).
    // The areas add up to the face's. 3D: a quarter of each adjacent facet.
    double area = 0;
    for (const auto f : node_faces[node])
      {
        const auto &nodes = faces[f].nodes;
        if (!surface.has(faces[f]))
          continue;
        if constexpr (dim == 2)
          {
            const double length = x[nodes[0]].distance(x[nodes[1]]);
            if (!axisymmetric)
              area += 0.5 * length;
            else
              {
                const double r     = std::abs(x[node][0]);
                const double other = std::abs(x[nodes[0] == node ? nodes[1] : nodes[0]][0]);
                area += 2 * numbers::PI * length * (2 * r + other) / 6;
              }
          }
        else
          {
            const Tensor<1, dim> d1 = x[nodes[3]] - x[nodes[0]], d2 = x[nodes[2]] - x[nodes[1]];
            area += 0.25 * 0.5 * cross_product_3d(d1, d2).norm();
          }
      }
    return area;
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
