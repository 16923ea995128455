#pragma once

// Errors found on some ranks only (a node, a point, a cell they own) must end
// every rank with the same line: the lowest rank that has one tells.

#include <deal.II/base/mpi.h>

#include <string>

namespace anvil
{
  /// The lowest rank's non-empty @p local message, on every rank; "" if no rank has one.
  inline std::string first_message(const std::string &local, const MPI_Comm comm)
  {
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
    const unsigned int first   = dealii::Utilities::MPI::min(
      local.empty() ? n_ranks : dealii::Utilities::MPI::this_mpi_process(comm), comm);
    if (first == n_ranks)
      return "";
    return dealii::Utilities::MPI::broadcast(comm, local, first);
  }
} // namespace anvil
