#include <turgor/parallel/metis_partition.h>
#include <metis.h>
#include <limits>
#include <vector>

namespace turgor {

static const char *MetisStatus(int status)
{
  switch (status) {
  case METIS_ERROR_INPUT:
    return "METIS_ERROR_INPUT (the graph is not valid)";
  case METIS_ERROR_MEMORY:
    return "METIS_ERROR_MEMORY (out of memory)";
  default:
    return "METIS_ERROR";
  }
}

/* METIS 5.1 stops with an error when asked for contiguous parts of a graph that is not connected */
static bool Connected(const CSRGraph &g)
{
  const PetscInt        n = g.NumVertices();
  std::vector<char>     seen((size_t)n, 0);
  std::vector<PetscInt> stack = {0};
  PetscInt              count = 1;
  if (n == 0) return true;
  seen[0] = 1;
  while (!stack.empty()) {
    const PetscInt v = stack.back();
    stack.pop_back();
    for (PetscInt k = g.xadj[v]; k < g.xadj[v + 1]; k++)
      if (!seen[g.adjncy[k]]) {
        seen[g.adjncy[k]] = 1;
        count++;
        stack.push_back(g.adjncy[k]);
      }
  }
  return count == n;
}

PetscErrorCode MetisPartGraphKway(MPI_Comm comm, const CSRGraph &graph, PetscInt nparts, const MetisOptions &options, const char *option,
                                  std::vector<PetscInt> *part, PetscInt *objval, PetscReal *seconds)
{
  const PetscInt n = graph.NumVertices();
  PetscFunctionBeginUser;
  if (objval) *objval = 0;
  if (seconds) *seconds = 0;
  PetscCheck(nparts >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %" PetscInt_FMT ": the number of parts must be >= 1", option, nparts);
  PetscCheck(nparts <= n, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %" PetscInt_FMT ": more parts than the %" PetscInt_FMT " cells to partition", option,
             nparts, n);
  PetscCheck(graph.vwgt.empty() || (PetscInt)graph.vwgt.size() == n, comm, PETSC_ERR_ARG_SIZ, "METIS graph: %zu vertex weights for %" PetscInt_FMT " vertices",
             graph.vwgt.size(), n);
  PetscCheck(graph.adjwgt.empty() || graph.adjwgt.size() == graph.adjncy.size(), comm, PETSC_ERR_ARG_SIZ, "METIS graph: %zu edge weights for %zu edges",
             graph.adjwgt.size(), graph.adjncy.size());
  part->assign((size_t)n, 0);
  if (nparts == 1) PetscFunctionReturn(PETSC_SUCCESS);

  /* idx_t is METIS's own integer (32 bits in Debian's build); PetscInt may be wider */
  const PetscInt big = (PetscInt)std::numeric_limits<idx_t>::max();
  PetscCheck((PetscInt)graph.adjncy.size() <= big, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: the graph has %zu edge ends, more than METIS's idx_t holds",
             option, graph.adjncy.size());
  PetscInt vsum = 0, esum = 0;
  for (PetscInt w : graph.vwgt) vsum += w;
  for (PetscInt w : graph.adjwgt) esum += w;
  PetscCheck(vsum <= big && esum <= big, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %s: the graph's total weights overflow METIS's idx_t", option);
  std::vector<idx_t> xadj(graph.xadj.begin(), graph.xadj.end()), adjncy(graph.adjncy.begin(), graph.adjncy.end());
  std::vector<idx_t> vwgt(graph.vwgt.begin(), graph.vwgt.end()), adjwgt(graph.adjwgt.begin(), graph.adjwgt.end()), where((size_t)n, 0);
  idx_t              nvtxs = (idx_t)n, ncon = 1, np = (idx_t)nparts, cut = 0;
  idx_t              opts[METIS_NOPTIONS];
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_NUMBERING] = 0;
  opts[METIS_OPTION_SEED]      = (idx_t)options.seed;
  opts[METIS_OPTION_CONTIG]    = options.contiguous && Connected(graph) ? 1 : 0;
  opts[METIS_OPTION_NCUTS]     = (idx_t)options.ncuts;
  PetscLogDouble t0, t1;
  PetscCall(PetscTime(&t0));
  const int status = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.empty() ? nullptr : vwgt.data(), nullptr,
                                         adjwgt.empty() ? nullptr : adjwgt.data(), &np, nullptr, nullptr, opts, &cut, where.data());
  PetscCall(PetscTime(&t1));
  PetscCheck(status == METIS_OK, comm, PETSC_ERR_LIB, "Option %s = %" PetscInt_FMT ": METIS_PartGraphKway failed: %s", option, nparts, MetisStatus(status));
  for (PetscInt v = 0; v < n; v++) (*part)[v] = (PetscInt)where[v];
  if (objval) *objval = (PetscInt)cut;
  if (seconds) *seconds = (PetscReal)(t1 - t0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
