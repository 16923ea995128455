// A body's material points in one block (MaterialModel::create_points with
// PointOptions), checked from outside the law:
//  1. the points of an adiabatic scene (J2AdiabaticPoint) answer an
//     isothermal increment with the plain J2 point's stress, tangent and
//     ∂σ/∂σ̃ₙ, bit for bit (the same update);
//  2. their adiabatic update equals a single adiabatic point's (create_point),
//     and its stress is the isothermal one at T + ΔT_ad to the fixed point's
//     tolerance (the definition of the Armero–Simo update);
//  3. a plain point refuses an adiabatic increment (its block has no room for
//     the iteration's state) instead of allocating it;
//  4. no heap allocation per point: create_points(n) makes a bounded number
//     of allocations whatever n, and repeated adiabatic updates none (the
//     global operator new counts them); the points of a block are evenly
//     spaced, the adiabatic ones wider by at least the state they carry
//     (2 symmetric tensors and 2 doubles).
// Prints the figures; fails on any difference or allocation.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/material_point.h>

#include "adiabatic_materials.h"
#include "check.h"

#include <atomic>
#include <cstring>
#include <cstdlib>
#include <iostream>
#include <new>
#include <stdexcept>

namespace
{
  std::atomic<std::size_t> allocations{0};
}

void *operator new(std::size_t size)
{
  ++allocations;
  if (void *p = std::malloc(size ? size : 1))
    return p;
  throw std::bad_alloc();
}
void operator delete(void *p) noexcept { std::free(p); }
void operator delete(void *p, std::size_t) noexcept { std::free(p); }

using namespace dealii;
using namespace anvil;

namespace
{
  bool same(const SymmetricTensor<2, 3> &a, const SymmetricTensor<2, 3> &b)
  {
    return std::memcmp(a.begin_raw(), b.begin_raw(), 6 * sizeof(double)) == 0;
  }
  bool same(const SymmetricTensor<4, 3> &a, const SymmetricTensor<4, 3> &b)
  {
    return std::memcmp(a.begin_raw(), b.begin_raw(), 36 * sizeof(double)) == 0;
  }
  /// The spacing of consecutive points of @p block, or 0 if uneven.
  std::ptrdiff_t stride(const PointBlock &block)
  {
    const auto    *p = block.points.data();
    std::ptrdiff_t s = reinterpret_cast<const char *>(p[1]) - reinterpret_cast<const char *>(p[0]);
    for (std::size_t i = 1; i + 1 < block.points.size(); ++i)
      if (reinterpret_cast<const char *>(p[i + 1]) - reinterpret_cast<const char *>(p[i]) != s)
        return 0;
    return s;
  }
} // namespace

