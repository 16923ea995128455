#pragma once

// The heat equation's weak form term by term (seed eq. 26; Lethe's
// heat_transfer_assemblers.h in spirit): one small struct per term, each
// evaluating its contribution on one cell or face from a ScratchData that
// the caller has reinit'ed. ThermalProblem's WorkStream workers compose them.
//
//   ∫ ρc Ṫ φᵢ dv + ∫ k(T) ∇T·∇φᵢ dv = ∫ (ρr + χẆirr + Ẇthel) φᵢ dv + ∫ q_in φᵢ da
//
// on the current configuration (ρ dv = ρ₀ dV for the capacity), 2πr on every
// integral when axisymmetric. The semi-discrete form is M Ṫ = f(T, t) =
// −K(T) T + F(T, t); the tangent is A = ∂(K T − F)/∂T.
//
// Bit-identical results with the serial loop these replaced: the point
// formulas keep its floating-point operations in their order (the conduction
// and source integrands are summed before the weight multiplies them), so do
// not "simplify" them without rerunning the before/after comparison.

#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>

#include <anvil/thermal/assembly_data.h>
#include <anvil/thermal/thermal_problem.h>

#include <cmath>
#include <functional>

namespace anvil
{
  namespace thermal
  {
    constexpr double stefan_boltzmann = 5.670374e-11; // mW/(mm² K⁴)

    /// Axisymmetric (dim = 2): every volume and boundary integral carries 2πr,
    /// r = x[0] the current radius; heat flows are per full ring.
    template <int dim>
    inline double ring_factor(const dealii::Point<dim> &x, const bool axisymmetric)
    {
      return axisymmetric ? 2 * dealii::numbers::PI * x[0] : 1.;
    }

    /// Whether the mechanics' @p source is zero at all @p n_points points of
    /// @p cell (or absent): its integrals there are zero, no FEValues needed.
    template <int dim>
    bool zero_on_cell(const typename ThermalProblem<dim>::HeatSource &source,
                      const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
                      unsigned int n_points);

    /// JxW × ring factor at every point of @p fe_values (reinit'ed).
    template <int dim, class FEValuesType>
    void fill_weights(const FEValuesType &fe_values, bool axisymmetric, std::vector<double> &weights);

    /// Heat capacity ρc Ṫ (eq. 26). Mass is conserved, ρ dv = ρ₀ dV: M is
    /// integrated on the reference configuration whatever the current one.
    struct HeatCapacity
    {
      /// M_ij = ∫ ρ₀c φᵢ φⱼ dV (consistent) into copy.matrix, its row sums
      /// (the lumped mass) into copy.row_sums. scratch.fe_values on the reference mapping.
      template <int dim>
      static void cell_matrix(const ScratchData<dim> &scratch, double rho_c, CopyData &copy);

      /// ρc ġ_D per current volume at point q (the capacity per current
      /// volume is ρ₀c dV/dv): the lift of M_fD ġ_D into the free rows, from
      /// ġ at the cell's dofs in scratch.g_dot; fe_reference reinit'ed.
      template <int dim>
      static double dirichlet_rate(const ScratchData<dim> &scratch, unsigned int q, double rho_c,
                                   bool axisymmetric);
    };

    /// Conduction −div q, q = −k(T) ∇T (eq. 26), k(T) = k₀(1 + a(T − T_ref)).
    struct Conduction
    {
      /// −k ∇φᵢ·∇T: the integrand of f.
      template <int dim>
      static double residual(const double k, const dealii::Tensor<1, dim> &grad_phi_i,
                             const dealii::Tensor<1, dim> &grad_T)
      {
        return -k * (grad_phi_i * grad_T);
      }
      /// A_ij += ∫ (k ∇φᵢ·∇φⱼ + k'(T) φⱼ ∇φᵢ·∇T) dv into copy.matrix.
      template <int dim>
      static void cell_tangent(const ScratchData<dim> &scratch, const ThermalMaterial &material,
                               CopyData &copy);
    };

