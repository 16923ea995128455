// A heat system whose operators are diagonal, M ẏ = −K y + g(t) with
// g(t) = ω (M cos ωt) + K sin ωt (ω = 0: none), so that (M − γJ)⁻¹ and M⁻¹
// are exact divisions and y(t) = exp(−kᵢt/mᵢ) + sin ωt from y(0) = 1 is the
// closed form the integrator tests check against. Four unknowns, i shared out
// as i mod P, rates kᵢ/mᵢ = rate (1 + i/4).
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/trilinos_vector.h>

#include "../source/thermal/arkode_integrator.h"

#include <cmath>
#include <vector>

namespace anvil::testing
{
  struct DiagonalHeatSystem : thermal::ImplicitSystem
  {
    dealii::IndexSet    owned;
    std::vector<double> m, k; // by global index
    double              gamma = 0;
    double              omega = 0;     // the forcing's frequency (0: unforced)
    bool                exact = false; // offered to the linear DIRK loop

    DiagonalHeatSystem(const double rate, const double omega, const bool exact)
      : omega(omega)
      , exact(exact)
    {
      const unsigned int n_procs = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
      const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
      const unsigned int n       = 4;
      owned.set_size(n);
      for (unsigned int i = 0; i < n; ++i)
        if (i % n_procs == rank)
          owned.add_index(i);
      owned.compress();
      for (unsigned int i = 0; i < n; ++i)
        {
          m.push_back(1. + i);
          k.push_back(rate * (1. + i) * (1. + 0.25 * i));
        }
    }

    void reinit_vector(thermal::Vector &v) const override { v.reinit(owned, MPI_COMM_WORLD); }
    int  rhs(const double t, const thermal::Vector &y, thermal::Vector &f) override
    {
      for (const auto i : owned)
        f(i) = omega == 0 ? -k[i] * y(i) :
                            -k[i] * y(i) + m[i] * omega * std::cos(omega * t) +
                              k[i] * std::sin(omega * t);
      f.compress(dealii::VectorOperation::insert);
      return 0;
    }
    int setup_jacobian(double, const thermal::Vector &) override { return 0; }
    int jacobian_vmult(const thermal::Vector &v, thermal::Vector &Jv) override
    {
      for (const auto i : owned)
        Jv(i) = -k[i] * v(i);
      Jv.compress(dealii::VectorOperation::insert);
      return 0;
    }
    int setup_newton_matrix(const double g) override
    {
      gamma = g;
      return 0;
    }
    int solve_newton_matrix(thermal::Vector &x, const thermal::Vector &b) override
    {
      for (const auto i : owned)
        x(i) = b(i) / (m[i] + gamma * k[i]);
      x.compress(dealii::VectorOperation::insert);
      return 1;
    }
    bool newton_matrix_is_exact(const double g) const override { return g == gamma; }
    bool can_solve_exactly() const override { return exact; }
    int  mass_vmult(const thermal::Vector &v, thermal::Vector &Mv) override
    {
      for (const auto i : owned)
        Mv(i) = m[i] * v(i);
      Mv.compress(dealii::VectorOperation::insert);
      return 0;
    }
    int solve_mass(thermal::Vector &x, const thermal::Vector &b, double) override
    {
      for (const auto i : owned)
        x(i) = b(i) / m[i];
      x.compress(dealii::VectorOperation::insert);
      return 0;
    }
  };
} // namespace anvil::testing
