#pragma once
/* Bending hinges of polygonal cells (the L-hyphen model): at every interior node of a polygon (every
   node of a closed cell, all but the two ends of an open one) a moment M = k_r (theta - theta0 -
   theta_p) between its two bars, |M| capped at M_max (elastic-perfectly plastic). theta is the
   signed angle from the bar to the previous node to the bar to the next node, theta0 its value in
   the reference geometry. The moment acts as force couples: M/l perpendicular to each bar at its far
   node, balanced at the hinge node, so that linear and angular momentum are conserved exactly.
   The plastic angle theta_p changes only in AcceptStep (return mapping at the accepted state). */
#include <turgor/physics/force_term.h>
#include <cstdint>
#include <vector>

namespace turgor {

class Hinges : public ForceTermBase<Hinges> {
public:
  const char    *Name() const override { return "hinges"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  bool           HasInternalState() const override { return max_moment > 0; }
  PetscErrorCode AcceptStep(const ForceInput &in) override;
  PetscReal      Dissipation() const override { return dissipated_; }
  PetscErrorCode View(PetscViewer viewer) const override;
  void           Statistics(std::vector<TermStatistic> &stats) const override;

  /* Reference angles from positions X[2n]; without a call, the first evaluation's positions. */
  void      SetReference(const PetscReal *X);
  PetscReal PlasticDissipation() const { return dissipated_; } /* sum M_max |d theta_p| so far [µN µm] */
  size_t    NumHinges() const { return b_.size(); }
  PetscReal PlasticAngle(size_t h) const { return theta_p_[h]; }
  PetscReal Angle(size_t h, const PetscReal *x) const; /* theta - theta0 of hinge h at x */
  PetscInt  HingeNode(size_t h) const { return b_[h]; }
  bool      BarsInOrder() const { return contiguous_; }                 /* the hinges' nodes consecutive: bars read from x in order */
  void      SetBlockHinges(size_t h) { block_hinges_ = h > 0 ? h : 1; } /* the vectorised passes' blocks (tests: several on a small tissue) */

  PetscReal stiffness  = 1.0e4; /* k_r [µN µm / rad] */
  PetscReal max_moment = 0;     /* M_max [µN µm]; 0 = elastic */

  /* Declared state: each hinge's reference and plastic angles (by its node), the dissipation. */
  void           DeclareState(const ParticleSet &P, StateDeclaration &d) override;
  PetscErrorCode AfterStateRead(const ForceInput &in) override
  {
    have_angles_ = false;
    return PETSC_SUCCESS;
  }

private:
  struct Hinge {
    PetscInt a, b, c; /* previous node, hinge node, next node */
  };
  struct Run {
    PetscInt first, count; /* the hinges of one polygon, in order: hinge h's next bar is hinge h+1's previous one */
    bool     closed;       /* closed ring: the last hinge's next node is the first hinge's node */
  };
  Hinge HingeAt(size_t h) const { return {a_[h], b_[h], c_[h]}; }
  void  AddHinge(PetscInt a, PetscInt b, PetscInt c) { a_.push_back(a), b_.push_back(b), c_.push_back(c); }
  template <bool VIRIAL, bool CACHE, bool ROUND>
  void                       Kernel(const PetscReal *x, const ForceGrain &grain, PetscReal *f, PetscReal *virial);
  void                       VectorKernel(const PetscReal *x, PetscReal *f);
  void                       VectorBlock(const PetscReal *x, PetscReal *f, size_t r0, size_t r1);
  size_t                     block_hinges_ = 512; /* VectorKernel's blocks: about this many hinges (whole polygons) */
  std::vector<PetscInt>      a_, b_, c_;          /* each hinge's nodes, by field (the vectorised loop reads them so) */
  bool                       contiguous_ = false; /* b_[h] = b_[0] + h: the bars read from x in order */
  std::vector<std::uint64_t> interior_;           /* all ones for a hinge neither first nor last in its polygon, else 0 */
  std::vector<Run>           runs_;
  std::vector<PetscReal>     cos0_, sin0_, theta_p_;
  std::vector<PetscReal>     d_;       /* angles of the last AddForces (plastic hinges) */
  std::vector<PetscReal>     scratch_; /* the vectorised kernel's per-hinge values */
  std::vector<PetscInt>      general_; /* ... and the indices of those outside the series */
  PetscReal                  dissipated_ = 0;
  bool                       have_ref_ = false, have_angles_ = false;
};

} // namespace turgor
