#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <anvil/contact/rigid_tool.h>

#include <string>
#include <vector>

namespace anvil
{
  /**
   * Node-to-segment frictional contact elements, seed §3.1 (eq. 27–29): the
   * mathematics of one slave node against one master segment (2D), facet
   * (3D) or rigid tool, with its residual and its exact tangent. Finding the
   * pairs, the tributary areas, assembly, parallel exchange and the heat
   * exchange (eq. 30–34) are the caller's.
   *
   * Conventions.
   *  - Positions are current coordinates (mm); `*_old` are those at t_n, the
   *    start of the step.
   *  - The master normal n points from the master body towards the slave. The
   *    gap is g_N = (x_s − x_m(ξ)) · n: > 0 apart, < 0 penetration.
   *  - Master parametrization on the unit segment/square (deal.II's reference
   *    face): 2D x_m(ξ) = (1 − ξ) x₀ + ξ x₁, ξ ∈ [0, 1], and n is the LEFT
   *    normal of x₁ − x₀ (x₀ → x₁ rotated by +90°); 3D x_m(ξ, η) =
   *    Σ N_a(ξ, η) x_a with the bilinear N₀ = (1−ξ)(1−η), N₁ = ξ(1−η),
   *    N₂ = (1−ξ)η, N₃ = ξη (vertices in lexicographic order, as deal.II
   *    numbers a face's vertices), (ξ, η) ∈ [0, 1]², and n ∥ x_{m,ξ} × x_{m,η}.
   *    The caller orders the master nodes so that this n points out of the
   *    master body: taking the vertices of face f of a deal.II cell as
   *    cell->vertex(GeometryInfo<dim>::face_to_cell_vertices(f, v)), that is
   *    the case for faces 0 and 3 in 2D and the odd faces in 3D; for the
   *    others reverse the two vertices (2D) or swap vertices 1 and 2 (3D).
   *    face_order_gives_outward_normal() says which.
   *  - The projection ξ of the slave is the closest point on the master (in 3D
   *    by Newton in (ξ, η) on the bilinear surface). If it falls outside the
   *    parameter domain (by more than 1e-3, so that a slave just beyond the end of a master surface stays in contact with the end segment extended), projection_inside = false and
   *    in_contact = false: the caller tries the neighbouring master. At a
   *    vertex both neighbours may accept the node: the caller keeps one.
   *  - Normal contact, penalty (eq. 27): t_N = c_N ⟨−g_N⟩ ≥ 0 per node (the
   *    caller scales c_N by a tributary area for a per-area penalty). No
   *    contact if g_N >= 0: then t_N = 0, t_T = 0 and in_contact = false.
   *  - Tangential increment of the step (relative to the master, on the
   *    current tangent plane):
   *      Δg_T = (I − n⊗n) [(x_s − x_s,old) − (x_m(ξ) − x_m,old(ξ))],
   *    with the master's old position taken at the CURRENT ξ (so a slave that
   *    passed from one master segment to the next sees only its own motion);
   *    for a tool x_m(ξ) − x_m,old(ξ) is u(t) − u(t_old).
   *  - Friction, elastic predictor and radial return (eq. 28–29):
   *      t_trial = P_n t_T,n + c_T Δg_T,
   *    P_n t_T,n being the old force projected on the current tangent plane
   *    with its magnitude kept (zero if the node was not in contact at t_n);
   *    stick if |t_trial| <= μ_static t_N: t_T = t_trial, no slip; otherwise
   *    slide: t_T = μ_dynamic t_N t_trial/|t_trial| and the slip increment is
   *    (|t_trial| − μ_dynamic t_N)/c_T · t_trial/|t_trial|. Requires
   *    μ_dynamic <= μ_static. c_T = 0 is frictionless: t_T = 0 and all of
   *    Δg_T is slip (sliding). frictional_work = t_T · slip_increment >= 0
   *    (the step's share of eq. 31, D_tot Δt).
   *  - t_T, as used in these formulas, points along the relative tangential
   *    motion of the slave (it is the reaction of an elastic tangential
   *    spring): the friction force that acts ON the slave is −t_T (opposite
   *    to its motion), the one on the master +t_T. Likewise the normal force
   *    on the slave is +t_N n.
   *  - Residual: the generalized internal force of the contact,
   *      r · δx = −t_N δg_N + t_T · δg_T,
   *    δg_N = n · (δx_s − Σ N_a δx_a), δg_T = (I − n⊗n)(δx_s − Σ N_a δx_a):
   *      r_s = −t_N n + t_T,   r_a = N_a(ξ) (t_N n − t_T),
   *    ordered [slave (dim), master node 0 (dim), master node 1 (dim), ...]
   *    (only the slave for a tool). Adding r to R = f_int − f_ext pushes the
   *    bodies apart.
   *  - Tangent: d r / d(current coordinates, same ordering), computed by
   *    forward automatic differentiation (Sacado::Fad::DFad) of the residual:
   *    the consistent linearization, including the variation of ξ and n and
   *    of the stick/slip response, with the branch (contact, stick or slide)
   *    chosen by value. It is generally not symmetric. Filled only when
   *    requested (otherwise left empty); zero when not in contact.
   */
  namespace contact
  {
    /// Penalty and Coulomb parameters of a contact pair.
    struct FrictionLaw
    {
      double penalty_normal  = 0; // c_N, N/mm: t_N = c_N <-g_N> (eq. 27)
      double penalty_tangent = 0; // c_T, N/mm: elastic slip (eq. 28)
      double mu_static = 0, mu_dynamic = 0; // Coulomb (eq. 29): stick limit mu_static t_N, sliding force mu_dynamic t_N
    };

