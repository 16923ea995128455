// The kinematics and the material update at the points of one cell, the
// first step of every cell's assembly (assembly_kernels.h).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    namespace
    {
      /// W = ½ σ : H(T)⁻¹ : σ = p²/2K + s : s/4G, per current volume (MPa = N mm/mm³).
      double elastic_energy_density(const SymmetricTensor<2, 3> &sigma, const double K,
                                    const double G)
      {
        const double p = trace(sigma) / 3;
        const auto   s = deviator(sigma);
        return 0.5 * p * p / K + (s * s) / (4 * G);
      }

      /// det F; of the form [2x2, 0; 0, F₃₃] (plane strain, axisymmetric)
      /// by the nonzero terms of deal.II's cofactor sum, F₀₀(F₁₁F₂₂) −
      /// F₀₁(F₁₀F₂₂): the others are exact zeros, so the bits are the same
      /// (but for the sign of a zero result, which no > 0 test sees).
      double point_determinant(const Tensor<2, 3> &F)
      {
        if (F[0][2] == 0 && F[1][2] == 0 && F[2][0] == 0 && F[2][1] == 0)
          return F[0][0] * (F[1][1] * F[2][2]) - F[0][1] * (F[1][0] * F[2][2]);
        return determinant(F);
      }

      /// σ̄ = ½(ΔR σ_n ΔRᵀ + σ_n+1): the step's stress on the configuration of
      /// Δε (Hughes–Winget; the update's own rotated σ̃_n, doc/energy_audit.md).
      /// On raw arrays, with the sums of deal.II's products and symmetrize().
      SymmetricTensor<2, 3> mean_stress(const IncrementalKinematics  &kin,
                                        const SymmetricTensor<2, 3> &stress_old,
                                        const SymmetricTensor<2, 3> &stress_new)
      {
        const Tensor<2, 3> &R = kin.rotation_increment;
        double              A[3][3], X[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int l = 0; l < 3; ++l)
            A[i][l] = R[i][0] * stress_old[0][l] + R[i][1] * stress_old[1][l] +
                      R[i][2] * stress_old[2][l];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            X[i][j] = A[i][0] * R[j][0] + A[i][1] * R[j][1] + A[i][2] * R[j][2];
        SymmetricTensor<2, 3> s;
        for (unsigned int i = 0; i < 3; ++i)
          {
            s[i][i] = 0.5 * (X[i][i] + stress_new[i][i]);
            for (unsigned int j = i + 1; j < 3; ++j)
              s[i][j] = 0.5 * ((X[i][j] + X[j][i]) * 0.5 + stress_new[i][j]);
          }
        return s;
      }

      bool is_planar(const Tensor<2, 3> &F)
      {
        return F[0][2] == 0 && F[1][2] == 0 && F[2][0] == 0 && F[2][1] == 0;
      }

      bool is_planar(const SymmetricTensor<2, 3> &s) { return s[0][2] == 0 && s[1][2] == 0; }

      /// det(½(F + F_n)), planar ones by their five entries (point_determinant()'s terms).
      double mid_determinant(const Tensor<2, 3> &F, const Tensor<2, 3> &F_old)
      {
        if (!is_planar(F) || !is_planar(F_old))
          return point_determinant(0.5 * (F + F_old));
        const double H00 = 0.5 * (F[0][0] + F_old[0][0]), H01 = 0.5 * (F[0][1] + F_old[0][1]);
        const double H10 = 0.5 * (F[1][0] + F_old[1][0]), H11 = 0.5 * (F[1][1] + F_old[1][1]);
        const double H22 = 0.5 * (F[2][2] + F_old[2][2]);
        return H00 * (H11 * H22) - H01 * (H10 * H22);
      }

      /**
       * σ̄ : Δε over the step on the true F (Hughes–Winget, Jaumann): the
       * numbers of IncrementalKinematics::reinit()'s planar path and
       * mean_stress() where F, F_n and both stresses are [2x2, 0; 0, (2,2)],
       * with the products of their exact zeros left out (the same bits); the
       * general kinematics in @p kin otherwise.
       */
      double true_stress_work(const Tensor<2, 3>          &F,
                              const Tensor<2, 3>          &F_old,
                              const SymmetricTensor<2, 3> &stress_old,
                              const SymmetricTensor<2, 3> &stress_new,
                              const ObjectiveRate          rate,
                              IncrementalKinematics       &kin)
      {
        if (!(rate == ObjectiveRate::jaumann && is_planar(F) && is_planar(F_old) &&
              is_planar(stress_old) && is_planar(stress_new)))
          {
            kin.reinit(F, F_old, rate, kinematics_planar_path);
            return mean_stress(kin, stress_old, stress_new) * kin.strain_increment;
          }
        // ΔL = (F − F_n) F½⁻¹ on the block, and (2,2).
        const double H00 = 0.5 * (F[0][0] + F_old[0][0]), H01 = 0.5 * (F[0][1] + F_old[0][1]);
        const double H10 = 0.5 * (F[1][0] + F_old[1][0]), H11 = 0.5 * (F[1][1] + F_old[1][1]);
        const double H22 = 0.5 * (F[2][2] + F_old[2][2]);
        const double d   = H00 * H11 - H01 * H10;
        const double Hi[2][2] = {{H11 / d, -H01 / d}, {-H10 / d, H00 / d}};
        double       dL[2][2];
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            dL[i][j] = (F[i][0] - F_old[i][0]) * Hi[0][j] + (F[i][1] - F_old[i][1]) * Hi[1][j];
        const double dL22 = (F[2][2] - F_old[2][2]) * (1 / H22);
        // ΔR and R_h: plane rotations by the Cayley transforms of ½Δω and ¼Δω.
        const double s = 0.25 * (dL[0][1] - dL[1][0]);
        const auto plane = [](double (&T)[2][2], const double s) {
          const double c = 2, w = 1 / (1 + s * s);
          T[0][0] = T[1][1] = 1 - c * s * s * w;
          T[0][1]           = c * s * w;
          T[1][0]           = -c * s * w;
        };
        double R[2][2], Q[2][2];
        plane(R, s);
        plane(Q, 0.5 * s);
        // Δε = R_h sym(ΔL) R_hᵀ.
        const double m00 = dL[0][0], m11 = dL[1][1], m01 = 0.5 * (dL[0][1] + dL[1][0]);
        const double M00 = Q[0][0] * m00 + Q[0][1] * m01, M01 = Q[0][0] * m01 + Q[0][1] * m11;
        const double M10 = Q[1][0] * m00 + Q[1][1] * m01, M11 = Q[1][0] * m01 + Q[1][1] * m11;
        SymmetricTensor<2, 3> strain;
        strain[0][0] = M00 * Q[0][0] + M01 * Q[0][1];
        strain[1][1] = M10 * Q[1][0] + M11 * Q[1][1];
        strain[0][1] = 0.5 * ((M00 * Q[1][0] + M01 * Q[1][1]) + (M10 * Q[0][0] + M11 * Q[0][1]));
        strain[2][2] = dL22;
        // σ̄ = ½(ΔR σ_n ΔRᵀ + σ_n+1) (mean_stress()).
        const SymmetricTensor<2, 3> &S = stress_old;
        const double A00 = R[0][0] * S[0][0] + R[0][1] * S[1][0], A01 = R[0][0] * S[0][1] + R[0][1] * S[1][1];
        const double A10 = R[1][0] * S[0][0] + R[1][1] * S[1][0], A11 = R[1][0] * S[0][1] + R[1][1] * S[1][1];
        const double X00 = A00 * R[0][0] + A01 * R[0][1], X01 = A00 * R[1][0] + A01 * R[1][1];
        const double X10 = A10 * R[0][0] + A11 * R[0][1], X11 = A10 * R[1][0] + A11 * R[1][1];
        SymmetricTensor<2, 3> mean;
        mean[0][0] = 0.5 * (X00 + stress_new[0][0]);
        mean[1][1] = 0.5 * (X11 + stress_new[1][1]);
        mean[2][2] = 0.5 * (S[2][2] + stress_new[2][2]);
        mean[0][1] = 0.5 * ((X01 + X10) * 0.5 + stress_new[0][1]);
        return mean * strain;
      }
    } // namespace

    template <int dim>
    void MaterialPointUpdate<dim>::audit_terms(const CellIterator<dim>   &cell,
                                               const MaterialModel       &model,
                                               const bool                 kept_step,
                                               const unsigned int         q,
                                               const Tensor<2, 3>        &F,
                                               const Tensor<2, 3>        &F_old,
                                               const PointValues         &p,
                                               const MaterialIncrement   &increment,
                                               IncrementalKinematics     &true_kin,
                                               std::array<double, n_audit_terms> &terms) const
    {
      const MaterialPoint         &point   = *p.point;
      const MaterialResponse      &r       = p.response;
      const SymmetricTensor<2, 3> &sigma_n = point.committed_stress();
      // dv½ = det(½(F + F_n)) dV: the mid configuration Δε lives on.
      const double dv_half = mid_determinant(F, F_old) * p.w;

      // The material's stress power over the step, on its own kinematics (F̄ with F-bar):
      // a point that kept σ̄ and Δε of its last update (MaterialModel::last_step()),
      // the same numbers as from its kinematics here.
      const SymmetricTensor<2, 3> *mean = nullptr, *strain = nullptr;
      SymmetricTensor<2, 3>        mean_here;
      if (kept_step)
        model.last_step(point, mean, strain);
      else
        {
          mean_here = mean_stress(p.kin, sigma_n, r.stress);
          mean      = &mean_here;
          strain    = &p.kin.strain_increment;
        }
      const SymmetricTensor<2, 3> &sigma_bar = *mean;
      terms[audit_material_work] = (sigma_bar * *strain) * dv_half;
      // What the internal force works with: the true F (∫ σ : ∇ₓδv dv,
      // stress_divergence.cc): its own Hughes–Winget increment, an independent
      // route to the work the nodes see (doc/energy_audit.md).
      if (context.formulation->f_bar)
        terms[audit_stress_work] =
          true_stress_work(F, F_old, sigma_n, r.stress, context.formulation->objective_rate,
                           true_kin) *
          dv_half;
      else
        terms[audit_stress_work] = terms[audit_material_work];

      // Plastic work from the flow rule alone: Δεᵖ = Δε̄ᵖ (3/2) s_n+1/q_n+1
      // (radial return, eq. 12-16), with the same σ̄ (trapezoidal, like Δε's work).
      terms[audit_plastic_work] = 0;
      const double dp = r.equivalent_plastic_strain - point.committed_equivalent_plastic_strain();
      if (dp > 0)
        {
          const auto   s  = deviator(r.stress);
          const double qn = std::sqrt(1.5 * (s * s));
          if (qn > 0)
            terms[audit_plastic_work] = dp * 1.5 * (sigma_bar * s) / qn * dv_half;
        }

      // Thermal terms: the expansion's work σ̄ : βΔT I and the energy the
      // stress σ_n gains or loses because the moduli change from T_n to T_n+1.
      const double         T_new = context.has_temperature_field() ?
                                     (*context.material_temperature)(cell, q) :
                                     increment.temperature;
      const double T_old = context.has_temperature_field() ?
                             (*context.material_temperature_old)(cell, q) :
                             increment.temperature;
      const double K_new = model.bulk_modulus_at(T_new), G_new = model.shear_modulus_at(T_new);
      // (The same function of the same T where it did not move: two virtual calls fewer.)
      const double K_old = T_old == T_new ? K_new : model.bulk_modulus_at(T_old);
      const double G_old = T_old == T_new ? G_new : model.shear_modulus_at(T_old);
      const double thermal_strain = model.thermal_strain(T_new, T_new - T_old);
      const double W_old_at_old = elastic_energy_density(sigma_n, K_old, G_old);
      // (The same function of the same numbers where the moduli did not move.)
      const double W_old_at_new = K_new == K_old && G_new == G_old ?
                                    W_old_at_old :
                                    elastic_energy_density(sigma_n, K_new, G_new);
      // W_n+1, and the state's energy W J dV at the end of the step from the
      // same p and s : s (compute_step_audit()'s sum, its grouping of the terms).
      const double p_new  = trace(r.stress) / 3;
      const auto   s_new  = deviator(r.stress);
      const double ss_new = s_new * s_new;
      const double W_new  = 0.5 * p_new * p_new / K_new + ss_new / (4 * G_new);
      const double J      = point_determinant(F);
      terms[audit_elastic_energy] =
        0.5 * (p_new * p_new / K_new + ss_new / (2 * G_new)) * J * p.w;
      terms[audit_thermal_work] =
        (trace(sigma_bar) * thermal_strain - (W_old_at_new - W_old_at_old)) * dv_half;
      // The heat source's plastic work Ẇirr Δt dv (eq. 21), reported beside the audit's.
      terms[audit_heat_plastic_work] = r.plastic_work_rate * context.time_step * J * p.w;
      // ∫ W dv changes with the volume alone: d(W J)/dt = J Ẇ + W J tr D.
      terms[audit_volume_work] =
        0.5 * (W_old_at_old + W_new) * (J - point_determinant(F_old)) * p.w;
    }

    template <int dim>
    bool MaterialPointUpdate<dim>::update(const CellIterator<dim> &cell, ScratchData<dim> &scratch,
                                          CopyData &copy) const
    {
      const Formulation<dim> &formulation = *context.formulation;
      const ReferenceCellValues    &ref         = scratch.cell;
      const bool              heat        = context.has_temperature_field();
      // F_n and F̄_n: kept per cell for the step (StepStart), computed by the
      // cell's first update of a step (the same operations: the same bits);
      // at every update where the table is empty (3D: point_setup.cc).
      const std::vector<double> &u_old = scratch.local_u_old;
      PointStart                *kept  = nullptr;
      bool                       have_start = false;
      if (context.step_start && !context.step_start->points.empty())
        {
          const auto key = context.step_start->u_old[cell];
          kept           = context.step_start->points[cell].data();
          have_start     = std::memcmp(key.data(), u_old.data(), key.size() * sizeof(double)) == 0;
          if (!have_start)
            key[0] = std::numeric_limits<double>::quiet_NaN(); // while the points are rewritten
        }
      if (formulation.f_bar)
        f_bar.evaluate_centre(scratch, !have_start);
      auto cell_points = (*context.points)[cell];

      MaterialIncrement    increment;
      PointStart           start;
      // The audit's terms where this state may be the step's last (Context::audit).
      const MaterialModel *model =
        context.audit ? context.materials->at(cell->material_id()).get() : nullptr;
      const bool kept_step = model && model->keeps_last_step();
      // The kernels take the tangent factored where the law gives it (cauchy_tangent).
      const MaterialRequest request = context.request & request_tangent ?
                                        context.request | request_factored_tangent :
                                        context.request;
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          PointValues       &p     = scratch.points[q];
          const double       R     = formulation.radius(ref, q);
          const Tensor<2, 3> F     = formulation.deformation_gradient(ref, q, scratch.local_u, R);
          if (!have_start)
            {
              start.F_old    = formulation.deformation_gradient(ref, q, u_old, R);
              start.beta_old = formulation.f_bar ? f_bar.old_root(scratch, start.F_old) : 1.;
              if (kept)
                kept[q] = start;
            }
          const PointStart  &s0    = have_start ? kept[q] : start;
          const Tensor<2, 3> &F_old = s0.F_old;
          const double J = point_determinant(F);
          if (!(J > 0) || !(point_determinant(0.5 * (F + F_old)) > 0) || !(scratch.J0 > 0))
            {
              copy.failed = true; // an element inverted
              return false;
            }
          double       beta  = 1;
          Tensor<2, 3> F_mat = F; // what the material sees
          const Tensor<2, 3>  F_mat_old = formulation.f_bar ? formulation.bar(F_old, s0.beta_old) : F_old;
          if (formulation.f_bar)
            F_mat = f_bar.material_gradient(scratch, F, beta);
          IncrementalKinematics &kin = p.kin;
          kin.reinit(F_mat, F_mat_old, formulation.objective_rate,
                     kinematics_planar_path | (context.with_matrix ? kinematics_tangent : kinematics_increment));
          increment.strain_increment   = kin.strain_increment;
          increment.rotation_increment = kin.rotation_increment;
          increment.temperature        = heat ? scratch.T_new[q] : context.reference_temperature;
          increment.temperature_increment =
            heat ? scratch.T_new[q] - (*context.material_temperature_old)(cell, q) : 0.;
          increment.adiabatic    = heat && context.adiabatic_split;
          increment.time_step    = context.time_step;
          increment.volume_ratio = J;
          MaterialPoint    &point    = *cell_points[q];
          MaterialResponse &response = p.response;
          try
            {
              response.factored.active = false; // (a response of another law's point)
              point.update(increment, request, response);
            }
          catch (const MaterialPointError &e)
            {
              // Say where; the step is cut back (all ranks learn it).
              std::ostringstream where_text;
              where_text << e.what() << " (material point " << q << " of the cell at "
                         << cell->center() << ", body id " << cell->material_id() << ")";
              copy.failure = where_text.str();
              copy.failed  = true;
              return false;
            }
          p.R         = R;
          p.J         = J;
          p.beta      = beta;
          p.F         = F;
          p.F_mat     = F_mat;
          p.point     = &point;
          p.adiabatic = increment.adiabatic;
          p.w         = formulation.weight(ref, q, R);
          // Heat sources χẆirr + Ẇthel (eq. 20–22) and the temperature the point ends at.
          if (context.heat_sources)
            {
              (*context.heat_sources)(cell, q) =
                response.plastic_dissipation_rate + response.thermoelastic_heating_rate;
              (*context.thermoelastic_sources)(cell, q) = response.thermoelastic_heating_rate;
            }
          if (heat)
            (*context.material_temperature)(cell, q) =
              increment.temperature +
              (increment.adiabatic ? response.adiabatic_temperature_increment : 0.);
          // The energy audit needs the step's last evaluation only: its terms
          // here where that may be this one, else at commit (audit(), from
          // this and the state: the same numbers).
          (*context.plastic_work_rates)(cell, q) = response.plastic_work_rate;
          copy.max_plastic_increment =
            std::max(copy.max_plastic_increment,
                     response.equivalent_plastic_strain - point.committed_equivalent_plastic_strain());
          if (model)
            audit_terms(cell, *model, kept_step, q, F, F_old, p, increment, scratch.audit_kin,
                        copy.audit[q]);
        }
      // Every point's F_n and F̄_n are kept: the key last (an update that
      // failed part-way leaves it unset, and the next one computes them again).
      if (kept && !have_start)
        std::copy(u_old.begin(), u_old.end(), context.step_start->u_old[cell].begin());
      return true;
    }

    template <int dim>
    void MaterialPointUpdate<dim>::audit(const CellIterator<dim> &cell, ScratchData<dim> &scratch,
                                         CopyData &copy) const
    {
      // F of update() at the same u (bit for bit: the same operations), F_n
      // as the step's updates kept it (StepStart, where its key is this u_n),
      // the stresses and plastic strains the points hold from the last
      // update, and the plastic work rate it stored. A law whose points keep
      // what the audit needs of the material's kinematics (F̄ with F-bar:
      // MaterialModel::keeps_last_step()) spares it; else they are computed.
      const Formulation<dim>    &formulation = *context.formulation;
      const ReferenceCellValues &ref         = scratch.cell;
      auto                 cell_points = (*context.points)[cell];
      const MaterialModel &model       = *context.materials->at(cell->material_id());
      const bool           kept_step   = model.keeps_last_step();
      const PointStart *kept = nullptr;
      if (context.step_start && !context.step_start->points.empty())
        {
          const auto key = context.step_start->u_old[cell];
          if (std::memcmp(key.data(), scratch.local_u_old.data(), key.size() * sizeof(double)) == 0)
            kept = context.step_start->points[cell].data();
        }
      // F̄ needs J₀ of the centre; F̄_n comes from the root the step's
      // updates kept (update()'s route), so neither J₀ₙ nor the centre's
      // derivatives (the tangent's) are computed: J₀ by evaluate_centre()'s
      // operations, the same bits.
      if (formulation.f_bar && !kept_step && kept)
        {
          const double R0 = formulation.radius(ref, scratch.points.size());
          scratch.J0      = formulation.active_det(
            formulation.deformation_gradient(ref.centre_grad, ref.centre_value, scratch.local_u, R0));
        }
      else if (formulation.f_bar && !kept_step)
        f_bar.evaluate_centre(scratch);
      MaterialIncrement    increment;
      increment.temperature = context.reference_temperature; // without a temperature field
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          PointValues       &p     = scratch.points[q];
          const double       R     = formulation.radius(ref, q);
          const Tensor<2, 3> F     = formulation.deformation_gradient(ref, q, scratch.local_u, R);
          const Tensor<2, 3> F_old =
            kept ? kept[q].F_old : formulation.deformation_gradient(ref, q, scratch.local_u_old, R);
          if (!kept_step)
            {
              double       beta  = 1;
              Tensor<2, 3> F_mat = F, F_mat_old = F_old;
              if (formulation.f_bar && kept)
                {
                  F_mat_old = formulation.bar(F_old, kept[q].beta_old);
                  F_mat     = f_bar.material_gradient(scratch, F, beta);
                }
              else if (formulation.f_bar)
                F_mat = f_bar.material_gradient(scratch, F, F_old, beta, F_mat_old);
              p.kin.reinit(F_mat, F_mat_old, formulation.objective_rate, kinematics_planar_path);
            }
          MaterialPoint &point                  = *cell_points[q];
          p.response.stress                     = point.stress();
          p.response.equivalent_plastic_strain = point.equivalent_plastic_strain();
          p.response.plastic_work_rate          = (*context.plastic_work_rates)(cell, q);
          p.point = &point;
          p.w     = formulation.weight(ref, q, R);
          audit_terms(cell, model, kept_step, q, F, F_old, p, increment, scratch.audit_kin, copy.audit[q]);
        }
    }

    ANVIL_INSTANTIATE_CLASS(MaterialPointUpdate)
  } // namespace MechanicsAssembly
} // namespace anvil
