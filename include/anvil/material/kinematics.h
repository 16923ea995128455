#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <anvil/material/material_point.h>
#include <anvil/material/objective_rates.h>

#include <array>
#include <utility>

namespace anvil
{
  /**
   * Incremental kinematics of one quadrature point over [t_n, t_n+1]
   * (Hughes & Winget 1980), the strain measure behind the incrementally
   * objective update of eq. (9):
   *
   *   F_½ = ½(F + F_n),  ΔL = (F − F_n) F_½⁻¹   (gradient of Δu at the mid-point),
   *   Δω = skew ΔL,  ΔR = (I − ½Δω)⁻¹ (I + ½Δω),
   *   Δε = R_h sym(ΔL) R_hᵀ with the half-step rotation R_h = (I − ¼Δω)⁻¹ (I + ¼Δω).
   *
   * σ_n+1 = ΔR σ_n ΔRᵀ + H : Δε then integrates the Jaumann rate with
   * second-order accuracy (without R_h, the unrotated increment makes it first
   * order: an error of about ½ G γ Δγ in simple shear).
   *
   * A rigid rotation of any angle below 180° gives Δε = 0 and ΔR equal to that
   * rotation exactly (ΔR is the Cayley transform of ½Δω); a sequence of small
   * increments integrates the Jaumann rate with second-order accuracy.
   *
   * F is 3x3 always: plane strain embeds the 2x2 gradient with F₃₃ = 1.
   *
   * Other objective rates (objective_rates.h) change only Δω and R_h:
   *  - logarithmic: Δω = Ω^log Δt, the log spin at F_½ (Xiao et al. 1997),
   *    with the same Cayley transforms as above;
   *  - Green–Naghdi: ΔR = R_n+1 R_nᵀ and R_h = R_n+1 R_½ᵀ from the polar
   *    rotations of F, F_n and F_½ (total F: the reference is F = I). In the
   *    frame of R, σ̂ = Rᵀσ R, this is the mid-point rule for dσ̂/dt = H : RᵀDR.
   */
  /// What IncrementalKinematics::reinit() computes beyond the increment
  /// (ΔL, F_½⁻¹, Δε, ΔR, R_h): bits, like MaterialRequest.
  enum KinematicsUpdate : unsigned int
  {
    kinematics_increment = 0,
    kinematics_inverse   = 1, // J and F⁻¹ (first_piola_stress, first_piola_tangent)
    kinematics_tangent   = 2, // A⁻¹ and A_h⁻¹ (cauchy_tangent)
    /// Jaumann with F and F_n of the form [2x2, 0; 0, F₃₃] (plane strain,
    /// axisymmetric): the same quantities by 2x2 formulas. Without this
    /// bit the general 3x3 path (tests compare the two).
    kinematics_planar_path = 4,
    kinematics_all         = 7
  };

  struct IncrementalKinematics
  {
    /// @p what: KinematicsUpdate bits; the quantities not asked for keep
    /// their previous values.
    void reinit(const dealii::Tensor<2, 3> &F, const dealii::Tensor<2, 3> &F_old,
                ObjectiveRate rate = ObjectiveRate::jaumann,
                unsigned int  what = kinematics_all);

    ObjectiveRate                 rate = ObjectiveRate::jaumann;
    /// Set by the 2x2 path (kinematics_planar_path): cauchy_tangent takes its
    /// planar form (planar_tangent.cc).
    bool                          planar = false;
    dealii::Tensor<2, 3>          F, F_old, F_inv, F_half_inv, dL, A_inv, A_half_inv, half_rotation;
    double                        J = 1.;
    /// sym ΔL on the mid-point configuration.
    dealii::SymmetricTensor<2, 3> mid_strain;
    /// R_h sym(ΔL) R_hᵀ: the mid-point strain increment carried to t_n+1.
    dealii::SymmetricTensor<2, 3> strain_increment;
    dealii::Tensor<2, 3>          rotation_increment;

  private:
    void reinit_planar(unsigned int what);
    /// Every tensor above is zero outside the [2x2, 0; 0, (2,2)] pattern
    /// (the planar path wrote last): reinit_planar() writes the block only.
    bool off_block_zero = false;
  };

  /**
   * The first Piola–Kirchhoff stress P = J σ F⁻ᵀ, whose divergence over the
   * reference mesh equals the divergence of σ over the current one: the
   * residual ∫ σ : ∇ₓδv dv of the updated-Lagrangian form is evaluated as
   * ∫ P : ∇_X δv dV without moving the mesh.
   */
  dealii::Tensor<2, 3> first_piola_stress(const IncrementalKinematics          &kin,
                                          const dealii::SymmetricTensor<2, 3> &cauchy);

