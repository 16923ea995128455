#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/material/kinematics.h>
#include <anvil/mechanics/reference_values.h>

#include <vector>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /**
     * G_a = ∂F/∂u_a of one shape function at one point, sparse over the
     * formulation's directions δF = e_k ⊗ e_L: the dim in-plane entries of
     * its gradient, and for the radial shape functions of an axisymmetric
     * element the hoop entry N_a/R.
     */
    struct ShapeGradient
    {
      unsigned int n = 0;
      int          c[4]; // direction index (TangentDirections::kl)
      double       v[4];
    };

    /**
     * What is fixed for one mechanical problem: plane strain, axisymmetric or
     * 3D, standard or F-bar, and the δF directions its linearisation needs.
     * Read-only, shared by every thread of an assembly.
     *
     * The axisymmetric hoop term lives here: F₃₃ = 1 + u_r/R, the hoop entry
     * N_a/R of ∂F/∂u_a, and the ring measure 2πR dR dZ.
     */
    template <int dim>
    class Formulation
    {
    public:
      Formulation(const dealii::FiniteElement<dim> &fe, bool axisymmetric, bool f_bar,
                  ObjectiveRate objective_rate = ObjectiveRate::jaumann);

      const bool axisymmetric, f_bar;
      /// Mechanics/Objective rate: how the kinematics rotate the stress.
      const ObjectiveRate objective_rate;
      /// Only the in-plane block of F is active (plane strain: F₃₃ = 1).
      const bool plane_strain;
      /// F-bar exponent: F̄ = (J₀/J)^α F on the active block (α = 1/2 in
      /// plane strain, 1/3 otherwise).
      const double                    alpha;
      const TangentDirections         directions;
      const unsigned int              n_dofs;
      /// Vector component of each shape function, and its node (the scalar
      /// shape function it carries; n_nodes of them).
      std::vector<unsigned int>       component, node;
      unsigned int                    n_nodes = 0;
      /// Index of the direction (k, L) in `directions`, −1 if not used.
      int                             where[3][3];
      /// n_dofs if dim = 2 and dof a has component a mod 2 (FESystem of FE_Q^2)
      /// with 8 or 18 dofs (Q1, Q2): the layout of the fixed-size planar paths; else 0.
      unsigned int                    planar_dofs = 0;

      /// 3x3 F from the in-plane gradient (and the hoop stretch if axisymmetric).
      dealii::Tensor<2, 3> deformation_gradient(const dealii::Tensor<2, dim> &grad_u,
                                                double                        radial_displacement,
                                                double                        radius) const;
      /// F from the cell's dof values @p values, with @p grad ([a][d]) and
      /// @p value ([a]) the shape functions at one point (R: radius for the hoop term).
      dealii::Tensor<2, 3> deformation_gradient(const double              *grad,
                                                const double              *value,
                                                const std::vector<double> &values,
                                                double                     radius) const;
      /// F at point @p q of @p cell.
      dealii::Tensor<2, 3> deformation_gradient(const ReferenceCellValues       &cell,
                                                const unsigned int         q,
                                                const std::vector<double> &values,
                                                const double               radius) const
      {
        return deformation_gradient(cell.grad + q * n_dofs * dim, cell.value + q * n_dofs, values,
                                    radius);
      }
      /// det of the active block of F.
      double active_det(const dealii::Tensor<2, 3> &F) const
      {
        return plane_strain ? F[0][0] * F[1][1] - F[0][1] * F[1][0] : determinant(F);
      }
      /// β F on the active block (F-bar); in plane strain F₃₃ stays 1.
      dealii::Tensor<2, 3> bar(const dealii::Tensor<2, 3> &F, const double beta) const
      {
        dealii::Tensor<2, 3> Fb = beta * F;
        if (plane_strain)
          Fb[2][2] = 1;
        return Fb;
      }
      /// Radius of point @p q (n_q: the centre) for the hoop term (1 when not axisymmetric).
      double radius(const ReferenceCellValues &cell, const unsigned int q) const
      {
        return axisymmetric ? cell.x[q] : 1.;
      }
      /// Integration weight of point @p q: per full ring 2πR in the axisymmetric case.
      double weight(const ReferenceCellValues &cell, const unsigned int q, const double R) const
      {
        return cell.JxW[q] * (axisymmetric ? 2 * dealii::numbers::PI * R : 1.);
      }
      /// G_a = ∂F/∂u_a of shape function @p a at point @p q (hoop entry N_a/R included).
      void shape_gradient(const ReferenceCellValues &cell,
                          unsigned int         a,
                          unsigned int         q,
                          double               R,
                          ShapeGradient       &g) const;
    };
  } // namespace MechanicsAssembly
} // namespace anvil
