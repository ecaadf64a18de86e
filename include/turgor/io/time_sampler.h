#pragma once
/* Output at fixed times for any TS run: from a TSMonitor, calls `sample` at n_samples + 1 equally
   spaced times over [0, T] and `snapshot` at n_snapshots + 1, with the state interpolated by TS
   between the last two steps (not whichever steps the integrator took; an integrator without
   interpolation, PETSc's ssp, gives the first step end at or after each time, stamped with the
   step's own time), and prints a progress line
   (time reached, steps/s, evaluations/s, ETA: since this process started stepping, a restarted run's
   own) every `interval` seconds of wall time. */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>
#include <functional>

namespace turgor {

class TimeSampler {
public:
  using Callback = std::function<PetscErrorCode(PetscReal t, Vec U)>;

  void Configure(PetscReal t_final, PetscInt n_samples, PetscInt n_snapshots, PetscReal progress_interval)
  {
    t_final_ = t_final, n_samples_ = n_samples, n_snapshots_ = n_snapshots, interval_ = progress_interval;
    next_sample_ = next_snapshot_ = 0;
    started_                      = false;
  }
  /* Checkpoints: the next sample and snapshot indices; a restarted run continues from them (its
     first monitor call, at the checkpoint's step, then writes nothing twice). */
  void Position(PetscInt *sample, PetscInt *snapshot) const { *sample = next_sample_, *snapshot = next_snapshot_; }
  void SetPosition(PetscInt sample, PetscInt snapshot) { next_sample_ = sample, next_snapshot_ = snapshot; }
  /* Call from the TS monitor; `evals` is the caller's count of function evaluations so far. */
  PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, const Callback &sample, const Callback &snapshot, PetscInt evals);
  PetscLogDouble Elapsed() const;
  ~TimeSampler();

private:
  PetscErrorCode At(TS ts, PetscInt step, PetscReal t, Vec U, PetscReal tk, Vec *X);
  PetscErrorCode Emit(TS ts, PetscInt step, PetscReal t, Vec U, PetscInt n, PetscInt *next, const Callback &cb);

  PetscReal      t_final_ = 1, interval_ = 10;
  PetscInt       n_samples_ = 0, n_snapshots_ = 0, next_sample_ = 0, next_snapshot_ = 0;
  PetscLogDouble start_ = 0, last_report_ = 0;
  Vec            work_       = nullptr;
  bool           started_    = false;               /* the wall clock starts at the first monitor call (step 0, or a restart's first) */
  PetscInt       start_step_ = 0, start_evals_ = 0; /* and the rates and the ETA count from there: a restart's own */
  PetscReal      start_t_ = 0;
};

} // namespace turgor
