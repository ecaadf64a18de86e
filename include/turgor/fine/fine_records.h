#pragma once
/* The records a fine run keeps beside its samples: the energy balance (-fine_energy, energy.csv:
   one row at the start and one per tip sample interval, energy_balance.h) and the terms' logs (the
   glue's breaks.csv: one row per event, gathered from every rank to the first, which writes). */
#include <turgor/fine/energy_balance.h>
#include <turgor/io/output.h>
#include <functional>
#include <memory>

namespace turgor {

class FineRecords {
public:
  /* Opens a CSV time series in the run's output directory (TimeRun::OpenSeries: a restart writes
     the checkpoint's rows again and goes on after them). */
  using OpenSeries = std::function<PetscErrorCode(CsvWriter &, const std::string &, const std::vector<std::string> &)>;

  /* energy: -fine_energy; the balance starts at the local state (x0, v0) of t = 0; a row whose
     relative residual exceeds tolerance (> 0) fails the run. Collective. */
  PetscErrorCode SetUp(MPI_Comm comm, bool energy, PetscReal tolerance, bool distributed, ForceModel &model, const Controls &controls, const ParticleSet &P,
                       const PetscReal *x0, const PetscReal *v0);
  /* The files, and (a new run) energy.csv's first row at (x0, v0); a row every t_final / samples. */
  PetscErrorCode Open(const OpenSeries &open, PetscReal t_final, PetscInt samples, bool restarted, const PetscReal *x0, const PetscReal *v0);
  /* Anything to do after a step? */
  bool Active() const { return energy_on_ || !record_csv_.empty(); }
  /* After an accepted step to the local state (x, v) of time t: the terms' log rows and the energy
     balance's works (its row when due). Collective. */
  PetscErrorCode AfterStep(PetscReal t, const PetscReal *x, const PetscReal *v, PetscReal t_final);
  /* Declared state: the next energy row's time and the balance's sums. */
  void           DeclareState(std::deque<StateDeclaration> &decls);
  PetscErrorCode AddSummary(JsonObject &js) const;                                /* collective */
  void           SetRoundOffEnergy(PetscReal e) { energy_.SetRoundOffEnergy(e); } /* EnergyBalance::SetRoundOffEnergy */

private:
  PetscErrorCode EnergyRow(PetscReal t, const PetscReal *x, const PetscReal *v);

  MPI_Comm                                comm_      = MPI_COMM_NULL;
  bool                                    energy_on_ = false, distributed_ = false;
  ForceModel                             *model_ = nullptr;
  EnergyBalance                           energy_;
  CsvWriter                               energy_csv_;
  PetscReal                               energy_next_ = 0, energy_every_ = 0, tolerance_ = 0;
  std::vector<std::string>                record_names_;
  std::vector<std::unique_ptr<CsvWriter>> record_csv_;
};

} // namespace turgor
