#pragma once
/* Node-bar contact of polygonal cells (the L-hyphen model). A node is a disk and a bar a capsule,
   both of radius r = ParticleSet::bar_radius; they touch when the node is closer than 2 r to the
   bar's segment. Pairs: a node against the bars of other cells, and of its own closed cell except
   its two own bars and the two next to them (crushed cells fold); open cells have no self-contact.
   Normal force k_n delta (+ damping on the normal relative velocity, only pushing); tangential
   spring k_t xi with history xi per pair (node gid, bar), capped at mu f_n (Coulomb slip). The
   history changes only in AcceptStep, is kept by key across neighbour-list rebuilds and is dropped
   when the pair separates. The bar's share goes to its end nodes by the lever rule, plus a couple
   that balances the torque of the tangential force: linear and angular momentum are conserved.
   Each node touches a cell's wall once where the wall is one surface: a node whose closest point
   is a bar end (a corner) is counted by one bar only, and a node in front of two consecutive bars
   (the inner side of a joint) by the nearer one; the stored energy is then continuous in the
   positions (see contact.cpp). The normal dashpot's part of the force is reported apart (the energy
   balance counts its work as dissipation).

   Two lists: the neighbour search's node-bar pairs within 2 r + skin (rebuilt when a node has moved
   skin/2), and from them the pairs within 2 r + skin/4, refreshed when a node has moved skin/8
   since; only the second is visited per evaluation (a few pairs per node in a packed tissue are
   near, most are not). */
#include <turgor/physics/contact_first_pass.h>
#include <turgor/physics/force_term.h>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace turgor {

class Contact : public ForceTermBase<Contact> {
public:
  const char    *Name() const override { return "contact"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscReal      Reach(const ParticleSet &P) const override { return 2 * P.bar_radius; }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  bool           HasInternalState() const override { return Tangential(); }
  bool           HasDashpotForce() const override { return damping > 0; }
  PetscErrorCode AcceptStep(const ForceInput &in) override;
  PetscReal      Dissipation() const override { return dissipated_; } /* by frictional slip: |f_t| x the slip at each accepted step */
  PetscErrorCode View(PetscViewer viewer) const override;
  void           Statistics(std::vector<TermStatistic> &stats) const override;

  PetscInt CandidateListBuilds() const { return list_builds_; } /* filtered node-bar lists built */
  size_t   Candidates() const { return cand_.size(); }          /* pairs within 2 r + skin */
  size_t   NearCandidates() const { return near_.size(); }      /* pairs within 2 r + skin/4: visited per evaluation */
  PetscInt NearListBuilds() const { return near_builds_; }
  PetscInt ActiveContacts() const { return active_; } /* pairs in contact at the last evaluation */
  size_t   HistoryEntries() const;                    /* pairs with a tangential history */

  PetscReal stiffness            = 1.0e4; /* k_n [N/m] */
  PetscReal damping              = 0;     /* normal dashpot [ng/µs] */
  PetscReal friction             = 0;     /* mu */
  PetscReal tangential_stiffness = -1;    /* k_t [N/m]; < 0: k_n */

  /* Declared state: the live tangential histories by (node, bar), the commits and the friction's
     dissipation; after a restart the pair lists are rebuilt from the restored neighbour lists and the
     histories attached to them. */
  void           DeclareState(const ParticleSet &P, StateDeclaration &d) override;
  PetscErrorCode AfterStateRead(const ForceInput &in) override;

private:
  struct History {
    PetscReal xi      = 0;     /* committed elastic tangential displacement [µm] */
    PetscReal lam_ref = 0;     /* the contact point's material coordinate on the bar at the last accepted step */
    bool      live    = false; /* the pair was in contact at the last accepted step */
    PetscInt  stamp   = 0;     /* the commit that last set it */
  };
  struct Trial {             /* a touching pair's values at the last evaluation (friction) */
    PetscInt  k;             /* index into cand_ */
    PetscReal xi, lam, slip; /* capped tangential displacement, contact point, the slip's dissipation */
  };
  struct Candidate {
    PetscInt p, a, b, s; /* node, bar ends, bar */
    /* the bars next to s at a and at b, as the corner and nearer-bar rules see them: their far ends
       (-1: none, or one that may not touch p) and whether each is numbered below s (the rules'
       tie-break); fixed by the topology, so found once per list instead of at every evaluation */
    PetscInt oa, ob;
    bool     lower_a, lower_b;
  };
  struct Geometry { /* of a pair: e = x_b - x_a, d = x_p - (x_a + lam e), d2 = |d|^2 */
    PetscReal ex, ey, dx, dy, d2, lam, iL2;
  };
  bool Tangential() const { return friction > 0 && kt_ > 0; }
  template <int MODE>
  PetscReal Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial);
  /* The pair's geometry at x, and whether it is a contact that counts (closer than 2 r, and the
     bar the node touches the wall through). */
  bool        Counts(const PetscReal *x, const Candidate &C, Geometry &g) const;
  static bool NearerNeighbour(const PetscReal *x, PetscInt p, PetscInt q, PetscInt o, bool lower, PetscReal d2);
  Candidate   MakeCandidate(const ParticleSet &P, PetscInt p, PetscInt s) const; /* with its neighbour bars */