    /// The history of one slave node, committed at t_n (revert it with the
    /// rest of the state when a step is cut back; save it in checkpoints).
    template <int dim>
    struct NodeState
    {
      bool                   in_contact = false, sliding = false;
      dealii::Tensor<1, dim> tangential_force; // t_T at t_n (N), global components
    };

    template <int dim>
    struct ContactResult
    {
      bool   in_contact = false, sliding = false, projection_inside = true;
      double gap          = 0; // g_N (mm), < 0 penetration
      double normal_force = 0; // t_N >= 0 (N)
      dealii::Tensor<1, dim> normal;           // master normal n (towards the slave)
      dealii::Tensor<1, dim> tangential_force; // t_T (N), see the sign convention above
      dealii::Tensor<1, dim> slip_increment;   // slip part of the tangential increment (mm)
      double frictional_work = 0;              // t_T . slip over the step (N mm), >= 0
      std::vector<double>        xi;           // master parametric coordinates of the projection (empty for a tool)
      dealii::Vector<double>     residual;     // [slave (dim), master node 0 (dim), ...]
      dealii::FullMatrix<double> tangent;      // d residual / d current coordinates, same ordering
      NodeState<dim>             new_state;    // the state to commit if the step is accepted
    };

    /**
     * Whether face @p face of a (non-inverted) deal.II cell, with its vertices
     * in the order cell->vertex(GeometryInfo<dim>::face_to_cell_vertices(face, v)),
     * is a master whose normal n points out of the cell: true for faces 0 and
     * 3 in 2D, for the odd faces in 3D. Otherwise reverse the two vertices
     * (2D) or swap vertices 1 and 2 (3D) before calling node_to_segment().
     */
    template <int dim>
    bool face_order_gives_outward_normal(unsigned int face);

