// MueLu's smoothed-aggregation AMG as an Epetra_Operator whose ApplyInverse
// is one V-cycle: the module libanvil-muelu.so, loaded by build_muelu()
// (amg_solver.cc) only when a scene asks for AMG package = MueLu, so that
// runs on ML do not load Tpetra, KokkosKernels, MueLu, Ifpack2, Amesos2 at
// start-up. Debian's MueLu is built without Epetra (HAVE_MUELU_EPETRA off,
// Xpetra without Epetra): the hierarchy is built on a Tpetra copy of the
// Epetra matrix's CSR arrays. The local column numbering is Epetra's (the
// Tpetra column map lists Epetra's column GIDs in order), so the copied
// indices mean the same columns. doc/linear_solver.md.
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Operator.h>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Details_initializeKokkos.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>

#include <MueLu_CreateTpetraPreconditioner.hpp>

#include <exception>
#include <string>
#include <vector>

namespace
{
  using SC   = double;
  using LO   = int;
  using GO   = long long; // the only global ordinal Debian's Tpetra is instantiated for
  using Map  = Tpetra::Map<LO, GO>;
  using NO   = Map::node_type;
  using CRS  = Tpetra::CrsMatrix<SC, LO, GO, NO>;
  using MV   = Tpetra::MultiVector<SC, LO, GO, NO>;
  using MLOp = MueLu::TpetraOperator<SC, LO, GO, NO>;

  Teuchos::RCP<const Map> tpetra_map(const Epetra_BlockMap &map, const Teuchos::RCP<const Teuchos::Comm<int>> &comm)
  {
    std::vector<GO> gids(map.NumMyElements());
    for (int i = 0; i < map.NumMyElements(); ++i)
      gids[i] = map.GID64(i);
    return Teuchos::rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                Teuchos::ArrayView<const GO>(gids.data(), gids.size()), 0, comm));
  }

  class MueLuOperator : public Epetra_Operator
  {
  public:
    MueLuOperator(const Epetra_CrsMatrix &K, const Epetra_MultiVector &modes, Teuchos::ParameterList &list)
      : epetra(K)
    {
      Tpetra::Details::initializeKokkos();
      const auto &mpi = dynamic_cast<const Epetra_MpiComm &>(K.Comm());
      const Teuchos::RCP<const Teuchos::Comm<int>> comm = Teuchos::rcp(new Teuchos::MpiComm<int>(mpi.Comm()));
      row_map = tpetra_map(K.RowMap(), comm);
      const auto col_map = tpetra_map(K.ColMap(), comm);

      int    *offsets = nullptr, *columns = nullptr;
      double *values  = nullptr;
      if (K.ExtractCrsDataPointers(offsets, columns, values) != 0)
        throw std::runtime_error("MueLu: the Epetra matrix's storage is not optimized (no CSR arrays to view)");
      const int n = K.NumMyRows(), nnz = offsets[n];
      using local_matrix = CRS::local_matrix_device_type;
      typename local_matrix::row_map_type::non_const_type row_offsets("row offsets", n + 1);
      for (int i = 0; i <= n; ++i)
        row_offsets(i) = offsets[i];
      // Copies: Tpetra 13.2 refuses views of memory it does not own
      // (WrappedDualView). The fine level's A, 12 B per entry, lives as long
      // as the hierarchy.
      typename local_matrix::index_type::non_const_type  cols("columns", nnz);
      typename local_matrix::values_type::non_const_type vals("values", nnz);
      std::copy(columns, columns + nnz, cols.data());
      std::copy(values, values + nnz, vals.data());
      local_matrix local("K", n, K.NumMyCols(), nnz, vals, row_offsets, cols);
      matrix = Teuchos::rcp(new CRS(local, row_map, col_map, row_map, row_map));

      auto nullspace = Teuchos::rcp(new MV(row_map, modes.NumVectors()));
      for (int k = 0; k < modes.NumVectors(); ++k)
        {
          auto data = nullspace->getDataNonConst(k);
          for (int i = 0; i < n; ++i)
            data[i] = modes[k][i];
        }
      list.sublist("user data").set("Nullspace", nullspace);
      preconditioner = MueLu::CreateTpetraPreconditioner<SC, LO, GO, NO>(
        Teuchos::rcp_implicit_cast<Tpetra::Operator<SC, LO, GO, NO>>(matrix), list);
      list.sublist("user data").remove("Nullspace");
      x = Teuchos::rcp(new MV(row_map, 1));
      y = Teuchos::rcp(new MV(row_map, 1));
    }

    /// K's current values into the fine level's copy (same pattern): a kept
    /// hierarchy smooths and takes residuals with the current tangent, as ML's
    /// does (it references K). Serial node: the host view is the matrix's memory.
    void refresh()
    {
      int    *offsets = nullptr, *columns = nullptr;
      double *values  = nullptr;
      epetra.ExtractCrsDataPointers(offsets, columns, values);
      const auto local = matrix->getLocalMatrixHost();
      std::copy(values, values + offsets[epetra.NumMyRows()], local.values.data());
    }

    int ApplyInverse(const Epetra_MultiVector &X, Epetra_MultiVector &Y) const override
    {
      const int n = row_map->getNodeNumElements();
      for (int k = 0; k < X.NumVectors(); ++k)
        {
          {
            auto in = x->getDataNonConst(0);
            for (int i = 0; i < n; ++i)
              in[i] = X[k][i];
          }
          preconditioner->apply(*x, *y);
          const auto out = y->getData(0);
          for (int i = 0; i < n; ++i)
            Y[k][i] = out[i];
        }
      return 0;
    }
    int Apply(const Epetra_MultiVector &X, Epetra_MultiVector &Y) const override { return epetra.Apply(X, Y); }
    int SetUseTranspose(bool) override { return -1; }
    double NormInf() const override { return 0; }
    const char *Label() const override { return "MueLu smoothed aggregation"; }
    bool UseTranspose() const override { return false; }
    bool HasNormInf() const override { return false; }
    const Epetra_Comm &Comm() const override { return epetra.Comm(); }
    const Epetra_Map &OperatorDomainMap() const override { return epetra.OperatorDomainMap(); }
    const Epetra_Map &OperatorRangeMap() const override { return epetra.OperatorRangeMap(); }

  private:
    const Epetra_CrsMatrix     &epetra;
    Teuchos::RCP<const Map>     row_map;
    Teuchos::RCP<CRS>           matrix;
    Teuchos::RCP<MLOp>          preconditioner;
    Teuchos::RCP<MV>            x, y;
  };
} // namespace

/// The module's entry point (dlsym'd by amg_solver.cc): a new operator, or
/// null with @p error set (MueLu's exceptions do not cross the boundary).
extern "C" Epetra_Operator *anvil_muelu_create(const Epetra_CrsMatrix *K,
                                               const Epetra_MultiVector *modes,
                                               Teuchos::ParameterList   *list,
                                               std::string              *error)
{
  try
    {
      return new MueLuOperator(*K, *modes, *list);
    }
  catch (const std::exception &e)
    {
      *error = e.what();
      return nullptr;
    }
}

extern "C" void anvil_muelu_refresh(Epetra_Operator *op)
{
  dynamic_cast<MueLuOperator &>(*op).refresh();
}
