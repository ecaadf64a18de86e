#include <turgor/io/time_sampler.h>
#include <petsc/private/tsimpl.h> /* whether the integrator can interpolate (ops->interpolate) */
#include <cmath>

namespace turgor {

TimeSampler::~TimeSampler()
{
  PetscCallVoid(VecDestroy(&work_));
}

PetscLogDouble TimeSampler::Elapsed() const
{
  PetscLogDouble now = 0;
  (void)PetscTime(&now);
  return now - start_;
}

PetscErrorCode TimeSampler::At(TS ts, PetscInt step, PetscReal t, Vec U, PetscReal tk, Vec *X)
{
  /* a fixed step sums n dt: the last step ends at T only up to n rounding errors */
  const PetscReal eps = 1e-9 * t_final_;
  PetscFunctionBeginUser;
  if (step == 0 || std::fabs(tk - t) <= eps) *X = U;
  else {
    if (!work_) PetscCall(VecDuplicate(U, &work_));
    PetscCall(TSInterpolate(ts, tk, work_));
    *X = work_;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The due times k T / n (k = *next ...) up to the step's end t: each at its time, interpolated;
   without interpolation (PETSc's ssp) the step's end once, at its own time, for all of them. */
PetscErrorCode TimeSampler::Emit(TS ts, PetscInt step, PetscReal t, Vec U, PetscInt n, PetscInt *next, const Callback &cb)
{
  const PetscReal T = t_final_, eps = 1e-9 * T;
  Vec             X = NULL; /* set by At (GCC warns it may be used uninitialised) */
  PetscFunctionBeginUser;
  if (!cb || n <= 0) PetscFunctionReturn(PETSC_SUCCESS);
  if (step > 0 && !ts->ops->interpolate) {
    PetscReal tk = -1;
    while (*next <= n && T * *next / n <= t + eps) tk = T * (*next)++ / n;
    if (tk >= 0) PetscCall(cb(std::fabs(tk - t) <= eps ? tk : t, U));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  while (*next <= n) {
    const PetscReal tk = T * *next / n;
    if (tk > t + eps) break;
    PetscCall(At(ts, step, t, U, tk, &X));
    PetscCall(cb(tk, X));
    (*next)++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeSampler::Monitor(TS ts, PetscInt step, PetscReal t, Vec U, const Callback &sample, const Callback &snapshot, PetscInt evals)
{
  const PetscReal T = t_final_;
  PetscFunctionBeginUser;
  PetscCall(Emit(ts, step, t, U, n_samples_, &next_sample_, sample));
  PetscCall(Emit(ts, step, t, U, n_snapshots_, &next_snapshot_, snapshot));
  PetscLogDouble now;
  PetscCall(PetscTime(&now));
  if (!started_) {
    start_ = last_report_ = now;
    started_              = true;
    start_step_ = step, start_evals_ = evals, start_t_ = t;
  } else if (interval_ > 0 && now - last_report_ >= interval_) {
    const PetscReal frac = t / T, el = now - start_, done = t - start_t_, eta = done > 0 ? el * (T - t) / done : 0;
    PetscInt        rej;
    MPI_Comm        comm;
    PetscCall(TSGetStepRejections(ts, &rej));
    PetscCall(PetscObjectGetComm((PetscObject)ts, &comm));
    PetscCall(PetscPrintf(comm,
                          "  t = %.6g / %g µs (%5.1f%%)  step %" PetscInt_FMT " (%" PetscInt_FMT " rejected)  %.3g steps/s  %.3g evaluations/s  ETA %.0f s\n",
                          (double)t, (double)T, 100.0 * frac, step, rej, (step - start_step_) / el, (evals - start_evals_) / el, eta));
    last_report_ = now;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