    /**
     * The three contact elements (each documented at its value-returning form below) evaluated into @p result, whose storage is
     * reused (the assembly keeps one per kind): once it has held a result of
     * this size, a residual-only evaluation allocates nothing. The master's
     * dim == 2 ? 2 : 4 nodes are given as arrays; the tool by its translations
     * u(t), u(t_old), evaluated once per assembly (muparser, ~250
     * instructions each). ContactResult::tangent is left as it was when
     * @p tangent is false.
     */
    template <int dim>
    void node_to_segment(ContactResult<dim>       &result,
                         const dealii::Point<dim> &slave,
                         const dealii::Point<dim> &slave_old,
                         const dealii::Point<dim> *master,
                         const dealii::Point<dim> *master_old,
                         const NodeState<dim>     &state,
                         const FrictionLaw        &law,
                         bool                      tangent);
    template <int dim>
    void node_to_vertex(ContactResult<dim>       &result,
                        const dealii::Point<dim> &slave,
                        const dealii::Point<dim> &slave_old,
                        const dealii::Point<dim> &vertex,
                        const dealii::Point<dim> &vertex_old,
                        const NodeState<dim>     &state,
                        const FrictionLaw        &law,
                        bool                      tangent);
    template <int dim>
    void node_to_tool(ContactResult<dim>           &result,
                      const dealii::Point<dim>     &slave,
                      const dealii::Point<dim>     &slave_old,
                      const RigidTool<dim>         &tool,
                      const dealii::Tensor<1, dim> &tool_displacement,
                      const dealii::Tensor<1, dim> &tool_displacement_old,
                      const NodeState<dim>         &state,
                      const FrictionLaw            &law,
                      bool                          tangent);

    /**
     * Slave node against a deformable master: a straight segment of 2 nodes
     * (2D) or a bilinear facet of 4 nodes (3D), see the conventions above.
     * @p tangent: also compute ContactResult::tangent.
     */
    template <int dim>
    ContactResult<dim> node_to_segment(const dealii::Point<dim>              &slave,
                                       const dealii::Point<dim>              &slave_old,
                                       const std::vector<dealii::Point<dim>> &master,
                                       const std::vector<dealii::Point<dim>> &master_old,
                                       const NodeState<dim>                  &state,
                                       const FrictionLaw                     &law,
                                       const bool                             tangent)
    {
      const unsigned int n_master = dim == 2 ? 2 : 4;
      AssertThrow(master.size() == n_master && master_old.size() == n_master,
                  dealii::ExcMessage("node_to_segment: the master needs " + std::to_string(n_master) +
                                     " nodes (2D: a segment, 3D: a bilinear facet)"));
      ContactResult<dim> result;
      node_to_segment(result, slave, slave_old, master.data(), master_old.data(), state, law, tangent);
      return result;
    }

    /**
     * Slave node behind a concave corner of a deformable master, in the region
     * below the corner's vertex where it projects into neither face (the
     * caller detects it): the closest master point is the vertex, the normal
     * n = (x_v − x_s)/|x_v − x_s| and the gap −|x_v − x_s|, continuous with
     * node_to_segment() on both faces at the region's edges. Friction as
     * above, relative to the vertex. Residual and tangent ordered
     * [slave (dim), vertex (dim)].
     */
    template <int dim>
    ContactResult<dim> node_to_vertex(const dealii::Point<dim> &slave,
                                      const dealii::Point<dim> &slave_old,
                                      const dealii::Point<dim> &vertex,
                                      const dealii::Point<dim> &vertex_old,
                                      const NodeState<dim>     &state,
                                      const FrictionLaw        &law,
                                      const bool                tangent)
    {
      ContactResult<dim> result;
      node_to_vertex(result, slave, slave_old, vertex, vertex_old, state, law, tangent);
      return result;
    }

    /**
     * Slave node against a rigid tool at time @p t (the step being from
     * @p t_old): gap and normal from RigidTool::project(), the tangential
     * increment relative to the tool's translation. The residual and tangent
     * have only the slave's dim components; projection_inside is always true.
     */
    template <int dim>
    ContactResult<dim> node_to_tool(const dealii::Point<dim> &slave,
                                    const dealii::Point<dim> &slave_old,
                                    const RigidTool<dim>     &tool,
                                    const double              t,
                                    const double              t_old,
                                    const NodeState<dim>     &state,
                                    const FrictionLaw        &law,
                                    const bool                tangent)
    {
      ContactResult<dim> result;
      node_to_tool(result, slave, slave_old, tool, tool.displacement(t), tool.displacement(t_old), state,
                   law, tangent);
      return result;
    }
  } // namespace contact
} // namespace anvil
