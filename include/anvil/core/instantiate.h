#pragma once

/**
 * The one instantiation macro. anvil's templates are instantiated for
 * dim = 2 and 3 in the .cc file that defines them (template bodies stay out
 * of headers, which keeps compile times in check):
 *
 *   #define INSTANTIATE(dim) template class MechanicalProblem<dim>;
 *   ANVIL_INSTANTIATE(INSTANTIATE)
 *   #undef INSTANTIATE
 *
 * or, for a class template of dim alone, ANVIL_INSTANTIATE_CLASS(Simulator).
 */
#define ANVIL_INSTANTIATE(M) M(2) M(3)

#define ANVIL_INSTANTIATE_CLASS_(C, dim) template class C<dim>;
#define ANVIL_INSTANTIATE_CLASS(C)                                                               \
  ANVIL_INSTANTIATE_CLASS_(C, 2)                                                                 \
  ANVIL_INSTANTIATE_CLASS_(C, 3)