    /// Volume sources: ρr from an expression in x, y(, z), t and the
    /// mechanics' χẆirr + Ẇthel per point (eq. 26), in mW/mm³.
    struct VolumeSource
    {
      /// φᵢ × rate: the integrand of f.
      static double residual(const double phi_i, const double rate) { return phi_i * rate; }

      /**
       * scratch.rate[q] = s − ρc ġ_D with s the expression (time set by the
       * caller) plus the mechanics' source. @p expression and @p mechanical
       * may be null/empty; @p mechanical is called from worker threads, so it
       * must only read (ThermalProblem::set_heat_source says so).
       * @p dirichlet_rho_c > 0: subtract HeatCapacity::dirichlet_rate.
       */
      template <int dim>
      static void cell_rates(ScratchData<dim>                                              &scratch,
                             const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
                             const dealii::FunctionParser<dim>                             *expression,
                             const typename ThermalProblem<dim>::HeatSource                *mechanical,
                             double dirichlet_rho_c, bool axisymmetric);

      /// F_i += ∫ φᵢ rate dv into copy.vector (the sources alone: the fast linear path).
      template <int dim>
      static void cell_load(const ScratchData<dim> &scratch, CopyData &copy);
    };

    /// f_i += ∫ (−k ∇φᵢ·∇T + φᵢ (s − ρc ġ_D)) dv into copy.vector: conduction
    /// and sources summed per point, then weighted (see the note above).
    template <int dim>
    void volume_residual(const ScratchData<dim> &scratch, const ThermalMaterial &material,
                         CopyData &copy);

    // ------------------------------------------------------ boundary terms
    // q_in at a point of a Flux, Convection or Radiation boundary; a
    // Temperature boundary is a constraint (ThermalProblem) and takes none.

    /// Prescribed flux q_in = q̄(x, t) (into the body > 0).
    struct PrescribedFlux
    {
      template <int dim>
      static void add(const typename ThermalBoundaryConditions<dim>::Boundary &b,
                      const dealii::Point<dim> &x, BoundaryFlux &q)
      {
        if (b.flux)
          q.into_body += b.flux->value(x);
      }
    };

    /// Convection q_in = h (T∞ − T).
    struct Convection
    {
      template <int dim>
      static void add(const typename ThermalBoundaryConditions<dim>::Boundary &b,
                      const dealii::Point<dim> &x, const double T, BoundaryFlux &q)
      {
        if (!b.h)
          return;
        const double h = b.h->value(x);
        q.into_body += h * (b.T_convection->value(x) - T);
        q.d_dT -= h;
      }
    };

    /// Radiation q_in = εσ (T∞⁴ − T⁴).
    struct Radiation
    {
      template <int dim>
      static void add(const typename ThermalBoundaryConditions<dim>::Boundary &b,
                      const dealii::Point<dim> &x, const double T, BoundaryFlux &q)
      {
        if (!b.emissivity)
          return;
        const double es = b.emissivity->value(x) * stefan_boltzmann;
        const double Ti = b.T_radiation->value(x);
        q.into_body += es * (Ti * Ti * Ti * Ti - std::pow(T, 4));
        q.d_dT -= 4 * es * std::pow(T, 3);
      }
    };

    /// The boundary terms of face @p face of @p cell: q_in of every kind at
    /// each point, f_i += ∫ φᵢ q_in da into copy.vector and, if @p tangent,
    /// A_ij −= ∫ ∂q_in/∂T φᵢ φⱼ da into copy.matrix. Reinit's scratch.fe_face;
    /// @p T the ghosted temperature, or null where only prescribed fluxes are
    /// integrated (no convection or radiation on @p b).
    template <int dim>
    void boundary_face(ScratchData<dim>                                              &scratch,
                       const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
                       unsigned int face, const typename ThermalBoundaryConditions<dim>::Boundary &b,
                       const dealii::TrilinosWrappers::MPI::Vector *T, bool axisymmetric,
                       bool tangent, CopyData &copy);
  } // namespace thermal
} // namespace anvil
