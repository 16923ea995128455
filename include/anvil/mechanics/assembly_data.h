#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <anvil/core/point_data.h>
#include <anvil/material/material_point.h>
#include <anvil/mechanics/boundary_conditions.h>
#include <anvil/mechanics/element_formulation.h>
#include <anvil/mechanics/reference_values.h>
#include <anvil/mechanics/step_start.h>
#include <anvil/material/kinematics.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * The mechanical assembly as kernels (doc/mechanics.md, "Assembly"): one
   * class per term of the weak form, evaluated cell by cell on the threads of
   * a process with deal.II's WorkStream. A worker fills ScratchData and
   * CopyData for one cell; the copier adds CopyData into the global matrix,
   * vectors and scalars, serially and in cell order, so the result does not
   * depend on the number of threads.
   */
  namespace MechanicsAssembly
  {
    /// Temperatures at the quadrature points of a cell (must be reentrant: threads call it).
    template <int dim>
    using TemperatureField =
      std::function<void(const typename dealii::Triangulation<dim>::active_cell_iterator &,
                         std::vector<double> &T)>;

    /**
     * Everything one assembly pass reads, and the per-point stores it writes
     * (each point belongs to one cell, so threads never share an entry).
     */
    template <int dim>
    struct Context
    {
      const Formulation<dim> *formulation = nullptr;
      bool                    with_matrix = true;
      double                  time        = 0;
      MaterialRequest         request     = request_stress;
      double                  time_step   = 1;
      /// Uniform temperature of a scene without a temperature field, K.
      double                  reference_temperature = 293;

      const dealii::TrilinosWrappers::MPI::Vector *solution = nullptr; // u_{n+1}, ghosted
      const BoundaryConditions<dim> *boundary_conditions = nullptr;
      const TemperatureField<dim>   *temperature_field   = nullptr; // empty function: none
      bool                           adiabatic_split     = false;

      // Dynamics: generalized-α (Chung & Hulbert 1993) and Newmark.
      bool   dynamic = false, lumped_mass = false;
      double alpha_m = 0, alpha_f = 0, newmark_beta = 0.25;
      /// Body force per unit mass ρ g, mm/s² (zero: none).
      dealii::Tensor<1, dim> gravity;
      bool                   body_force = false;

      /// The bodies' material models (the energy audit reads their elastic laws).
      const std::map<dealii::types::material_id, std::shared_ptr<const MaterialModel>> *materials =
        nullptr;
      PointData<MaterialPoint *>                *points                   = nullptr;
      PointData<double>                         *heat_sources             = nullptr;
      PointData<double>                         *thermoelastic_sources    = nullptr;
      PointData<double>                         *plastic_work_rates       = nullptr; // Ẇirr, the audit's
      PointData<double>                         *material_temperature     = nullptr;
      const PointData<double>                   *material_temperature_old = nullptr;
      /// Dynamics: per cell its node mass m_ij = Σ ρ₀ N_i N_j w (n_nodes² entries,
      /// NaN until the first assembly computes it: ρ₀ dV is conserved).
      PointData<double>                         *node_masses              = nullptr;
      /// The points' start-of-step kinematics per cell (null: computed at every update).
      StepStart                                 *step_start               = nullptr;
      /// The update also computes the energy audit's terms (CopyData::audit):
      /// an evaluation whose state may be the one the step commits.
      bool                                       audit                    = false;

      bool has_temperature_field() const { return temperature_field && *temperature_field; }
    };

    /// What the kernels compute at one quadrature point and pass on.
    struct PointValues
    {
      double                R = 1, w = 0; // radius (hoop term), weight dV (2πR dA)
      double                J = 1, beta = 1; // det F; F-bar factor (J₀/J)^α
      dealii::Tensor<2, 3>  F, F_mat;        // true F; what the material sees (F̄)
      IncrementalKinematics kin;             // of F_mat
      MaterialResponse      response;
      const MaterialPoint  *point     = nullptr;
      bool                  adiabatic = false;
    };

    /**
     * Per-thread work space: FEValues and the buffers of one cell. Copies
     * (one per thread) rebuild their FEValues.
     */
    template <int dim>
    struct ScratchData
    {
      ScratchData(const dealii::Mapping<dim>       &mapping,
                  const dealii::FiniteElement<dim> &fe,
                  const dealii::Quadrature<dim>    &quadrature,
                  const dealii::Quadrature<dim - 1> &face_quadrature,
                  dealii::UpdateFlags               cell_flags);
      ScratchData(const ScratchData &other);

      const dealii::UpdateFlags cell_flags;
      dealii::FEValues<dim>     fe_values;      // without ReferenceValues only
      dealii::FEValues<dim>     fe_center;      // the cell centre (F-bar), likewise
      dealii::FEFaceValues<dim> fe_face_values; // follower pressure

      /// The cell's shape functions, JxW and radii (what the kernels read):
      /// ReferenceValues' entry, or fe_values copied into `own_values`.
      ReferenceCellValues       cell;
      std::vector<double> own_values, own_radii;
      /// Points cell at the values of @p c: from @p reference if not null,
      /// else by FEValues (fe_center too if @p centre).
      void reinit(const typename dealii::Triangulation<dim>::active_cell_iterator &c,
                  const ReferenceValues<dim> *reference,
                  const std::vector<unsigned int> &component,
                  bool                             centre,
                  bool                             with_radius);

      /// Dof values of the cell: u_{n+1}, u_n; dynamics v_n, a_n and a_{n+1}.
      std::vector<double> local_u, local_u_old, local_v_old, local_a_old, local_a;
      std::vector<double> T_new; // temperatures at the points (temperature field)
      double              rho = 0; // density of the cell's body (dynamics, gravity)

      // F-bar: the cell centre's J₀ (at t_n+1 and t_n), F₀⁻¹ and tr(F₀⁻¹ ∂F₀/∂u_a).
      double               J0 = 1, J0_old = 1;
      dealii::Tensor<2, 3> F0_inv;
      std::vector<double>  center_trace;

      std::vector<PointValues> points;
      IncrementalKinematics    audit_kin; // the energy audit's true kinematics (F-bar)

      // Stress divergence: G_a, δσ per direction, A = ∂P_c/∂F_d, T0 (F-bar);
      // Gᵀ dense (n_dir x n_dofs) and (A : G_b)ᵀ (n_dir + 1 rows: one spare).
      std::vector<ShapeGradient>                  G;
      std::array<dealii::SymmetricTensor<2, 3>, 9> dsigma;
      std::array<std::array<double, 9>, 9>        A;
      std::array<double, 9>                       T0;
      std::vector<double>                         Gt, AGt;

      std::vector<double>                 node_mass; // inertia: per node pair, work space
      const double *cell_node_mass = nullptr; // inertia: the cell's kept node mass
      std::vector<dealii::Tensor<2, dim>> face_grad_u;
      std::vector<dealii::Tensor<1, dim>> face_u;
      std::vector<dealii::Tensor<1, dim>> face_d_nda; // follower pressure: δ(n da) per column
    };

    /// The energy audit's terms at a point over a step (doc/energy_audit.md), N mm.
    enum AuditTerm : unsigned int
    {
      audit_stress_work,     // σ̄ : Δε dv½, true kinematics (what f_int works with)
      audit_material_work,   // σ̄ : Δε̄ dv½, what the material sees (F̄ with F-bar)
      audit_plastic_work,    // σ̄ : Δεᵖ dv½ (flow rule)
      audit_thermal_work,    // [σ̄ : βΔT I − (W(σ_n, T_n+1) − W(σ_n, T_n))] dv½
      audit_volume_work,     // ½(W_n + W_n+1)(J_n+1 − J_n) dV
      audit_heat_plastic_work, // Ẇirr Δt dv (eq. 21, the heat source's plastic work)
      audit_elastic_energy,  // W(σ_n+1, T_n+1) J dV: the state's energy at the step's end, not a step sum
      n_audit_terms
    };

    /// What one cell adds to the global system, and its per-cell scalars.
    struct CopyData
    {
      CopyData(unsigned int n_dofs, unsigned int n_q_points);

      dealii::FullMatrix<double> matrix;
      dealii::Vector<double>     rhs;      // −R of the cell
      dealii::Vector<double>     internal; // f_int
      dealii::Vector<double>     external; // f_ext
      dealii::Vector<double>     inertia;  // M a_{n+1} (dynamics)
      std::vector<dealii::types::global_dof_index> dof_indices;
      unsigned int cell_index = 0; // the cell's active_cell_index()

      /// Per point, the energy audit's terms of the step (AuditTerm; filled
      /// by MaterialPointUpdate::update() when Context::audit, or by audit()
      /// at commit; summed point by point in cell order).
      std::vector<std::array<double, n_audit_terms>> audit;
      double              max_plastic_increment = 0;

      /// An element inverted or a material point failed (then the rest is not used).
      bool        failed = false;
      std::string failure; // the material point's message, where (empty: inverted)
    };
  } // namespace MechanicsAssembly
} // namespace anvil
