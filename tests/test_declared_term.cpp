/* A force term with history defined here, outside turgor, that restarts through its declarations
   alone: "damage_springs", wall springs whose stiffness degrades with a damage variable D per
   spring, D = min(1, max(D, (strain - e0) / (e1 - e0))) committed at every accepted step (the
   largest strain so far decides), the force (1 - D) k (l - l0) along the spring. The term declares
   its damage per spring and the energy its damage dissipated (DeclareState) and has no checkpoint
   code: tests/declared_state.cmake runs the fine mode with it through this program (the turgor
   executable with one more term), stops and continues it on 1 and 2 ranks, and compares the final
   state with the run that was not stopped. */
#include <turgor/turgor.hpp>
#include <turgor/core/errors.h>
#include <turgor/modes/run_mode.h>
#include <turgor/physics/force_term.h>
#include <cmath>

namespace {

using namespace turgor;

class DamageSprings : public ForceTermBase<DamageSprings> {
public:
  const char    *Name() const override { return "damage_springs"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override
  {
    PetscFunctionBeginUser;
    PetscOptionsBegin(comm, "damage_", "Damaging wall springs (a test term)", "turgor");
    PetscCall(TurgorOptionsReal(ctx.params, "-stiffness", "Spring stiffness k [N/m]", "DamageSprings", k_, &k_, NULL));
    PetscCall(TurgorOptionsReal(ctx.params, "-onset", "Strain where damage starts", "DamageSprings", e0_, &e0_, NULL));
    PetscCall(TurgorOptionsReal(ctx.params, "-failure", "Strain where a spring is broken", "DamageSprings", e1_, &e1_, NULL));
    PetscOptionsEnd();
    PetscCheck(k_ > 0 && e1_ > e0_, comm, PETSC_ERR_ARG_OUTOFRANGE, "Options -damage_*: k > 0 and failure > onset");
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override
  {
    PetscFunctionBeginUser;
    damage_.assign(P.springs.size(), 0.0);
    dissipated_ = 0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override
  {
    PetscFunctionBeginUser;
    for (size_t s = 0; s < in.P->OwnedSprings(); s++) {
      PetscReal ex, ey, l;
      Geometry(in, s, &ex, &ey, &l);
      const PetscReal mag = (1 - damage_[s]) * k_ * (l - in.P->springs[s].rest_length);
      const PetscInt  i = in.P->springs[s].i, j = in.P->springs[s].j;
      f[2 * i] += mag * ex, f[2 * i + 1] += mag * ey;
      f[2 * j] -= mag * ex, f[2 * j + 1] -= mag * ey;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  bool           HasInternalState() const override { return true; }
  PetscErrorCode AcceptStep(const ForceInput &in) override
  {
    PetscFunctionBeginUser;
    for (size_t s = 0; s < in.P->OwnedSprings(); s++) {
      PetscReal ex, ey, l;
      Geometry(in, s, &ex, &ey, &l);
      const PetscReal l0 = in.P->springs[s].rest_length, strain = (l - l0) / l0;
      const PetscReal D = std::min<PetscReal>(1, std::max(damage_[s], (strain - e0_) / (e1_ - e0_)));
      dissipated_ += (D - damage_[s]) * 0.5 * k_ * (l - l0) * (l - l0);
      damage_[s] = D;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscReal Dissipation() const override { return dissipated_; }
  void      Statistics(std::vector<TermStatistic> &stats) const override
  {
    PetscReal damaged = 0;
    for (size_t s = 0; s < damage_.size(); s++) damaged += damage_[s] > 0;
    stats.push_back({"damage_springs_damaged", damaged});
    stats.push_back({"damage_springs_dissipation", dissipated_});
  }
  PetscErrorCode View(PetscViewer viewer) const override
  {
    return PetscViewerASCIIPrintf(viewer, "damage_springs: k = %g N/m, damage from strain %g to %g\n", (double)k_, (double)e0_, (double)e1_);
  }
  /* All it keeps from step to step, declared once: its checkpoints and restarts on any number of
     ranks are these two lines. */
  void DeclareState(const ParticleSet &P, StateDeclaration &d) override
  {
    d.Scalar("dissipation", &dissipated_, Combine::Sum);
    d.Table("springs", StateEntity::Bar).Rows([this] { return damage_.size(); }).Column("damage", damage_);
  }

private:
  void Geometry(const ForceInput &in, size_t s, PetscReal *ex, PetscReal *ey, PetscReal *l) const
  {
    const PetscInt   i = in.P->springs[s].i, j = in.P->springs[s].j;
    const PetscReal *x  = in.x;
    const PetscReal  dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    *l = std::sqrt(dx * dx + dy * dy), *ex = dx / *l, *ey = dy / *l;
  }
  PetscReal              k_ = 1e4, e0_ = 1e-3, e1_ = 1e-2, dissipated_ = 0;
  std::vector<PetscReal> damage_; /* per spring of the tissue on this rank (owned first) */
};

} // namespace

int main(int argc, char **argv)
{
  int                 status = 0;
  turgor::ErrorRecord errors;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "The fine mode with a test term that damages its springs (tests/declared_state.cmake)"));
  PetscCall(turgor::PushErrorHandler(&errors));
  PetscCall(TurgorRegisterAll());
  PetscCall(turgor::ForceTermRegister("damage_springs", turgor::CreateInstance<turgor::ForceTerm, DamageSprings>));
  if (turgor::RunMode(PETSC_COMM_WORLD, "fine", &status)) status = 1;
  PetscCall(turgor::FinishRanks(PETSC_COMM_WORLD, status, errors, 20.0));
  PetscCall(PetscFinalize());
  return status;
}