  /**
   * The exact derivative A = ∂P/∂F (only the in-plane block for dim = 2) of
   * the discrete update above, given the material's ∂σ/∂Δε and ∂σ/∂σ̃_n:
   *
   *   δΔL = (I − ½ΔL) δF F_½⁻¹,   δΔR = ½ A⁻¹ skew(δΔL) (I + ΔR),
   *   δΔε = δ(R_h sym ΔL R_hᵀ),   δR_h = ¼ A_h⁻¹ skew(δΔL) (I + R_h),
   *   δσ̃  = δΔR σ_n ΔRᵀ + ΔR σ_n δΔRᵀ,
   *   δσ  = C_alg : sym(δΔL) + S : δσ̃,
   *   δP  = J [ tr(δF F⁻¹) σ F⁻ᵀ + δσ F⁻ᵀ − σ F⁻ᵀ δFᵀ F⁻ᵀ ].
   *
   * Consistent with the residual, so Newton converges quadratically.
   */
  template <int dim>
  dealii::Tensor<4, dim> first_piola_tangent(const IncrementalKinematics          &kin,
                                             const dealii::SymmetricTensor<2, 3> &stress_old,
                                             const MaterialResponse              &response);

  /// The unit directions δF = e_k ⊗ e_L a formulation needs, as (k, L).
  struct TangentDirections
  {
    unsigned int                                      n = 0;
    std::array<std::pair<unsigned int, unsigned int>, 9> kl;
    /// dim x dim in-plane directions, plus (2, 2) for the hoop strain if @p hoop.
    static TangentDirections in_plane(unsigned int dim, bool hoop);
  };

  /// δσ = C : δΔε + S : δσ̃ of @p response, dense or factored (FactoredTangent).
  inline dealii::SymmetricTensor<2, 3>
  contract_material_tangent(const MaterialResponse              &response,
                            const dealii::SymmetricTensor<2, 3> &deps,
                            const dealii::SymmetricTensor<2, 3> &drot)
  {
    if (response.factored.active)
      {
        dealii::SymmetricTensor<2, 3> ds;
        double                       *s = ds.begin_raw();
        response.factored.add_tangent(deps.begin_raw(), s);
        if (response.sensitivity_is_identity)
          ds += drot;
        else
          response.factored.add_sensitivity(drot.begin_raw(), s);
        return ds;
      }
    dealii::SymmetricTensor<2, 3> ds = response.tangent * deps;
    if (response.sensitivity_is_identity)
      ds += drot;
    else
      ds += response.rotated_stress_sensitivity * drot;
    return ds;
  }

  /**
   * δσ of the incremental update for each unit direction δF = e_k ⊗ e_L of
   * @p directions (F_n fixed), written to @p dsigma[0..n): the Cauchy part of
   * the linearisation above, from which the mechanics builds δP for its
   * element formulation (standard, F-bar, axisymmetric).
   */
  void cauchy_tangent(const IncrementalKinematics          &kin,
                      const dealii::SymmetricTensor<2, 3> &stress_old,
                      const MaterialResponse              &response,
                      const TangentDirections             &directions,
                      dealii::SymmetricTensor<2, 3>       *dsigma);

  /**
   * cauchy_tangent for the Green–Naghdi and logarithmic rates: δΔε and δΔR
   * by central differences of the kinematics alone (step 1e-6 in F, error
   * ~1e-10 relative, enough for quadratic Newton), chained exactly with the
   * material's C_alg and S as above. The polar decomposition's and the log
   * spin's eigen-derivatives are not worth their code for the gain.
   */
  void rate_cauchy_tangent(const IncrementalKinematics          &kin,
                           const dealii::SymmetricTensor<2, 3> &stress_old,
                           const MaterialResponse              &response,
                           const TangentDirections             &directions,
                           dealii::SymmetricTensor<2, 3>       *dsigma);

  /// cauchy_tangent for IncrementalKinematics::planar (Jaumann, F = [F_2x2,
  /// 0; 0, F₃₃]): the same δσ with the vectors' zero components left out.
  void planar_cauchy_tangent(const IncrementalKinematics          &kin,
                             const dealii::SymmetricTensor<2, 3> &stress_old,
                             const MaterialResponse              &response,
                             const TangentDirections             &directions,
                             dealii::SymmetricTensor<2, 3>       *dsigma);

  /// Embed a dim x dim tensor in 3x3 (identity in the missing directions for F).
  template <int dim>
  dealii::Tensor<2, 3> embed(const dealii::Tensor<2, dim> &t, double out_of_plane);
} // namespace anvil
