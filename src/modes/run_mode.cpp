/* turgor::RunMode(): one mode, start to end, as the turgor executable and TurgorRunMode() run it. */
#include <turgor/modes/run_mode.h>
#include <turgor/core/errors.h>
#include <turgor/modes/simulation.h>
#include <cstring>

namespace turgor {

namespace {

/* Options of solvers created only when first needed (PCREDUNDANT's and PCBJACOBI's inner solvers, the
   external factorisation packages, an RVE's tangent solver at its first tangent): unread before the
   first solve, so they are reported after the solve instead. */
bool ReadAtFirstSolve(const char name[])
{
  for (const char *part :
       {"redundant_", "sub_", "fieldsplit_", "mg_levels_", "mg_coarse_", "mat_mumps_", "mat_superlu", "mat_strumpack_", "mat_mkl_", "rve_tangent_"})
    if (std::strstr(name, part)) return true;
  return false;
}

/* Options of the PETSc objects a mode configures in its set-up (the integrator, the mesh, the solvers:
   -ts_*, -coarse_dm_plex_*, ...): unread before the set-up, so they are reported after it. */
bool ReadAtSetUp(const char name[])
{
  for (const char *object :
       {"ts_", "snes_", "ksp_", "pc_", "mat_", "dm_", "eps_", "pep_", "nep_", "svd_", "st_", "bv_", "ds_", "rg_", "fn_", "tao_", "vec_", "sf_", "petsc"}) {
    const std::string inner = std::string("_") + object;
    if (std::strncmp(name, object, std::strlen(object)) == 0 || std::strstr(name, inner.c_str())) return true;
  }
  return false;
}

/* When CheckUnusedOptions() reports an option: before the set-up (most: misspelled, or not for this
   -mode), after it (ReadAtSetUp()), or after the solve (ReadAtFirstSolve()). */
enum class UnusedCheck {
  BeforeSetUp,
  AfterSetUp,
  AfterSolve
};

/* Options nobody read are reported before any work they could have changed: an error with -strict,
   a warning otherwise. */
PetscErrorCode CheckUnusedOptions(MPI_Comm comm, PetscBool strict, UnusedCheck when)
{
  PetscInt    n;
  char      **names, **values;
  std::string list;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++)
    if ((ReadAtFirstSolve(names[k]) ? UnusedCheck::AfterSolve : ReadAtSetUp(names[k]) ? UnusedCheck::AfterSetUp : UnusedCheck::BeforeSetUp) == when)
      list += std::string(list.empty() ? "" : ", ") + "-" + names[k] + (values[k] ? std::string(" ") + values[k] : std::string());
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  if (list.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(!strict, comm, PETSC_ERR_ARG_WRONG, "Options not used by this -mode (misspelled, or for another mode): %s", list.c_str());
  PetscCall(PetscPrintf(comm, "WARNING: options not used by this -mode (misspelled, or for another mode; -strict makes this an error): %s\n", list.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Configure, set up, and (unless -help: every object is then configured, so all options are
   listed, but nothing is solved) solve and summarise the chosen mode. */
PetscErrorCode Run(MPI_Comm comm, const char default_mode[], std::unique_ptr<Simulation> &sim)
{
  char      mode[64] = "fe2"; /* the executable's default scene: the seed's bending bar with FE^2 */
  PetscBool help, strict = PETSC_FALSE;
  PetscFunctionBeginUser;
  if (default_mode) {
    PetscCheck(std::strlen(default_mode) < sizeof mode, comm, PETSC_ERR_ARG_OUTOFRANGE, "RunMode(): mode '%s' is too long", default_mode);
    PetscCall(PetscStrncpy(mode, default_mode, sizeof mode));
  }
  const std::string modes = "What to run: " + SimulationNames();
  PetscOptionsBegin(comm, NULL, "turgor", "turgor");
  PetscCall(PetscOptionsString("-mode", modes.c_str(), "turgor", mode, mode, sizeof mode, NULL));
  PetscCall(PetscOptionsBool("-strict", "Unused (misspelled) options are an error, not a warning", "turgor", strict, &strict, NULL));
  PetscOptionsEnd();
  PetscCheck(mode[0], comm, PETSC_ERR_ARG_WRONG, "Option -mode: empty (known: %s)", SimulationNames().c_str());
  PetscCall(SimulationCreate(comm, mode, &sim));
  if (!sim->Checkpoints())
    for (const char *o : {"-restart", "-restart_allow", "-checkpoint_interval", "-checkpoint_wall_interval"}) {
      PetscBool given;
      PetscCall(PetscOptionsHasName(NULL, NULL, o, &given));
      PetscCheck(!given, comm, PETSC_ERR_SUP, "Option %s: -mode %s has no checkpoints (-mode fine and -mode fe2 have)", o, mode);
    }
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(sim->SetFromOptions());
  if (!help) PetscCall(CheckUnusedOptions(comm, strict, UnusedCheck::BeforeSetUp)); /* before a long set-up (a large tissue) */
  PetscCall(sim->SetUp());
  if (help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(CheckUnusedOptions(comm, strict, UnusedCheck::AfterSetUp));
  PetscCall(sim->Solve());
  PetscCall(sim->WriteSummary());
  PetscCall(CheckUnusedOptions(comm, strict, UnusedCheck::AfterSolve));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode RunMode(MPI_Comm comm, const char mode[], int *status, std::unique_ptr<Simulation> *keep)
{
  std::unique_ptr<Simulation> local, &sim = keep ? *keep : local;
  PetscErrorCode              ierr;
  PetscFunctionBeginUser;
  *status = 0;
  ierr    = CatchExceptions(PETSC_FUNCTION_NAME, __LINE__, __FILE__, [&] { return Run(comm, mode, sim); });
  if (ierr) {
    /* the error and its trace are printed already: leave a summary.json that says so; an error
       raised for SIGINT/SIGTERM ends the run "interrupted" */
    const char *text        = NULL;
    char       *specific    = NULL;
    const bool  interrupted = IsInterruptError(ierr);
    if (interrupted) *status = 130;
    if (!PetscErrorMessage(ierr, &text, &specific) && sim) {
      const std::string reason = specific && specific[0] ? specific : (text ? text : "error");
      (void)CatchExceptions(PETSC_FUNCTION_NAME, __LINE__, __FILE__,
                            [&] { return sim->WriteFailure(reason, interrupted ? "interrupted" : "failed"); }); /* best effort, after the failure */
    }
    return ierr; /* PETSc's error, reported already (not raised again) */
  }
  if (sim && sim->Interrupted()) *status = 130;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
