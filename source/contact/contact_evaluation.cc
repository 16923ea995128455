// ContactProblem::assemble(): every slave node this process evaluates, against
// its candidate master faces or its tool, into the mechanics (seed §3.1,
// eq. 27–29: the penalty normal force, the return-mapped friction force and
// their tangents). The surfaces and the search are in contact_problem.cc.
#include <deal.II/base/mpi.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/contact/free_end.h>
#include <anvil/core/instantiate.h>

#include <algorithm>
#include <limits>

namespace anvil
{
  using namespace dealii;


  template <int dim>
  bool ContactProblem<dim>::near_step_start(const std::vector<Point<dim>> &x) const
  {
    // The step's candidate lists (margin 1.5 faces at t_n) hold every face
    // this search (margin 0.5 at x) finds while no surface node has moved by
    // 0.5 of the largest face in a coordinate relative to a common
    // translation τ (the midrange of the nodes' motion: a tube crushed onto
    // its base moves as a whole at the top): a face's box moved by τ and at
    // most δ more, the node by τ + δ, so the node lies within 0.5 + 2δ ≤ 1.5
    // of the old box moved by τ, i.e. the old node of the old box. Filtered
    // by the search's own test they are its candidates, bit for bit, without
    // an R-tree query per node (0.4: clear of round-off).
    bool near_start = x_old.size() == x.size();
    for (unsigned int d = 0; near_start && d < dim; ++d)
      {
        double lo = std::numeric_limits<double>::max(), hi = -lo;
        for (unsigned int n = 0; n < x.size(); ++n)
          {
            lo = std::min(lo, x[n][d] - x_old[n][d]);
            hi = std::max(hi, x[n][d] - x_old[n][d]);
          }
        near_start = x.empty() || hi - lo < 0.8 * largest_face;
      }
    return near_start;
  }


  template <int dim>
  const contact::ContactResult<dim> &
  ContactProblem<dim>::evaluate_on_faces(const unsigned int p, const unsigned int pass,
                                         const unsigned int i, Slot &slot,
                                         const CandidateLists &candidates,
                                         const std::vector<Point<dim>> &x,
                                         const contact::FrictionLaw &law, const bool with_matrix,
                                         std::vector<types::global_dof_index> &dofs, bool &missing)
  {
    const unsigned int n          = slot.node;
    Trial             &trial      = slot.trial;
    auto              &beyond_end = scratch_beyond_end; // (face, its end)
    contact::ContactResult<dim> *result = &face_result;
    beyond_end.clear();
    result->in_contact = false;
    result->new_state  = contact::NodeState<dim>();
    int best_face = closest_face(p, n, candidates.faces.data() + candidates.start[i],
                                 candidates.start[i + 1] - candidates.start[i], x, slot.state, law,
                                 *result, beyond_end);
    bool extended = false; // best_face is an end segment extended (free_end_contact)
    // A coupling the matrix pattern lacks: the pattern grows and the caller
    // re-assembles (nothing of this evaluation is added).
    const auto note = [&](const unsigned int f) {
      insert_sorted(step_allowed, {{p, pass, n, f}});
      if (insert_sorted(allowed, {{p, pass, n, f}}))
        {
          grew    = true;
          missing = true;
        }
    };
    if (best_face < 0)
      {
        // Concave corners are detected in 2D only (doc/contact.md).
        const auto corner =
          dim == 2 ? concave_corner(beyond_end) : std::pair<int, unsigned int>(-1, 0);
        if (corner.first < 0)
          {
            const int f = free_end_face(p, pass, n, beyond_end, x, slot.state, law, with_matrix,
                                        best_face, *result);
            if (f >= 0)
              {
                best_face = f;
                extended  = true;
              }
          }
        if (corner.first >= 0)
          {
            const unsigned int v = faces[corner.first].nodes[corner.second];
            result               = &vertex_result;
            contact::node_to_vertex(*result, x[n], x_old[n], x[v], x_old[v], slot.state, law,
                                    with_matrix);
            if (result->in_contact)
              {
                note(corner.first);
                dofs.insert(dofs.end(), node_dofs[v].begin(), node_dofs[v].end());
                trial.face       = corner.first;
                trial.weights[0] = corner.second == 0 ? 1. : 0.;
                trial.weights[1] = corner.second == 0 ? 0. : 1.;
              }
          }
      }
    else if (with_matrix && result->in_contact)
      {
        // The tangent for the face kept only.
        std::array<Point<dim>, 4> xm, xm_old;
        face_positions(best_face, x, xm, xm_old);
        contact::node_to_segment(*result, x[n], x_old[n], xm.data(), xm_old.data(), slot.state,
                                 law, true);
      }
    if (best_face >= 0 && result->in_contact)
      {
        note(best_face);
        for (const auto m : faces[best_face].nodes)
          dofs.insert(dofs.end(), node_dofs[m].begin(), node_dofs[m].end());
        trial.face     = best_face;
        const auto &xi = result->xi;
        if (dim == 2 && extended) // the heat goes to the end node
          trial.weights = {{xi[0] < 0 ? 1. : 0., xi[0] < 0 ? 0. : 1., 0., 0.}};
        else if (dim == 2)
          trial.weights = {{1 - xi[0], xi[0], 0., 0.}};
        else
          trial.weights = {{(1 - xi[0]) * (1 - xi[1]), xi[0] * (1 - xi[1]), (1 - xi[0]) * xi[1],
                            xi[0] * xi[1]}};
      }
    return *result;
  }


