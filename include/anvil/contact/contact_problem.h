#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <anvil/contact/contact_element.h>
#include <anvil/contact/rigid_tool.h>
#include <anvil/contact/self_contact.h>
#include <anvil/core/heat_exchange.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;
  template <int dim>
  class Geometry;

  /**
   * The contact pairs of a scene (seed §3): node-to-segment (2D) or
   * node-to-facet (3D) penalty contact with Coulomb friction between named
   * boundaries, or between a named boundary and a rigid tool.
   *
   *   subsection Contact
   *     set Pairs = sliding
   *     set Tools = floor
   *     subsection sliding
   *       set Slave  = upper_bottom      # a boundary: its nodes are the slaves
   *       set Master = lower_top         # a boundary (its faces) or a tool
   *       set Penalty normal = 1e3       # c_N, N/mm (per node) or N/mm^3 (per area)
   *       ...
   *     end
   *     subsection floor
   *       set Type = plane ...           # RigidTool
   *     end
   *   end
   *
   * Parallel: the surfaces' topology (nodes with their displacement dofs and
   * reference positions, faces) is gathered on every process once; at every
   * evaluation the current and old displacements of the surface nodes are
   * summed over the processes, and each process evaluates every P-th node of
   * each surface, whatever the cells' partition. Node numbers follow the reference coordinates, so
   * they do not depend on the partition (checkpoints may change it).
   *
   * Search: per pair, an R-tree of the master faces' bounding boxes (current
   * configuration); a slave node is tested against the faces whose box,
   * enlarged by half the largest face, contains it: O(n log n).
   *
   * Linearization: the elements' exact tangents (contact_element.h); the
   * tributary area of a per-area penalty is taken at the start of the step
   * (held over the step), so the tangent stays exact.
   */
  template <int dim>
  class ContactProblem
  {
  public:
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    struct Pair
    {
      std::string                             name;
      std::string                             slave_name, master_name; // as written in the scene
      std::vector<dealii::types::boundary_id> slaves, masters;         // sorted; masters empty for a tool
      int                                     tool     = -1; // index into tools, or -1
      bool                                    two_pass = false;
      /// Self-contact: Slave and Master are the same boundaries. Every node is
      /// a slave of the faces across the fold, so one loop over the nodes is
      /// already both passes (two-pass: half penalties, as between bodies).
      bool                                    self     = false;
      bool                                    per_area = false;
      /// 2D: the taper beyond a free end of the master surface, in lengths of
      /// its end segment, in 3D beyond a free facet edge (free_end.h); 0: sharp.
      double                                  end_taper = 0.05;
      contact::FrictionLaw                    law;
      // Thermal contact (eq. 30–34).
      double conductance = 0, hardness = 1, exponent = 1, slave_share = 0.5;
      bool   frictional_heating = true; // false: the frictional power is not heat (seed §4.3, case 2)
      /// Loops over the slave nodes: two for a two-pass pair between distinct boundaries.
      unsigned int passes() const { return two_pass && !self ? 2u : 1u; }
      /// Penalty factor: a two-pass pair shares the contact between its passes.
      double penalty_share() const { return two_pass ? 0.5 : 1.; }
    };

    /// The totals of one pair over the committed steps (or at the last commit).
    struct PairTotals
    {
      dealii::Tensor<1, dim> force;                 // contact force on the Slave body, N (last commit; with two passes the reverse pass's reaction)
      double                 normal = 0, tangential = 0; // sums of t_N and |t_T| over the nodes, N
      double                 friction_work   = 0;            // accumulated, N mm
      double                 max_penetration = 0;            // at the last commit, mm
      double                 heat_exchanged = 0; // accumulated conduction slave -> master (eq. 30), mJ
      double                 friction_heat  = 0; // accumulated frictional heat into the bodies (eq. 31-33), mJ
      unsigned int           active = 0, sliding = 0;        // nodes at the last commit
    };

    /// What an element adds: its dofs, r (internal-force convention) and dr/du.
    using Adder = std::function<void(const std::vector<dealii::types::global_dof_index> &,
                                     const dealii::Vector<double> &,
                                     const dealii::FullMatrix<double> *)>;

    /// Declares Contact/<pair> and Contact/<tool> for the names of pass one.
    static void declare_parameters(dealii::ParameterHandler       &prm,
                                   const std::vector<std::string> &pair_names,
                                   const std::vector<std::string> &tool_names);
    /// Reads them; boundary names resolve through @p geometry.
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene,
                          const Geometry<dim> &geometry);

    bool empty() const { return pairs.empty(); }
    const std::vector<Pair> &get_pairs() const { return pairs; }

    /// Gather the surfaces (collective). @p axisymmetric: areas carry 2πr.
    void setup(const dealii::DoFHandler<dim> &dof_handler, bool axisymmetric);
    /**
     * Record which surface dofs are constrained (Dirichlet, hanging), as the
     * owners know them (collective): a process adding an element whose
     * master node it does not even see as a ghost must condense such dofs.
     */
    void set_constrained(const std::function<bool(dealii::types::global_dof_index)> &owned_and_constrained);
    /// Every displacement dof of the contact surfaces (after setup()).
    dealii::IndexSet surface_dofs() const;
    /// The surface dofs their owners constrain.
    const std::set<dealii::types::global_dof_index> &constrained_dofs() const { return constrained; }

    /// The step [t_old, t_new] about to be solved; @p u_old the committed displacement.
    void begin_step(double t_old, double t_new, const Vector &u_old_ghosted);

    /**
     * Evaluate every slave node this process owns at the displacement @p u
     * (ghosted) and pass each active element to @p add. Returns false
     * (on every process) if an element coupled dofs that are not yet in the
     * matrix's sparsity: call couplings() and rebuild, then assemble again.
     */
    bool assemble(const Vector &u_ghosted, bool with_matrix, const Adder &add);

    /**
     * Dof groups that may couple in this step (each group all-to-all), for
     * the matrix sparsity: the candidates of the search, enlarged. Rigid
     * tools add nothing (a node couples only with itself).
     */
    std::vector<std::vector<dealii::types::global_dof_index>> couplings() const;
    /// Whether couplings() grew since the last call to it (collective).
    bool couplings_changed() const;
    /// How often couplings() was asked for: the matrix pattern was built anew
    /// (the first time included; summary.json's contact/pattern_rebuilds).
    unsigned int pattern_rebuilds() const { return pattern_rebuild_count; }

    /// Accept the last assemble() (histories, work); collective.
    void commit();
    /// Largest penetration of the last assemble() (mm, all processes).
    double last_max_penetration() const { return trial_max_penetration; }
    /// Contact/Maximum penetration (mm), resolved at setup.
    double maximum_penetration() const { return penetration_limit; }

    const std::vector<PairTotals> &totals() const { return pair_totals; }

    // ------------------------------------------------------------- heat
    /// Whether any pair exchanges heat (a conductance or friction).
    bool has_heat() const;
    /// Map the surface nodes to the temperature dofs (collective).
    void setup_heat(const dealii::DoFHandler<dim> &thermal_dofs);
    /**
     * Freeze the step's exchange from the last converged mechanics
     * (collective): per slave node in contact, the conductance
     * h A = h₀ (p/H)^e A (eq. 34, p = t_N/A, A its tributary area) to the
     * master point (or tool) below it, and the frictional power
     * D = t_T · slip / Δt (eq. 31), the slave side receiving the share given
     * by the relative effusivity (eq. 32–33) — none while sticking.
     */
    void prepare_heat(double time_step);
    /// The exchange as the thermal problem applies it (eq. 30–33).
    HeatExchange heat_exchange(const std::function<bool(dealii::types::global_dof_index)> &is_constrained);
    /**
     * For a Newton over both fields (coupling/monolithic.cc): for every slave
     * node and master face that may touch in this step (this process's
     * slave nodes; the step's candidates, not every pair the slide allowed), the displacement dofs its heat exchange depends on — the
     * node, the face's nodes (pressure, slip, projection) and the node's
     * neighbours on its surface (its area) — in @p u_columns, and the
     * temperature dofs it writes (the node, the face's nodes) in @p T_rows.
     * A tool's exchange writes the slave node only, within its cells: none.
     */
    void heat_links(std::vector<std::vector<dealii::types::global_dof_index>> &u_columns,
                    std::vector<std::vector<dealii::types::global_dof_index>> &T_rows) const;
    /**
     * ∂f/∂T of the exchange prepared last (eq. 30, h A frozen), f the heat
     * problem's right-hand side, as (row, column, value) to @p add: the rows
     * this process owns and that @p is_constrained does not name.
     */
    void exchange_tangent(
      const std::function<bool(dealii::types::global_dof_index)> &is_constrained,
      const std::function<void(dealii::types::global_dof_index, dealii::types::global_dof_index, double)>
        &add) const;
    /**
     * After an accepted thermal phase: heat exchanged over the step
     * (trapezoidal in T), friction heat; returns the heat that entered the
     * bodies from the contact: friction heat plus what rigid tools gave (mJ).
     */
    double account_heat(const Vector &T_old, const Vector &T_new, double time_step);

    /// Per-node results of the last commit, for output (this process's slave nodes).
    struct NodeOutput
    {
      dealii::Point<dim> position;          // current, mm
      double             pressure = 0;       // t_N / A, MPa
      double             gap = 0, slip = 0;  // mm (slip: this step's)
      double             friction_power = 0; // D = t_T . slip / dt, mW (per node)
      double             conductance = 0;    // h = h0 (p/H)^e, mW/(mm^2 K)
      double             heat_flux   = 0;    // conducted from the slave to the master, mW/mm^2 (last step)
      int                status = 0;         // 0 open, 1 stick, 2 slip
      unsigned int       pair   = 0;
    };
    std::vector<NodeOutput> node_outputs() const;

    /// Checkpoint: every committed node state (all processes take part; the
    /// stream is written on, or read by, every process alike).
    void save(std::ostream &out) const;
    void load(std::istream &in);

  private:
    struct Face
    {
      std::vector<unsigned int>  nodes; // ordered: the normal points out of the body
      dealii::types::boundary_id boundary;
    };
    struct Surface // the faces and nodes of one or several boundaries
    {
      std::set<dealii::types::boundary_id> boundaries;
      std::vector<unsigned int>            faces, nodes;
      bool has(const Face &f) const { return boundaries.count(f.boundary) > 0; }
    };
    /// The two sides of pair p (0 slave, 1 master; the master empty for a tool).
    const Surface &side(unsigned int p, unsigned int s) const { return pair_sides[p][s]; }
    /// The surface a pass's slave nodes / master faces lie on.
    const Surface &slave_side(unsigned int p, unsigned int pass) const { return side(p, pass == 0 ? 0 : 1); }
    const Surface &master_side(unsigned int p, unsigned int pass) const { return side(p, pass == 0 ? 1 : 0); }
    /// Whether @p face may be a master of @p node in pair @p p at the positions @p x
    /// (self-contact: not the node's own surface next to it, self_contact.h).
    bool may_touch(unsigned int p, unsigned int node, unsigned int face,
                   const std::vector<dealii::Point<dim>> &x) const;
    /// Among the (face, end) pairs a node lies behind and beyond, one whose end
    /// vertex another shares (the node is below a concave corner); face -1: none.
    std::pair<int, unsigned int>
    concave_corner(const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end) const;
    /// The closest master face of pair @p p (among @p candidates) that slave node
    /// @p n projects into (its element, no tangent, in @p result), or -1; the
    /// (face, end) pairs the node lies behind and beyond in @p beyond_end (3D:
    /// the facets it lies behind and outside of, end 0).
    int closest_face(unsigned int p, unsigned int n, const unsigned int *candidates,
                     unsigned int n_candidates,
                     const std::vector<dealii::Point<dim>> &x, const contact::NodeState<dim> &state,
                     const contact::FrictionLaw &law, contact::ContactResult<dim> &result,
                     std::vector<std::pair<unsigned int, unsigned int>> &beyond_end) const;
    /// Among @p beyond_end, an end segment at a free end of the master
    /// surface that carries node @p n (free_end_contact, closer than
    /// @p best_face's @p result, which it then replaces), or -1; 3D: free_edge_face.
    int free_end_face(unsigned int p, unsigned int pass, unsigned int n,
                      const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end,
                      const std::vector<dealii::Point<dim>> &x, const contact::NodeState<dim> &state,
                      const contact::FrictionLaw &law, bool with_matrix, int best_face,
                      contact::ContactResult<dim> &result) const;
    /// 3D: the same for a free facet edge (free_edge_contact; free_edge_face.cc):
    /// among @p beyond_end's facets, one whose edge the node is beyond borders
    /// no other facet of the master surface.
    int free_edge_face(unsigned int p, unsigned int pass, unsigned int n,
                       const std::vector<std::pair<unsigned int, unsigned int>> &beyond_end,
                       const std::vector<dealii::Point<dim>> &x, const contact::NodeState<dim> &state,
                       const contact::FrictionLaw &law, bool with_matrix, int best_face,
                       contact::ContactResult<dim> &result) const;
    /// Face @p f's nodes at @p x and at t_n.
    void face_positions(unsigned int f, const std::vector<dealii::Point<dim>> &x,
                        std::vector<dealii::Point<dim>> &xm,
                        std::vector<dealii::Point<dim>> &xm_old) const;
    void face_positions(unsigned int f, const std::vector<dealii::Point<dim>> &x,
                        std::array<dealii::Point<dim>, 4> &xm,
                        std::array<dealii::Point<dim>, 4> &xm_old) const;
    /// Candidate master faces of each slave node: those of faces[start[k]],
    /// ..., faces[start[k + 1] − 1] for the k-th node of a list (sorted).
    struct CandidateLists
    {
      std::vector<unsigned int> start, faces;
    };
    /// Node states keyed by (pair, pass, node).
    using Key = std::tuple<unsigned int, unsigned int, unsigned int>;
    struct Trial
    {
      contact::NodeState<dim> state;
      double normal_force = 0, tangential_force = 0, gap = 0, slip = 0, work = 0, area = 0;
      dealii::Tensor<1, dim>  force_on_slave; // normal + tangential, N
      int                     face = -1;      // master face (deformable master)
      dealii::Point<dim>      position;       // current slave position
      dealii::Tensor<1, dim>  normal;         // master normal at the projection
      std::array<double, 4>   weights = {{0, 0, 0, 0}}; // master shape functions at the projection
    };
    /// One slave node of one pass that this process evaluates, for the step:
    /// its tributary area and committed state at t_n, and its last trial.
    struct Slot
    {
      unsigned int            pair = 0, pass = 0, node = 0;
      double                  area = 0;
      contact::NodeState<dim> state;             // committed
      bool                    evaluated = false; // trial from the last assemble()
      Trial                   trial;
      Key key() const { return Key(pair, pass, node); }
    };
    /// A pass's slave nodes this process evaluates: slots[begin, end), their
    /// nodes, and their candidate faces at t_n with the margin of the step.
    struct StepSide
    {
      unsigned int              begin = 0, end = 0;
      std::vector<unsigned int> mine;
      CandidateLists            candidates;
    };
    /// One slave node's heat exchange over a step (gathered on every process).
    struct HeatElement
    {
      unsigned int pair = 0, slave = 0, n_master = 0;
      unsigned int master[4] = {0, 0, 0, 0};
      double       weight[4] = {0, 0, 0, 0};
      int          tool = -1;
      double       hA = 0, power = 0, share = 0.5; // mW/K, mW, slave share of the power
    };
    /// Whether no surface node moved, relative to the common translation, far
    /// enough since t_n that the step's candidate lists could miss a face
    /// (assemble() then filters them instead of searching; contact_evaluation.cc).
    bool near_step_start(const std::vector<dealii::Point<dim>> &x) const;
    /// Slave @p slot (the @p i-th of its pass) against its candidate master
    /// faces: the contact element of the closest face, a free end or a concave
    /// corner, its trial's face and weights, the masters' dofs appended to
    /// @p dofs; @p missing set when the pattern lacks a coupling it needs.
    const contact::ContactResult<dim> &
    evaluate_on_faces(unsigned int p, unsigned int pass, unsigned int i, Slot &slot,
                      const CandidateLists &candidates, const std::vector<dealii::Point<dim>> &x,
                      const contact::FrictionLaw &law, bool with_matrix,
                      std::vector<dealii::types::global_dof_index> &dofs, bool &missing);
    /// setup()'s parts: every process's contact faces as raw numbers (boundary,
    /// body, per vertex its dofs and reference position) gathered on all; the
    /// surface nodes numbered by reference position (independent of the
    /// partition) with faces, surfaces and node_faces; each pair's two sides.
    std::vector<std::vector<double>> gather_surface_faces(const dealii::DoFHandler<dim> &dof_handler) const;
    void number_surfaces(const std::vector<std::vector<double>> &all, const dealii::IndexSet &owned);
    void build_pair_sides();
    std::vector<double> gather_node_values(const Vector &v) const;
    /// The seed's characteristic area of a slave node (§3.1, Fig. 2): (L₁ + L₂)/2 with
    /// L₁, L₂ the projections of its two slave segments on the master's tangent,
    /// each clamped at zero (3D: its facets' quarters projected on the tangent plane;
    /// axisymmetric: each projection's ring share 2π L (2 r_node + r_other)/6).
    double characteristic_area(unsigned int node, const Surface &surface,
                               const dealii::Tensor<1, dim> &normal) const;
    std::vector<dealii::Point<dim>> x_last; // surface nodes at the last assemble()

    void   gather_positions(const Vector &u_ghosted, std::vector<dealii::Point<dim>> &x) const;
    /// node_mine: the k-th node of each surface is evaluated by process k mod P.
    void share_out_nodes();
    double tributary_area(unsigned int node, const Surface &surface,
                          const std::vector<dealii::Point<dim>> &x) const;
    /// Candidate master faces of each of @p slaves: the faces whose bounding
    /// box at @p x, enlarged by @p margin, holds the node (R-tree search).
    void   candidate_faces(const Surface &master, const std::vector<dealii::Point<dim>> &x,
                           double margin, const std::vector<unsigned int> &slaves,
                           CandidateLists &candidates) const;
    /// Whether the box of face @p f at @p x, enlarged by @p margin, holds @p point.
    bool face_box_holds(unsigned int f, const std::vector<dealii::Point<dim>> &x, double margin,
                        const dealii::Point<dim> &point) const;
    /// The same from @p superset, a list that holds every such face
    /// (the step's lists while the surface moved little; see assemble()).
    void   filter_candidates(const CandidateLists &superset, const std::vector<dealii::Point<dim>> &x,
                             double margin, const std::vector<unsigned int> &slaves,
                             CandidateLists &candidates) const;
    /// The R-tree of each master side and margin, kept while its nodes move less
    /// than its slack (contact_problem.cc); reset by setup().
    struct SearchCache;
    mutable std::shared_ptr<SearchCache> search_cache;

    MPI_Comm                            mpi_communicator = MPI_COMM_WORLD;
    std::vector<Pair>                   pairs;
    std::vector<std::unique_ptr<RigidTool<dim>>> tools;
    bool                                axisymmetric = false;
    double                              penetration_limit = 0;
    dealii::types::global_dof_index     n_global_dofs = 0;

    // Gathered topology.
    std::vector<dealii::Point<dim>>                              node_reference;
    std::vector<std::array<dealii::types::global_dof_index, dim>> node_dofs;
    std::vector<bool>                                            node_owned; // x dof locally owned
    std::vector<bool>                                            node_mine;  // evaluated here
    std::set<dealii::types::global_dof_index>                    constrained; // surface dofs
    std::vector<unsigned int>                                    node_body;  // material id
    std::vector<Face>                                            faces;
    std::vector<std::vector<unsigned int>>                       node_faces; // faces of each node
    std::map<dealii::types::boundary_id, Surface>                surfaces;
    std::vector<std::array<Surface, 2>>                          pair_sides;    // per pair: slave, master
    std::vector<contact::SelfContactNeighbourhood>               neighbourhood; // per pair (self-contact only)
    double                                                       largest_face = 0;

    // The step.
    double                          t_old = 0, t_new = 0;
    std::vector<dealii::Point<dim>> x_old;
    // The start of the step before (the couplings' look-ahead, begin_step()).
    double                          t_before = 0;
    std::vector<dealii::Point<dim>> x_before;
    std::vector<StepSide>           step_sides; // per pair and pass: 2 p + pass
    std::vector<Slot>               slots;      // ordered by (pair, pass, node)

    // Scratch of assemble(): kept so that an evaluation allocates nothing.
    CandidateLists                                   scratch_candidates;
    mutable contact::ContactResult<dim>              probe; // closest_face()'s trials
    contact::ContactResult<dim>                      face_result, vertex_result, tool_result;
    std::vector<std::pair<unsigned int, unsigned int>> scratch_beyond_end;
    std::vector<dealii::types::global_dof_index>     scratch_dofs;

    // Histories.
    std::map<Key, contact::NodeState<dim>> committed;
    double                                 trial_max_penetration = 0;
    std::vector<PairTotals>                pair_totals;

    // Sparsity bookkeeping (coupling_margin.cc): the (pair, pass, slave node,
    // face) couplings in the matrix pattern, and those of the current step
    // (the links of the monolithic scheme's colouring: heat_links()); sorted.
    using Coupling = std::array<unsigned int, 4>;
    mutable std::vector<Coupling> allowed, step_allowed;
    mutable bool                  grew                  = false;
    mutable unsigned int          pattern_rebuild_count = 0;
    /// Steps of the surface's last motion the pattern looks ahead (Contact/Pattern look-ahead).
    double look_ahead_steps = 10;
    /// The pattern's couplings when it must grow: the step's, and those its
    /// slave nodes meet over the next look_ahead_steps if they move relative
    /// to the master as in the last step (coupling_margin.cc).
    std::vector<Coupling> look_ahead_couplings() const;
    /// Self-contact's extra normal margin of the pattern, in largest face
    /// lengths (Contact/Self-contact pattern margin; -1: off, the default).
    double self_margin_faces = -1;
    /// look_ahead_couplings() of a self-contact pair @p p: each (node, face)
    /// with its own relative motion (a fold closes normal to the skin).
    template <typename Tree, typename Drift>
    void self_look_ahead(unsigned int p, const StepSide &side, const Tree &tree, const Drift &drift,
                         std::vector<Coupling> &wide) const;
    /// Adds @p c to the sorted @p set; whether it was not there.
    static bool insert_sorted(std::vector<Coupling> &set, const Coupling &c);

    // Heat.
    std::vector<dealii::types::global_dof_index> node_thermal_dof;
    std::vector<bool>                            node_thermal_owned;
    std::vector<HeatElement>                     heat_elements;
    /// Temperature dofs of each slave node and master face that exchanged
    /// heat, ever (sorted; the heat matrix pattern only grows), and whether
    /// the set grew since the heat problem last read it.
    std::set<std::vector<dealii::types::global_dof_index>> heat_couplings;
    bool                                                   heat_couplings_grew = false;
    std::map<std::pair<unsigned int, unsigned int>, double> heat_flux; // (pair, slave) -> Q, mW
  };
} // namespace anvil