int main()
{
  testing::Checks check;
  const auto        cases = testing::j2_softening_cases(testing::steel_elastic);
  const auto        model = MaterialFactory::create_from_text(cases.front().second);
  const MaterialRequest request = request_stress | request_tangent;
  SymmetricTensor<2, 3> sigma_n, de;
  sigma_n[0][0] = 100, sigma_n[0][1] = 40, sigma_n[2][2] = -30;
  de[0][0] = 4e-3, de[1][1] = -1e-3, de[0][1] = 1.5e-3, de[1][2] = -5e-4;

  const std::size_t n = 64;
  std::size_t       before = allocations;
  const PointBlock  plain  = model->create_points(n);
  const std::size_t plain_allocations = allocations - before;
  before                       = allocations;
  const PointBlock  adiabatic  = model->create_points(n, {true});
  const std::size_t adiabatic_allocations = allocations - before;
  const PointBlock  small = model->create_points(2, {true});
  before                  = allocations;
  const PointBlock  large = model->create_points(4 * n, {true});
  const std::size_t large_allocations = allocations - before;
  const std::ptrdiff_t plain_stride = stride(plain), adiabatic_stride = stride(adiabatic);
  std::cout << "create_points(" << n << "): " << plain_allocations << " allocations, "
            << adiabatic_allocations << " adiabatic, " << large_allocations << " for " << 4 * n
            << "; stride " << plain_stride << " B, adiabatic " << adiabatic_stride << " B"
            << std::endl;
  check(plain_allocations <= 4 && adiabatic_allocations <= 4 && large_allocations <= 4,
        "a bounded number of allocations per block, not one per point");
  check(plain_stride > 0 && adiabatic_stride > 0, "the points of a block are evenly spaced");
  check(adiabatic_stride - plain_stride >=
          std::ptrdiff_t(2 * sizeof(SymmetricTensor<2, 3>) + 2 * sizeof(double)),
        "the adiabatic points carry their state inline");
  (void)small;

  // 1. Isothermal increments: the same answers from both point types.
  MaterialIncrement iso = testing::adiabatic_test_increment(de, false);
  bool              equal = true;
  for (const double scale : {0.01, 1., 2.})
    {
      MaterialIncrement inc = iso;
      inc.strain_increment  = scale * de;
      MaterialPoint &a = *plain.points[3], &b = *adiabatic.points[5];
      a.set_stress(sigma_n);
      b.set_stress(sigma_n);
      MaterialResponse ra, rb;
      a.update(inc, request, ra);
      b.update(inc, request, rb);
      equal = equal && same(ra.stress, rb.stress) && same(ra.tangent, rb.tangent) &&
              ra.sensitivity_is_identity == rb.sensitivity_is_identity &&
              same(ra.rotated_stress_sensitivity, rb.rotated_stress_sensitivity) &&
              ra.equivalent_plastic_strain == rb.equivalent_plastic_strain;
    }
  check(equal, "isothermal: both point types give the same stress and tangent, bit for bit");

  // 2. Adiabatic: a block's point against a single point, and against the
  //    isothermal update at T + ΔT_ad.
  const MaterialIncrement ad = testing::adiabatic_test_increment(de, true);
  auto                    single = model->create_point({true});
  MaterialPoint          &b      = *adiabatic.points[7];
  single->set_stress(sigma_n);
  b.set_stress(sigma_n);
  MaterialResponse rs, rb, rt;
  single->update(ad, request, rs);
  b.update(ad, request, rb);
  const double x = rb.adiabatic_temperature_increment;
  MaterialIncrement at = iso;
  at.temperature += x, at.temperature_increment += x;
  plain.points[0]->set_stress(sigma_n);
  plain.points[0]->update(at, request, rt);
  const double fixed_point = (rt.stress - rb.stress).norm() / rb.stress.norm();
  std::cout << "adiabatic: dT_ad = " << x << " K, plastic strain " << rb.equivalent_plastic_strain
            << ", |sigma - sigma_iso(T + dT_ad)| / |sigma| = " << fixed_point << std::endl;
  check(x != 0 && rb.equivalent_plastic_strain > 0, "the adiabatic case flows and changes T");
  check(same(rs.stress, rb.stress) && same(rs.tangent, rb.tangent) && rs.adiabatic_temperature_increment == x,
        "adiabatic: a block's point equals a single point, bit for bit");
  check(fixed_point < 1e-10, "adiabatic stress = isothermal stress at T + dT_ad");

  // 3. A plain point refuses an adiabatic increment.
  bool refused = false;
  try
    {
      MaterialResponse r;
      plain.points[1]->update(ad, request, r);
    }
  catch (const std::logic_error &)
    {
      refused = true;
    }
  check(refused, "a plain point refuses an adiabatic increment");

  // 4. No allocation in repeated adiabatic updates.
  before = allocations;
  for (unsigned int k = 0; k < 5; ++k)
    for (MaterialPoint *p : adiabatic.points)
      {
        MaterialResponse r;
        p->set_stress(sigma_n);
        p->update(ad, request, r);
        p->commit();
      }
  const std::size_t update_allocations = allocations - before;
  std::cout << "allocations in " << 5 * n << " adiabatic updates: " << update_allocations << std::endl;
  check(update_allocations == 0, "no allocation in an adiabatic update");
  return check.finish();
}