  PetscErrorCode Refresh(const ForceInput &in);
  void           ForgetLists(); /* no pairs, histories or trials: the next Refresh builds them */
  void           BuildNearList(const ForceInput &in, const PetscReal *x, PetscInt n);
  bool           Eligible(const ParticleSet &P, PetscInt p, PetscInt s) const;
  void           CommitTrial();
  /* the pair lists from the neighbour lists at in.x, then the histories `saved` by Key */
  PetscErrorCode AttachHistories(const ForceInput &in, const std::unordered_map<std::uint64_t, History> &saved);
  static bool    CornerOwner(const PetscReal *x, PetscInt p, PetscInt q, PetscInt o, bool lower);
  std::uint64_t  Key(const ParticleSet &P, PetscInt p, PetscInt s) const { return (std::uint64_t)P.gid[p] * (std::uint64_t)n_springs_ + (std::uint64_t)s; }

  PetscReal                    r_ = 0, kt_ = 0, near_skin_ = 0;
  std::vector<PetscInt>        bar_poly_, bar_pos_, node_pos_, node_bars_;
  std::vector<Candidate>       cand_;                         /* eligible pairs of the neighbour list */
  std::vector<History>         hist_;                         /* beside cand_ */
  std::vector<ContactNearPair> near_;                         /* the candidates closer than 2 r + the near skin (or with a live history), for the first pass */
  std::vector<PetscInt>        near_cand_;                    /* beside near_: which candidate each is */
  std::vector<PetscInt>        touch_;                        /* the near pairs closer than 2 r, by their index in near_ (a kernel's first pass) */
  std::vector<Trial>           trial_;                        /* from the last evaluation (friction) */
  std::vector<PetscInt>        live_;                         /* indices into cand_ of the pairs with a live history */
  PetscInt                     trial_lists_ = -1, stamp_ = 0; /* list_builds_ of the trial values; commits made */
  PetscInt                     seen_rebuilds_ = -1, list_builds_ = 0, near_builds_ = 0, active_ = 0;
  PetscInt                     evaluations_ = 0, max_active_ = 0;               /* AddForces calls, most contacts in one */
  PetscReal                    sum_active_ = 0, sum_near_ = 0, dissipated_ = 0; /* over AddForces calls; friction */
  size_t                       n_springs_ = 0;
  struct SavedHistory { /* a live history as a checkpoint holds it */
    PetscInt  node, bar;
    PetscReal xi, lam_ref;
    PetscInt  age; /* commits since it was set */
  };
  std::vector<SavedHistory> saved_; /* DeclareState's view of the histories; AfterStateRead attaches what was read */
};

} // namespace turgor
