#pragma once
/* Glue bonds between neighbouring polygonal cells, and their fracture (the middle lamella of the
   L-hyphen model, its "Details of the model").

   Bonds are made once, at the first evaluation (the reference geometry; with -glue_start_time T, at
   the first accepted state at or after T, e.g. once the cells are inflated): every node within the
   gluing distance eps (-glue_distance: surface gap, i.e. closer than 2 r + eps to the bar's centre
   line) of a bar of another cell is bonded to the closest point of the closest such bar of that
   cell, c = (1 - lambda) x_a + lambda x_b with lambda fixed. A bond carries a length share L of its
   interface (docs/model.md "Glue"): along each run of consecutive bonded nodes of cell A on cell B,
   each bond gets half the distances to its neighbours' bond points, so that the shares of a straight
   interface sum to its length (bonds whose bond points coincide split one point's share); a lone bond
   gets half its shorter bar; and where both cells' nodes are
   bonded to each other, each side counts half.

   Opening: g = x_p - c in the bar's frame (t along the bar, n towards the node), delta_n = g.n -
   g0.n0, delta_t = g.t - g0.t0 from the reference g0. Per unit length: normal traction k_n <delta_n>
   (tension only: compression is contact's), tangential k_t delta_t; a bond's force is (1 - D) L times
   them, derived from its energy (1 - D) L (k_n <delta_n>^2 + k_t delta_t^2) / 2, so momentum and
   angular momentum are conserved exactly (the bar's share by the lever rule plus a couple).

   Laws (-glue_law):
     energy    (brittle) breaks when the stored energy per length reaches G_c: at delta_c = sqrt(2 G_c / k_n) in pure opening;
     strength  (brittle) breaks on the quadratic interaction (k_n <delta_n> / sigma_c)^2 + (k_t delta_t / tau_c)^2 >= 1;
     softening bilinear: damage D grows with the largest equivalent opening l = sqrt(<delta_n>^2 + (k_t/k_n) delta_t^2)
               from l_0 = sigma_c / k_n (the peak) to l_f = 2 G_c / sigma_c (broken); unloading is secant. The energy
               dissipated once the largest opening is l is G_c (l - l_0) / (l_f - l_0) per length (the integral of
               (1/2) k_n l^2 dD, whose integrand is constant), counted exactly whatever the time step: G_c per unit
               length at the break, whatever the node spacing.
   With -glue_compression an intact bond also resists closing, F_n = (1 - D) L k_n delta_n for delta_n < 0
   (the lamella carries compression; damage grows with opening only): the law is then smooth through
   zero opening, where a turgid tissue at rest sits, which an implicit solve (a polygon RVE) needs.
   Internal state (damage, the intact flag) changes only in AcceptStep, at the accepted state; an
   evaluation uses the damage its own opening would give (the trial value), never commits it. A
   broken bond stays in the list, flagged: nothing but a break removes a bond, so created = intact +
   broken always. Each break is recorded (BreakRecords) with its time, cells, node, bar, position,
   mode and the energy it released. */
#include <turgor/physics/force_term.h>
#include <turgor/physics/glue_bond_forces.h>
#include <cstdint>
#include <string>
#include <vector>

namespace turgor {

class Glue : public ForceTermBase<Glue> {
public:
  enum Law {
    ENERGY    = 0,
    STRENGTH  = 1,
    SOFTENING = 2
  };
  /* One break, as breaks.csv writes it (the bond named by its node's id and its bar's id: the same
     whatever the ranks). */
  struct Break {
    PetscReal   time, x, y, energy, length; /* energy released, the bond's length share */
    PetscInt    cell_node, cell_bar, node, bar;
    const char *mode; /* tension, shear or mixed (by the normal and tangential shares of the stored energy) */
  };

