// Every process's vector of doubles, in rank order, on every process.
// Utilities::MPI::all_gather serialises through boost and zlib even on one
// process (two_blocks: 35 M of the 37 M instructions of a heat step's
// contact preparation); contact data are plain doubles, so one
// MPI_Allgatherv of the raw values does the same without packing.
#ifndef anvil_core_gather_h
#define anvil_core_gather_h

#include <deal.II/base/mpi.h>

#include <numeric>
#include <vector>

namespace anvil
{
  inline std::vector<std::vector<double>> gather_doubles(const MPI_Comm             comm,
                                                         const std::vector<double> &local)
  {
    const unsigned int n = dealii::Utilities::MPI::n_mpi_processes(comm);
    if (n == 1)
      return {local};
    const int        size = static_cast<int>(local.size());
    std::vector<int> sizes(n), offsets(n, 0);
    int              ierr = MPI_Allgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
    AssertThrowMPI(ierr);
    std::partial_sum(sizes.begin(), sizes.end() - 1, offsets.begin() + 1);
    std::vector<double> all(offsets.back() + sizes.back());
    ierr = MPI_Allgatherv(local.data(), size, MPI_DOUBLE, all.data(), sizes.data(), offsets.data(),
                          MPI_DOUBLE, comm);
    AssertThrowMPI(ierr);
    std::vector<std::vector<double>> parts(n);
    for (unsigned int p = 0; p < n; ++p)
      parts[p].assign(all.begin() + offsets[p], all.begin() + offsets[p] + sizes[p]);
    return parts;
  }
} // namespace anvil

#endif
