#pragma once
/* Damped modes of the coarse model: the quadratic eigenproblem
     (K + s C + s^2 M) phi = 0,   s = -zeta omega +- i omega sqrt(1 - zeta^2)
   of M u'' + C u' + K u = 0 (C from the material points' D^v), by SLEPc's PEP (TOAR on the
   linearisation, shift-and-invert about a target, 0 by default: the eigenvalues of smallest
   modulus). Real arithmetic: a complex pair is reported once (Im s > 0); an overdamped mode is a real
   s < 0. Defaults through the API, then -<prefix>pep_* and -<prefix>st_* (the PEP's ST). */
#include <turgor/analysis/coarse_operators.h>
#include <slepcpep.h>
#include <string>
#include <vector>

namespace turgor {

struct DampedEigenvalue {
  PetscReal re = 0, im = 0; /* s [1/µs] */
  PetscReal residual = 0;   /* PEP's backward error */
  /* decay rate -Re s [1/µs], damped angular frequency Im s [rad/µs], damping ratio -Re s / |s| */
  PetscReal Decay() const { return -re; }
  PetscReal Damped() const { return im; }
  PetscReal Ratio() const { return std::hypot(re, im) > 0 ? -re / std::hypot(re, im) : 0; }
};

class DampedModes {
public:
  explicit DampedModes(MPI_Comm comm) : comm_(comm) { }
  ~DampedModes();
  DampedModes(const DampedModes &)            = delete;
  DampedModes &operator=(const DampedModes &) = delete;

  PetscErrorCode SetFromOptions(const std::string &prefix, PetscInt nev, PetscReal tol);
  /* ops assembled with damping; the eigenvalues sorted by |s| */
  PetscErrorCode                       Solve(const CoarseOperators &ops);
  const std::vector<DampedEigenvalue> &Values() const { return values_; }
  PetscInt                             Iterations() const { return its_; }
  PetscReal                            SolveTime() const { return solve_time_; }
  std::string                          Description() const { return description_; }

private:
  MPI_Comm                      comm_;
  PEP                           pep_ = nullptr;
  std::vector<DampedEigenvalue> values_;
  PetscInt                      its_ = 0, nev_ = 0; /* nev_: modes (pairs) asked for */
  PetscReal                     solve_time_ = 0;
  std::string                   description_;
  PetscLogEvent                 ev_solve_ = 0;
};

} // namespace turgor
