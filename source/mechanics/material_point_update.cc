// The kinematics and the material update at the points of one cell, the
// first step of every cell's assembly (assembly_kernels.h).
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <algorithm>
#include <sstream>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    bool MaterialPointUpdate<dim>::update(const CellIterator<dim> &cell, ScratchData<dim> &scratch,
                                          CopyData &copy) const
    {
      const Formulation<dim> &formulation = *context.formulation;
      const FEValues<dim>    &fe_values   = scratch.fe_values;
      const bool              heat        = context.has_temperature_field();
      if (formulation.f_bar)
        f_bar.evaluate_centre(cell, scratch);
      auto cell_points = (*context.points)[cell];

      MaterialIncrement increment;
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          PointValues       &p     = scratch.points[q];
          const double       R     = formulation.radius(fe_values, q);
          const Tensor<2, 3> F     = formulation.deformation_gradient(fe_values, q, scratch.local_u, R);
          const Tensor<2, 3> F_old =
            formulation.deformation_gradient(fe_values, q, scratch.local_u_old, R);
          const double J = determinant(F);
          if (!(J > 0) || !(determinant(0.5 * (F + F_old)) > 0) || !(scratch.J0 > 0))
            {
              copy.failed = true; // an element inverted
              return false;
            }
          double       beta  = 1;
          Tensor<2, 3> F_mat = F, F_mat_old = F_old; // what the material sees
          if (formulation.f_bar)
            F_mat = f_bar.material_gradient(scratch, F, F_old, beta, F_mat_old);
          IncrementalKinematics &kin = p.kin;
          kin.reinit(F_mat, F_mat_old);
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
              point.update(increment, context.request, response);
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
          p.w         = formulation.weight(fe_values, q, R);
          const double w = p.w;

          // The work of the step: ∫ ½(σ_n + σ_n+1) : Δε dv½ and ∫ Ẇirr Δt dv (eq. 21).
          copy.stress_work[q] = 0.5 * ((response.stress + point.committed_stress()) *
                                       kin.strain_increment) *
                                determinant(0.5 * (F + F_old)) * w;
          copy.plastic_work[q] = response.plastic_work_rate * context.time_step * J * w;
          // Heat sources χẆirr + Ẇthel (eq. 20–22) and the temperature the point ends at.
          (*context.heat_sources)(cell, q) =
            response.plastic_dissipation_rate + response.thermoelastic_heating_rate;
          (*context.thermoelastic_sources)(cell, q) = response.thermoelastic_heating_rate;
          if (heat)
            (*context.material_temperature)(cell, q) =
              increment.temperature +
              (increment.adiabatic ? response.adiabatic_temperature_increment : 0.);
          copy.max_plastic_increment =
            std::max(copy.max_plastic_increment,
                     response.equivalent_plastic_strain - point.committed_equivalent_plastic_strain());
        }
      return true;
    }

    ANVIL_INSTANTIATE_CLASS(MaterialPointUpdate)
  } // namespace MechanicsAssembly
} // namespace anvil
