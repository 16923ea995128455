// The mechanics' evaluations by kind, for Newton (newton.cc) and its
// predictor (predictor.cc).
#pragma once

namespace anvil
{
  namespace evaluation_kinds
  {
    // Distinct symbols for the two kinds of evaluation, which assemble()
    // does not tell apart by name: callgrind counts the assemblies with the
    // tangent apart from the residual-only ones (contrib/bench/instruction_ratio.py).
    template <typename Assemble>
    [[gnu::noinline]] bool tangent_assembly(const Assemble &assemble)
    {
      return assemble(true);
    }
    template <typename Assemble>
    [[gnu::noinline]] bool residual_assembly(const Assemble &assemble)
    {
      return assemble(false);
    }
    template <typename Assemble>
    bool evaluate(const bool with_matrix, const Assemble &assemble)
    {
      return with_matrix ? tangent_assembly(assemble) : residual_assembly(assemble);
    }
  } // namespace evaluation_kinds
} // namespace anvil
