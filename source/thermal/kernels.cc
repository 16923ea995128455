// The heat equation's weak-form terms (seed eq. 26) on one cell or face; see
// include/anvil/thermal/kernels.h. The arithmetic of every formula is that of
// the serial loop these came from, in the same order (bit-identical results).
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/numbers.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/kernels.h>

namespace anvil
{
  namespace thermal
  {
    using namespace dealii;

    template <int dim>
    ScratchData<dim>::ScratchData(const Mapping<dim> &mapping, const Mapping<dim> &reference_mapping,
                                  const FiniteElement<dim> &fe, const Quadrature<dim> &quadrature,
                                  const Quadrature<dim - 1> &face_quadrature,
                                  const UpdateFlags cell_flags, const UpdateFlags reference_flags,
                                  const UpdateFlags face_flags)
      : own_mapping()
      , fe_values(mapping, fe, quadrature, cell_flags)
      , fe_reference(reference_mapping, fe, quadrature, reference_flags)
      , fe_face(mapping, fe, face_quadrature, face_flags)
      , weight(quadrature.size())
      , T(quadrature.size())
      , grad_T(quadrature.size())
      , rate(quadrature.size())
      , g_dot(fe.n_dofs_per_cell())
      , face_weight(face_quadrature.size())
      , face_T(face_quadrature.size())
      , face_flux(face_quadrature.size())
    {}

    template <int dim>
    ScratchData<dim>::ScratchData(const ScratchData &other)
      : ScratchData(other.fe_values.get_mapping().clone(), other)
    {}

    template <int dim>
    ScratchData<dim>::ScratchData(std::unique_ptr<const Mapping<dim>> mapping, const ScratchData &other)
      : ScratchData(*mapping, other.fe_reference.get_mapping(), other.fe_values.get_fe(),
                    other.fe_values.get_quadrature(), other.fe_face.get_quadrature(),
                    other.fe_values.get_update_flags(), other.fe_reference.get_update_flags(),
                    other.fe_face.get_update_flags())
    {
      own_mapping = std::move(mapping); // the FEValues above point to it
    }

    CopyData::CopyData(const unsigned int dofs_per_cell)
      : matrix(dofs_per_cell, dofs_per_cell)
      , vector(dofs_per_cell)
      , row_sums(dofs_per_cell)
      , dofs(dofs_per_cell)
      , face_vectors(GeometryInfo<3>::faces_per_cell, dealii::Vector<double>(dofs_per_cell))
    {}

    template <int dim, class FEValuesType>
    void fill_weights(const FEValuesType &fe_values, const bool axisymmetric, std::vector<double> &weights)
    {
      for (unsigned int q = 0; q < weights.size(); ++q)
        weights[q] = fe_values.JxW(q) * ring_factor(fe_values.quadrature_point(q), axisymmetric);
    }

    template <int dim>
    void HeatCapacity::cell_matrix(const ScratchData<dim> &scratch, const double rho_c, CopyData &copy)
    {
      const FEValues<dim> &fe_values = scratch.fe_values;
      const unsigned int   n         = copy.dofs.size();
      copy.matrix                    = 0;
      for (unsigned int q = 0; q < scratch.weight.size(); ++q)
        {
          const double w = scratch.weight[q];
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = 0; j < n; ++j)
              copy.matrix(i, j) += rho_c * fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * w;
        }
      for (unsigned int i = 0; i < n; ++i)
        {
          copy.row_sums(i) = 0;
          for (unsigned int j = 0; j < n; ++j)
            copy.row_sums(i) += copy.matrix(i, j);
        }
    }

    template <int dim>
    double HeatCapacity::dirichlet_rate(const ScratchData<dim> &scratch, const unsigned int q,
                                        const double rho_c, const bool axisymmetric)
    {
      const double reference_weight =
        scratch.fe_reference.JxW(q) * ring_factor(scratch.fe_reference.quadrature_point(q), axisymmetric);
      double rho_c_g_dot = 0;
      for (unsigned int j = 0; j < scratch.g_dot.size(); ++j)
        rho_c_g_dot += rho_c * reference_weight / scratch.weight[q] *
                       scratch.fe_values.shape_value(j, q) * scratch.g_dot(j);
      return rho_c_g_dot;
    }

