#pragma once

#include <anvil/contact/contact_element.h>

namespace anvil
{
  namespace contact
  {
    /// The default of Contact/<pair>/Free end taper: how far beyond a free end
    /// of a 2D master surface (in lengths of its end segment; in 3D beyond a free
    /// facet edge, in the facet's parameter across it, past the
    /// parameter tolerance of contact_element.cc) a slave still feels the end
    /// segment, its force tapered smoothly to zero there.
    constexpr double default_end_taper = 0.05;
    /// contact_element.cc's parameter tolerance: up to it the end segment acts in full.
    constexpr double end_tolerance = 1e-3;

    /**
     * A slave node behind the line of a 2D master segment and just beyond its
     * end @p end (0 or 1), a vertex no other face of the master surface shares
     * (the end of a skin, e.g. the bottom corner of the tube): the end segment
     * extended, its force times w(d) = 1 − smoothstep((d − tol)/taper), d the
     * distance beyond the end in segment lengths. Without the taper the force
     * drops from c_N |g| to zero as d passes the tolerance, and a node resting
     * there flips in and out of contact at every Newton iteration until the
     * step is cut back (doc/contact.md, "Free ends"). Residual and tangent are
     * ordered as node_to_segment's [slave, master node 0, master node 1]; the
     * tangent includes w's derivative through ξ; xi is ξ on the segment itself
     * (< 0 or > 1). Not in contact (a default result) outside the taper.
     */
    ContactResult<2> free_end_contact(const dealii::Point<2> &xs, const dealii::Point<2> &xs_old,
                                      const std::vector<dealii::Point<2>> &xm,
                                      const std::vector<dealii::Point<2>> &xm_old,
                                      unsigned int end, const NodeState<2> &state,
                                      const FrictionLaw &law, bool with_matrix,
                                      double end_taper = default_end_taper);

    /**
     * The same in 3D: a slave behind the surface of a bilinear master facet
     * and just beyond its edge @p edge (2k + e: the edge ξ_k = e, deal.II's
     * numbering of a quadrilateral's lines), an edge no other facet of the
     * master surface shares, with the other coordinate within the facet: the
     * facet extended across the edge, its force times w(d), d the distance
     * beyond the edge in facet parameters. The tangent includes w's
     * derivative through the closest point (implicit function theorem).
     * Residual and tangent as node_to_segment's [slave, master nodes 0..3];
     * xi is the point projected onto the edge (in [0, 1]², the heat's
     * weights). Not in contact beyond the taper or beyond two edges at once
     * (a free corner is not tapered).
     */
    ContactResult<3> free_edge_contact(const dealii::Point<3> &xs, const dealii::Point<3> &xs_old,
                                       const std::vector<dealii::Point<3>> &xm,
                                       const std::vector<dealii::Point<3>> &xm_old,
                                       unsigned int edge, const NodeState<3> &state,
                                       const FrictionLaw &law, bool with_matrix,
                                       double end_taper = default_end_taper);
  } // namespace contact
} // namespace anvil