  template <int dim>
  bool ContactProblem<dim>::assemble(const Vector &u, const bool with_matrix, const Adder &add)
  {
    std::vector<Point<dim>> &x = x_last;
    gather_positions(u, x);
    bool       missing     = false;
    double     penetration = 0;
    const bool near_start  = near_step_start(x);
    auto      &dofs        = scratch_dofs;
    for (unsigned int p = 0; p < pairs.size(); ++p)
      {
        const Pair &pair = pairs[p];
        // A tool's translation, once per evaluation, not per node.
        Tensor<1, dim> tool_u, tool_u_old;
        if (pair.tool >= 0)
          {
            tool_u     = tools[pair.tool]->displacement(t_new);
            tool_u_old = tools[pair.tool]->displacement(t_old);
          }
        for (unsigned int pass = 0; pass < pair.passes(); ++pass)
          {
            const StepSide &side       = step_sides[2 * p + pass];
            CandidateLists &candidates = scratch_candidates;
            if (pair.tool < 0 && near_start)
              filter_candidates(side.candidates, x, 0.5 * largest_face, side.mine, candidates);
            else if (pair.tool < 0)
              candidate_faces(master_side(p, pass), x, 0.5 * largest_face, side.mine, candidates);

            for (unsigned int k = side.begin; k < side.end; ++k)
              {
                Slot              &slot = slots[k];
                const unsigned int n    = slot.node;
                contact::FrictionLaw law = pair.law;
                const double scale = (pair.per_area ? slot.area : 1.) * pair.penalty_share();
                law.penalty_normal *= scale;
                law.penalty_tangent *= scale;

                Trial &trial   = slot.trial;
                trial          = Trial();
                slot.evaluated = true;
                dofs.assign(node_dofs[n].begin(), node_dofs[n].end());
                const contact::ContactResult<dim> *result = &tool_result;
                if (pair.tool >= 0)
                  contact::node_to_tool(tool_result, x[n], x_old[n], *tools[pair.tool], tool_u,
                                        tool_u_old, slot.state, law, with_matrix);
                else
                  result = &evaluate_on_faces(p, pass, k - side.begin, slot, candidates, x, law,
                                              with_matrix, dofs, missing);
                const contact::ContactResult<dim> &r = *result;
                trial.position = x[n];
                if (!r.in_contact)
                  trial.face = -1;
                trial.state = r.new_state;
                trial.area  = slot.area;
                if (!r.in_contact)
                  continue;
                penetration            = std::max(penetration, -r.gap);
                trial.normal_force     = r.normal_force;
                trial.gap              = r.gap;
                trial.slip             = r.slip_increment.norm();
                trial.work             = r.frictional_work;
                trial.normal           = r.normal;
                trial.tangential_force = r.tangential_force.norm();
                trial.force_on_slave   = r.normal_force * r.normal - r.tangential_force;
                if (!missing)
                  add(dofs, r.residual, with_matrix ? &r.tangent : nullptr);
              }
          }
      }
    trial_max_penetration = Utilities::MPI::max(penetration, mpi_communicator);
    return Utilities::MPI::max(missing ? 1 : 0, mpi_communicator) == 0;
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