    template <int dim>
    void Conduction::cell_tangent(const ScratchData<dim> &scratch, const ThermalMaterial &material,
                                  CopyData &copy)
    {
      const FEValues<dim> &fe_values = scratch.fe_values;
      const unsigned int   n         = copy.dofs.size();
      const double         dk        = material.dk_dT();
      if (dk == 0)
        {
          // k(T) = k₀ (1 + 0·(T − T_ref)) = k₀ and the dk term adds zero: the
          // same entries without T (the linear tangent does not fetch it).
          // Symmetric term by term (∇φᵢ·∇φⱼ = ∇φⱼ·∇φᵢ in floating point too):
          // the upper triangle, mirrored. copy.matrix is zero on entry (the
          // one caller, ThermalProblem::assemble, zeroes it), so the mirrored
          // sums are those of the full loop, bit for bit.
          for (unsigned int q = 0; q < scratch.weight.size(); ++q)
            {
              const double w = scratch.weight[q];
              const double k = material.conductivity;
              for (unsigned int i = 0; i < n; ++i)
                for (unsigned int j = i; j < n; ++j)
                  copy.matrix(i, j) += (k * (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q))) * w;
            }
          for (unsigned int i = 0; i < n; ++i)
            for (unsigned int j = i + 1; j < n; ++j)
              copy.matrix(j, i) = copy.matrix(i, j);
          return;
        }
      for (unsigned int q = 0; q < scratch.weight.size(); ++q)
        {
          const double w = scratch.weight[q];
          const double k = material.k(scratch.T[q]);
          for (unsigned int i = 0; i < n; ++i)
            {
              const double gi_gT = fe_values.shape_grad(i, q) * scratch.grad_T[q];
              for (unsigned int j = 0; j < n; ++j)
                copy.matrix(i, j) += (k * (fe_values.shape_grad(i, q) * fe_values.shape_grad(j, q)) +
                                      dk * fe_values.shape_value(j, q) * gi_gT) * w;
            }
        }
    }

    template <int dim>
    void VolumeSource::cell_rates(ScratchData<dim>                                      &scratch,
                                  const typename DoFHandler<dim>::active_cell_iterator &cell,
                                  const FunctionParser<dim>                             *expression,
                                  const typename ThermalProblem<dim>::HeatSource        *mechanical,
                                  const double dirichlet_rho_c, const bool axisymmetric)
    {
      const bool with_mechanics = mechanical && *mechanical;
      for (unsigned int q = 0; q < scratch.rate.size(); ++q)
        {
          double s = expression ? expression->value(scratch.fe_values.quadrature_point(q)) : 0.;
          if (with_mechanics)
            s += (*mechanical)(cell, q); // χẆirr + Ẇthel (eq. 26)
          const double rho_c_g_dot =
            dirichlet_rho_c > 0 ? HeatCapacity::dirichlet_rate(scratch, q, dirichlet_rho_c, axisymmetric) : 0.;
          scratch.rate[q] = s - rho_c_g_dot;
        }
    }

    template <int dim>
    void VolumeSource::cell_load(const ScratchData<dim> &scratch, CopyData &copy)
    {
      for (unsigned int q = 0; q < scratch.weight.size(); ++q)
        for (unsigned int i = 0; i < copy.dofs.size(); ++i)
          copy.vector(i) += residual(scratch.fe_values.shape_value(i, q), scratch.rate[q]) * scratch.weight[q];
    }

    template <int dim>
    void volume_residual(const ScratchData<dim> &scratch, const ThermalMaterial &material, CopyData &copy)
    {
      const FEValues<dim> &fe_values = scratch.fe_values;
      for (unsigned int q = 0; q < scratch.weight.size(); ++q)
        {
          const double k = material.k(scratch.T[q]);
          for (unsigned int i = 0; i < copy.dofs.size(); ++i)
            copy.vector(i) += (Conduction::residual(k, fe_values.shape_grad(i, q), scratch.grad_T[q]) +
                               VolumeSource::residual(fe_values.shape_value(i, q), scratch.rate[q])) *
                              scratch.weight[q];
        }
    }

    template <int dim>
    void boundary_face(ScratchData<dim> &scratch, const typename DoFHandler<dim>::active_cell_iterator &cell,
                       const unsigned int face, const typename ThermalBoundaryConditions<dim>::Boundary &b,
                       const TrilinosWrappers::MPI::Vector *T, const bool axisymmetric, const bool tangent,
                       CopyData &copy)
    {
      FEFaceValues<dim> &fe_face = scratch.fe_face;
      fe_face.reinit(cell, face);
      Assert(T || !(b.h || b.emissivity), ExcMessage("convection and radiation need the temperature"));
      if (T)
        fe_face.get_function_values(*T, scratch.face_T);
      fill_weights<dim>(fe_face, axisymmetric, scratch.face_weight);
      const unsigned int n = copy.dofs.size();
      for (unsigned int q = 0; q < scratch.face_weight.size(); ++q)
        {
          const Point<dim> &x = fe_face.quadrature_point(q);
          BoundaryFlux      flux;
          PrescribedFlux::add<dim>(b, x, flux);
          Convection::add<dim>(b, x, scratch.face_T[q], flux);
          Radiation::add<dim>(b, x, scratch.face_T[q], flux);
          const double w = scratch.face_weight[q];
          for (unsigned int i = 0; i < n; ++i)
            {
              copy.vector(i) += fe_face.shape_value(i, q) * flux.into_body * w;
              if (tangent)
                for (unsigned int j = 0; j < n; ++j)
                  copy.matrix(i, j) -= flux.d_dT * fe_face.shape_value(i, q) * fe_face.shape_value(j, q) * w;
            }
        }
    }

    template <int dim>
    bool zero_on_cell(const typename ThermalProblem<dim>::HeatSource &source,
                      const typename DoFHandler<dim>::active_cell_iterator &cell, const unsigned int n_points)
    {
      if (!source)
        return true;
      for (unsigned int q = 0; q < n_points; ++q)
        if (source(cell, q) != 0)
          return false;
      return true;
    }

