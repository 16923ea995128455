#pragma once

#include <deal.II/dofs/dof_handler.h>

#include <anvil/mechanics/assembly_data.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /*
     * The kernels, one per term of the weak form (doc/mechanics.md):
     *
     *   ∫ P : ∇_X δv dV                       StressDivergence (F-bar and hoop
     *                                          through FBar and Formulation)
     *   − ∫ ρ₀ g · δv dV                       BodyForce
     *   + ∫ p J F⁻ᵀN · δv dA                   FollowerPressure (boundary faces)
     *   + ∫ ρ₀ ã · δv dV, generalized-α        Inertia
     *   + contact elements (seed eq. 27–29)    MechanicalProblem::assemble_contact (serial)
     *
     * MaterialPointUpdate comes first: the kinematics of each point and the
     * material's update, whose results (PointValues) the terms share. Each
     * kernel is const and touches only the scratch and copy data it is given
     * and the per-point entries of its own cell: the worker of one cell may
     * run on any thread.
     */
    template <int dim>
    using CellIterator = typename dealii::DoFHandler<dim>::active_cell_iterator;

    /**
     * F-bar (de Souza Neto et al. 1996; seed sec. 3.1, constant pressure
     * elements): the material sees F̄ = (J₀/J)^α F on the active block, with
     * J₀ the cell centre's dilatation, so isochoric plastic flow does not
     * lock. Its linearisation adds, per direction δF = e_k ⊗ e_L,
     *   δσ̄ = β δσ − α (F⁻¹)_Lk δσ(F̄) + α δσ(F̄) tr(F₀⁻¹ δF₀),
     * the last part coupling every dof through the centre (T0 · center_trace).
     */
    template <int dim>
    class FBar
    {
    public:
      explicit FBar(const Formulation<dim> &formulation)
        : formulation(formulation)
      {}
      /// J₀ at t_n+1 (and at t_n if @p with_old), F₀⁻¹ and tr(F₀⁻¹ ∂F₀/∂u_a) at the cell centre.
      void evaluate_centre(ScratchData<dim> &scratch, bool with_old = true) const;
      /// β = (J₀/J)^α and F̄ (returned), with F̄_n of the old configuration in @p F_mat_old.
      dealii::Tensor<2, 3> material_gradient(const ScratchData<dim>     &scratch,
                                             const dealii::Tensor<2, 3> &F,
                                             const dealii::Tensor<2, 3> &F_old,
                                             double                     &beta,
                                             dealii::Tensor<2, 3>       &F_mat_old) const;
      /// β = (J₀/J)^α and F̄ at t_n+1 only.
      dealii::Tensor<2, 3> material_gradient(const ScratchData<dim>     &scratch,
                                             const dealii::Tensor<2, 3> &F,
                                             double                     &beta) const;
      /// F̄_n = (J₀ₙ/J_n)^α F_n (evaluate_centre() with the old configuration).
      dealii::Tensor<2, 3> old_material_gradient(const ScratchData<dim>     &scratch,
                                                 const dealii::Tensor<2, 3> &F_old) const;
      /// Its root β_n = (J₀ₙ/J_n)^α alone: F̄_n = formulation.bar(F_n, β_n).
      double old_root(const ScratchData<dim> &scratch, const dealii::Tensor<2, 3> &F_old) const;
      /// δσ in the direction F̄ itself: Σ_d F̄_kL δσ_d.
      dealii::SymmetricTensor<2, 3>
      stress_along(const dealii::Tensor<2, 3>                        &F_mat,
                   const std::array<dealii::SymmetricTensor<2, 3>, 9> &dsigma) const;
      /// δσ̄ of direction d = (k, L): β δσ_d − α (F⁻¹)_Lk δσ(F̄) (the centre's part is T0).
      dealii::SymmetricTensor<2, 3>
      stress_derivative(const dealii::SymmetricTensor<2, 3> &dsigma_d,
                        const double                         beta,
                        const double                         F_inv_Lk,
                        const dealii::SymmetricTensor<2, 3> &dsigma_Fbar) const
      {
        return beta * dsigma_d - formulation.alpha * F_inv_Lk * dsigma_Fbar;
      }
      /// T0_c = J α (δσ(F̄) F⁻ᵀ)_c: the part of δP that follows tr(F₀⁻¹ δF₀).
      void centre_coupling(double                               J,
                           const dealii::Tensor<2, 3>          &F_inv_T,
                           const dealii::SymmetricTensor<2, 3> &dsigma_Fbar,
                           std::array<double, 9>               &T0) const;

    private:
      const Formulation<dim> &formulation;
    };

    /**
     * The kinematics and the material update at every point of a cell:
     * F, F_n (hoop stretch if axisymmetric), F̄ (F-bar), the incremental
     * kinematics (Hughes–Winget) and σ = M(σ̃_n, Δε, T); the point's heat
     * sources (χẆirr + Ẇthel, eq. 20–22) and the temperature it ends at;
     * the work of the step (stress work, plastic work eq. 21).
     * False if an element inverted or a point failed (copy.failure says where).
     */
    template <int dim>
    class MaterialPointUpdate
    {
    public:
      explicit MaterialPointUpdate(const Context<dim> &context)
        : context(context)
        , f_bar(*context.formulation)
      {}
      bool update(const CellIterator<dim> &cell, ScratchData<dim> &scratch, CopyData &copy) const;
      /// The energy audit's terms of every point of @p cell (copy.audit) at the
      /// state of the last update() (the same u, scratch's dof values).
      void audit(const CellIterator<dim> &cell, ScratchData<dim> &scratch, CopyData &copy) const;

    private:
      /// The energy audit's terms of point @p q over the step (AuditTerm), after its update
      /// (@p true_kin: work space for the true F's kinematics with F-bar).
      /// (@p kept: model.keeps_last_step(), asked once per cell.)
      void audit_terms(const CellIterator<dim>    &cell,
                       const MaterialModel        &model,
                       bool                        kept,
                       unsigned int                q,
                       const dealii::Tensor<2, 3> &F,
                       const dealii::Tensor<2, 3> &F_old,
                       const PointValues          &p,
                       const MaterialIncrement    &increment,
                       IncrementalKinematics      &true_kin,
                       std::array<double, n_audit_terms> &terms) const;

      const Context<dim> &context;
      const FBar<dim>     f_bar;
    };

    /**
     * ∫ P : ∇_X δv dV, P = J σ F⁻ᵀ (the updated-Lagrangian ∫ σ : ∇ₓδv dv on
     * the reference mesh), and its exact linearisation
     *   δP = J [tr(δF F⁻¹) σF⁻ᵀ + δσ F⁻ᵀ − σF⁻ᵀ δFᵀ F⁻ᵀ]
     * with δσ from the incremental update (kinematics.h), modified by F-bar
     * and by the adiabatic split's ∂σ/∂ln J.
     */
    template <int dim>
    class StressDivergence
    {
    public:
      /// @p planar_kernel false: the general kernel also where the planar one
      /// applies (tests compare the two).
      explicit StressDivergence(const Context<dim> &context, bool planar_kernel = true);
      void assemble(ScratchData<dim> &scratch, CopyData &copy) const;

    private:
      /// assemble() for dim = 2 with the components interleaved (FESystem of
      /// FE_Q^2: dof a has component a mod 2), @p N_DOFS shape functions:
      /// the planar block structure and the sparsity of ∂F/∂u_a at
      /// compile time (stress_divergence.cc).
      template <unsigned int N_DOFS, bool HOOP>
      void assemble_planar(ScratchData<dim> &scratch, CopyData &copy) const;
      /// n_dofs of assemble_planar's layout, 0 if the element has another.
      unsigned int planar_dofs = 0;
      void add_tangent(const PointValues        &p,
                       const dealii::Tensor<2, 3> &F_inv,
                       const dealii::Tensor<2, 3> &F_inv_T,
                       const dealii::Tensor<2, 3> &sigma_FiT,
                       ScratchData<dim>         &scratch,
                       CopyData                 &copy) const;
      const Context<dim> &context;
      const FBar<dim>     f_bar;
    };

    /// ∫ ρ₀ g · δv dV into f_ext (reference configuration: ρ₀ dV is conserved).
    template <int dim>
    class BodyForce
    {
    public:
      explicit BodyForce(const Context<dim> &context)
        : context(context)
      {}
      void assemble(ScratchData<dim> &scratch, CopyData &copy) const;

    private:
      const Context<dim> &context;
    };

    /**
     * Follower pressure: f_ext = −∫ p n da N, n da = J F⁻ᵀ N dA (Nanson); in
     * the axisymmetric case per full ring of the current radius r = R + u_r.
     * The pressure functions' time must be set before the threads start.
     */
    template <int dim>
    class FollowerPressure
    {
    public:
      explicit FollowerPressure(const Context<dim> &context)
        : context(context)
      {}
      void assemble(const CellIterator<dim> &cell, ScratchData<dim> &scratch, CopyData &copy) const;

    private:
      const Context<dim> &context;
    };

    /**
     * Inertia, generalized-α (Chung & Hulbert 1993):
     *   M ã + (1 − α_f) R(u_{n+1}) + α_f R(u_n) = 0,  ã = (1 − α_m) a_{n+1} + α_m a_n,
     * a_{n+1} from u_{n+1} by Newmark. mass() finds the cell's consistent
     * node mass (integrated at its first assembly, then kept) and a_{n+1};
     * assemble() combines it with the static part of the cell (α_f R(u_n) is
     * added globally after the loop).
     */
    template <int dim>
    class Inertia
    {
    public:
      explicit Inertia(const Context<dim> &context)
        : context(context)
      {}
      void mass(const CellIterator<dim> &cell, ScratchData<dim> &scratch) const;
      void assemble(ScratchData<dim> &scratch, CopyData &copy) const;
      /// a_{n+1} = (u − uₙ − Δt vₙ)/(βΔt²) − (½ − β)/β aₙ (Newmark).
      static double newmark_acceleration(double u, double u_old, double v_old, double a_old,
                                         double dt, double beta)
      {
        return (u - u_old - dt * v_old) / (beta * dt * dt) - (0.5 - beta) / beta * a_old;
      }

    private:
      const Context<dim> &context;
    };
  } // namespace MechanicsAssembly
} // namespace anvil
