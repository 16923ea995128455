#include <deal.II/base/utilities.h>

#include <anvil/coupling/dof_colouring.h>

#include <algorithm>
#include <limits>

namespace anvil
{
  using namespace dealii;

  std::vector<unsigned int> colour_columns(const CellDofs &columns, const CellDofs &links,
                                           const std::size_t n_columns, const std::size_t n_links,
                                           unsigned int &n_colours)
  {
    std::vector<std::vector<unsigned int>> cells_of_column(n_columns), cells_of_link(n_links);
    for (unsigned int c = 0; c < columns.size(); ++c)
      {
        for (const auto j : columns[c])
          cells_of_column[j].push_back(c);
        for (const auto l : links[c])
          cells_of_link[l].push_back(c);
      }
    const unsigned int        none = std::numeric_limits<unsigned int>::max();
    std::vector<unsigned int> colour(n_columns, none);
    std::vector<bool>         taken;
    n_colours = 0;
    for (std::size_t j = 0; j < n_columns; ++j)
      {
        taken.assign(n_colours + 1, false);
        for (const auto c1 : cells_of_column[j])
          for (const auto l : links[c1])
            for (const auto c2 : cells_of_link[l])
              for (const auto k : columns[c2])
                if (colour[k] != none)
                  taken[colour[k]] = true;
        colour[j] = std::find(taken.begin(), taken.end(), false) - taken.begin();
        n_colours = std::max(n_colours, colour[j] + 1);
      }
    return colour;
  }

  CellDofs gather_cells(const CellDofs &local, const MPI_Comm comm)
  {
    CellDofs all;
    for (const auto &part : Utilities::MPI::all_gather(comm, local))
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }
} // namespace anvil
