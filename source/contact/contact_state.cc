// ContactProblem, its history: per-pair totals of the accepted step, the
// committed stick/slip state and tangential forces (reverted with a cut-back),
// the slave nodes as output, and the state carried through checkpoints.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/rtree.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// The processes' pieces of text joined in rank order on process 0 (the
    /// others get an empty string).
    std::string gather_text(const MPI_Comm comm, const std::string &piece)
    {
      const unsigned int n = Utilities::MPI::n_mpi_processes(comm);
      if (n == 1)
        return piece;
      const int        size = static_cast<int>(piece.size());
      std::vector<int> sizes(n), offsets(n, 0);
      int ierr = MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm);
      AssertThrowMPI(ierr);
      std::partial_sum(sizes.begin(), sizes.end() - 1, offsets.begin() + 1);
      std::string all(Utilities::MPI::this_mpi_process(comm) == 0 ? offsets.back() + sizes.back() : 0, ' ');
      ierr = MPI_Gatherv(piece.data(), size, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0,
                         comm);
      AssertThrowMPI(ierr);
      return all;
    }
  } // namespace

  template <int dim>
  void ContactProblem<dim>::commit()
  {
    constexpr unsigned int w = dim + 5; // force (dim), t_N, |t_T|, work, active, sliding
    std::vector<double> sums(pairs.size() * w, 0.), maxima(pairs.size(), 0.);
    for (auto &slot : slots)
      {
        if (!slot.evaluated)
          continue;
        const Trial       &trial = slot.trial;
        const unsigned int p     = slot.pair;
        committed[slot.key()]    = trial.state;
        slot.state               = trial.state;
        double *s            = &sums[p * w];
        if (trial.normal_force > 0)
          {
            // The reverse pass of a two-pass pair acts on the Master body: its
            // reaction is what the Slave body feels.
            const double sign = slot.pass == 0 ? 1. : -1.;
            for (unsigned int d = 0; d < dim; ++d)
              s[d] += sign * trial.force_on_slave[d];
            s[dim] += trial.normal_force;
            s[dim + 1] += trial.tangential_force;
            s[dim + 2] += trial.work;
            s[dim + 3] += 1;
            s[dim + 4] += trial.state.sliding ? 1 : 0;
            maxima[p] = std::max(maxima[p], -trial.gap);
          }
      }
    Utilities::MPI::sum(sums, mpi_communicator, sums);
    Utilities::MPI::max(maxima, mpi_communicator, maxima);
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        const double *s = &sums[p * w];
        auto         &t = pair_totals[p];
        for (unsigned int d = 0; d < dim; ++d)
          t.force[d] = s[d];
        t.normal     = s[dim];
        t.tangential = s[dim + 1];
        t.friction_work += s[dim + 2];
        t.active          = static_cast<unsigned int>(s[dim + 3] + 0.5);
        t.sliding         = static_cast<unsigned int>(s[dim + 4] + 0.5);
        t.max_penetration = maxima[p];
      }
  }

  template <int dim>
  std::vector<typename ContactProblem<dim>::NodeOutput> ContactProblem<dim>::node_outputs() const
  {
    std::vector<NodeOutput> out;
    const double            dt = t_new - t_old;
    for (const auto &slot : slots)
      {
        if (!slot.evaluated)
          continue;
        const Trial &trial = slot.trial;
        const Pair  &pair  = pairs[slot.pair];
        NodeOutput   o;
        o.pair     = slot.pair;
        o.position = trial.position;
        if (trial.normal_force > 0 && trial.area > 0)
          {
            o.pressure    = trial.normal_force / (pair.penalty_share() * trial.area);
            o.conductance = pair.conductance > 0 ?
                              pair.conductance * std::pow(o.pressure / pair.hardness, pair.exponent) :
                              0.;
          }
        o.gap            = trial.gap;
        o.slip           = trial.slip;
        const auto q     = heat_flux.find({slot.pair, slot.node});
        if (q != heat_flux.end() && trial.area > 0)
          o.heat_flux = q->second / trial.area;
        o.friction_power = dt > 0 ? trial.work / dt : 0.;
        o.status         = trial.normal_force > 0 ? (trial.state.sliding ? 2 : 1) : 0;
        out.push_back(o);
      }
    return out;
  }

  template <int dim>
  void ContactProblem<dim>::save(std::ostream &out) const
  {
    // (pair, pass, node, in_contact, sliding, t_T) of every process. Each
    // process writes its own nodes' values as text and process 0, which
    // writes the state file, joins the pieces: the text is the cost (it was
    // gathered to every process and written there with ostream's %.17g,
    // ~3 k instructions a value: 192 M per process on the contact strip).
    // to_chars' shortest form reads back to the same bits as %.17g's.
    std::string  piece;
    std::size_t  n_local = 0;
    char         buffer[32];
    const auto   put = [&](const double x) {
      buffer[0]       = ' ';
      const auto end  = std::to_chars(buffer + 1, buffer + sizeof buffer, x).ptr;
      piece.append(buffer, end);
      ++n_local;
    };
    for (const auto &[key, st] : committed)
      if (node_mine[std::get<2>(key)])
        {
          put(std::get<0>(key));
          put(std::get<1>(key));
          put(std::get<2>(key));
          put(st.in_contact ? 1. : 0.);
          put(st.sliding ? 1. : 0.);
          for (unsigned int d = 0; d < dim; ++d)
            put(st.tangential_force[d]);
        }
    const std::size_t n_all = Utilities::MPI::sum(n_local, mpi_communicator);
    const std::string all   = gather_text(mpi_communicator, piece);
    if (Utilities::MPI::this_mpi_process(mpi_communicator) != 0)
      return;
    out << std::setprecision(17) << n_all << all;
    out << ' ' << pair_totals.size();
    for (const auto &t : pair_totals)
      out << ' ' << t.friction_work << ' ' << t.heat_exchanged << ' ' << t.friction_heat;
    out << '\n';
  }

  template <int dim>
  void ContactProblem<dim>::load(std::istream &in)
  {
    std::size_t n = 0;
    in >> n;
    // A count larger than the node states the surfaces can hold is damage, not
    // a state to allocate for.
    const std::size_t most = (node_reference.size() + 1) * (5 + dim) * 2 * std::max<std::size_t>(1, pairs.size());
    if (!in || n > most)
      throw InputError("the contact state holds " + std::to_string(n) +
                       " values, more than the contact surfaces can have (damaged?)");
    std::vector<double> all(n);
    for (double &x : all)
      in >> x;
    if (!in)
      throw InputError("the contact state is truncated (damaged?)");
    committed.clear();
    slots.clear(); // begin_step() takes the states from committed
    for (std::size_t i = 0; i + 5 + dim <= all.size(); i += 5 + dim)
      {
        contact::NodeState<dim> st;
        st.in_contact = all[i + 3] > 0.5;
        st.sliding    = all[i + 4] > 0.5;
        for (unsigned int d = 0; d < dim; ++d)
          st.tangential_force[d] = all[i + 5 + d];
        committed[Key(static_cast<unsigned int>(all[i]), static_cast<unsigned int>(all[i + 1]),
                      static_cast<unsigned int>(all[i + 2]))] = st;
      }
    std::size_t n_pairs = 0;
    in >> n_pairs;
    if (n_pairs != pair_totals.size())
      throw InputError("the checkpoint has " + std::to_string(n_pairs) + " contact pairs, the scene " +
                       std::to_string(pair_totals.size()));
    for (auto &t : pair_totals)
      in >> t.friction_work >> t.heat_exchanged >> t.friction_heat;
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