  const char    *Name() const override { return "glue"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscReal      Reach(const ParticleSet &P) const override { return 2 * P.bar_radius + distance; }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  bool           HasInternalState() const override { return true; }
  PetscErrorCode AcceptStep(const ForceInput &in) override;
  PetscReal      Dissipation() const override { return dissipated_; }
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscErrorCode OutputFields(const ForceInput &in, std::vector<TermField> &fields) override;
  PetscErrorCode OutputSegments(const ForceInput &in, TermSegments *segments) override;
  void           Statistics(std::vector<TermStatistic> &stats) const override;
  void           RecordFiles(std::vector<std::pair<std::string, std::vector<std::string>>> &files) const override;
  void           TakeRecords(std::vector<std::pair<std::string, std::vector<std::string>>> &rows) override;

  /* Make the bonds at positions X (without a call, at the first evaluation's positions). */
  PetscErrorCode CreateBonds(const ParticleSet &P, const PetscReal *X);
  /* Breaks since the last call (moved out). */
  std::vector<Break> TakeBreaks();

  PetscInt  Created() const { return (PetscInt)bonds_.size(); }
  PetscInt  Intact() const { return intact_; }
  PetscInt  Broken() const { return (PetscInt)bonds_.size() - intact_; }
  PetscReal LengthShare(PetscInt b) const { return bonds_[b].L; }
  PetscReal Damage(PetscInt b) const { return Damage(bonds_[b].lmax); }
  bool      IsIntact(PetscInt b) const { return bonds_[b].intact; }
  /* opening (delta_n, delta_t) of bond b at x */
  void Opening(PetscInt b, const PetscReal *x, PetscReal *dn, PetscReal *dt) const;

  Law       law                  = ENERGY;
  PetscReal distance             = 0.1;   /* eps [µm]: gluing distance (surface gap) */
  PetscReal normal_stiffness     = 1e4;   /* k_n [N/m per µm of interface] */
  PetscReal tangential_stiffness = -1;    /* k_t; < 0: k_n */
  PetscReal fracture_energy      = 1;     /* G_c [µN µm per µm of interface] */
  PetscReal strength             = -1;    /* sigma_c [N/m]; < 0: sqrt(2 G_c k_n), where the energy law breaks in opening */
  PetscReal shear_strength       = -1;    /* tau_c [N/m]; < 0: sigma_c sqrt(k_t / k_n) */
  bool      open_cells           = false; /* glue open cells (plates, walls) too */
  bool      compression          = false; /* -glue_compression: an intact bond resists closing too (k_n; no damage from it) */
  PetscReal start_time           = 0;     /* bonds made at the first evaluation (0), or at the first accepted state at or after this time [µs] */
  bool      has_unbonded_box     = false; /* -glue_unbonded_box: no bond whose bond point is inside (a pre-crack, a notch) */
  PetscReal unbonded_box[4]      = {0, 0, 0, 0};

  /* Declared state: every bond as made (its node, bar and cells, geometry, intact flag, largest
     opening), keyed by its node and bar, and the sums; a restart takes the bonds from the checkpoint
     instead of making them again (-glue_start_time: made from the positions of that time). */
  void           DeclareState(const ParticleSet &P, StateDeclaration &d) override;
  PetscErrorCode AfterStateRead(const ForceInput &in) override;
  void           SetBlockBonds(size_t n) { block_bonds_ = n > 0 ? n : 1; } /* the force evaluation's blocks (tests: several on a small tissue) */

private:
  struct Bond {        /* what every evaluation reads */
    PetscInt  p, a, b; /* node, bar ends */
    PetscInt  intact = 1;
    PetscReal lam, gn0, gt0, sign, L; /* bond point, reference opening components, side of n, length share */
    PetscReal lmax = 0;               /* committed largest equivalent opening, from the peak on (softening: D = D(lmax)) */
  };
  struct BondInfo { /* what only set-up and the break records read */
    PetscInt s, cell_p, cell_s;
  };
  struct Trial { /* a bond the accepted step must commit: past its peak (softening), breaking (the brittle laws) */
    size_t    k;
    PetscReal dnp, dt; /* <delta_n>, delta_t of the last evaluation */
  };
  template <int MODE>
  PetscReal Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial);
  template <int MODE>
  size_t BondRange(const ForceInput &in, size_t lo, size_t hi, size_t nt, PetscReal *E, size_t block_lo = 0);
  void   CopyGeometry(); /* geometry_ from bonds_, once they are made or read back */
  void   Commit(const ForceInput &in, size_t k, PetscReal dnp, PetscReal dt);
  /* the law's tests at the members' parameters (glue_bond_forces.h: the one formula of these and of the
     vectorised loop, which takes the parameters as locals) */
  PetscReal         Opening2(PetscReal dnp, PetscReal dt) const { return GlueOpening2(dnp, dt, beta2_); }
  bool              BeforePeak(const Bond &B, PetscReal l2) const { return GlueBeforePeak(law == SOFTENING, B.lmax, l2, l0_, l02_); }
  GlueLawParameters LawParameters() const;
  PetscReal         Damage(PetscReal l) const;     /* D(l) of the bilinear law, 0 for the brittle ones */
  PetscReal         Dissipated(PetscReal l) const; /* energy per length dissipated once the largest opening is l */

  PetscReal              kt_ = 0, beta2_ = 0, sigma_ = 0, tau_ = 0, l0_ = 0, l02_ = 0, lf_ = 0; /* beta2_ = k_t/k_n, l02_ = l0_^2 */
  std::vector<Bond>      bonds_;
  std::vector<BondInfo>  info_;
  std::vector<Trial>     trial_; /* room for every bond; the last force evaluation's first trial_n_, in bond order */
  size_t                 trial_n_     = 0;
  size_t                 trial_bonds_ = SIZE_MAX; /* the bond count trial_ was made for; SIZE_MAX: none since the bonds changed */
  size_t                 block_bonds_ = 1024;     /* the force evaluation's blocks of bonds */
  std::vector<PetscReal> push_;                   /* per bond of the block, its force on its bar and the share of bar end a (4 values), scattered after */
  std::vector<PetscReal> opening_;                /* the block's <delta_n> of every bond, then delta_t, then its mark */
  GlueBondGeometry       geometry_;               /* bonds_ by field, for the force loops (intact and lmax kept equal by Commit) */
  std::vector<Break>     breaks_;
  PetscInt               intact_ = 0, accepted_ = 0, unbonded_ = 0; /* unbonded_: pairs left unbonded by -glue_unbonded_box */
  PetscReal              dissipated_ = 0, time_ = 0;
  bool                   have_bonds_ = false;
  const ParticleSet     *P_          = nullptr;
};

} // namespace turgor