#define INSTANTIATE(dim)                                                                          \
  template struct ScratchData<dim>;                                                               \
  template bool zero_on_cell<dim>(const typename ThermalProblem<dim>::HeatSource &,               \
                                  const typename DoFHandler<dim>::active_cell_iterator &, unsigned int); \
  template void fill_weights<dim, FEValues<dim>>(const FEValues<dim> &, bool, std::vector<double> &); \
  template void fill_weights<dim, FEFaceValues<dim>>(const FEFaceValues<dim> &, bool,               \
                                                     std::vector<double> &);                       \
  template void HeatCapacity::cell_matrix<dim>(const ScratchData<dim> &, double, CopyData &);     \
  template double HeatCapacity::dirichlet_rate<dim>(const ScratchData<dim> &, unsigned int, double, \
                                                    bool);                                         \
  template void Conduction::cell_tangent<dim>(const ScratchData<dim> &, const ThermalMaterial &,  \
                                              CopyData &);                                        \
  template void VolumeSource::cell_rates<dim>(ScratchData<dim> &,                                 \
                                              const typename DoFHandler<dim>::active_cell_iterator &, \
                                              const FunctionParser<dim> *,                         \
                                              const typename ThermalProblem<dim>::HeatSource *,    \
                                              double, bool);                                       \
  template void VolumeSource::cell_load<dim>(const ScratchData<dim> &, CopyData &);               \
  template void volume_residual<dim>(const ScratchData<dim> &, const ThermalMaterial &, CopyData &); \
  template void boundary_face<dim>(ScratchData<dim> &,                                            \
                                   const typename DoFHandler<dim>::active_cell_iterator &,        \
                                   unsigned int,                                                  \
                                   const typename ThermalBoundaryConditions<dim>::Boundary &,     \
                                   const TrilinosWrappers::MPI::Vector *, bool, bool, CopyData &);
    ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
  } // namespace thermal
} // namespace anvil
