/* Checkpoints of a time run (TimeRun, run/time_run.h): what is written is what the run and its
   objects declare (io/declared_state.h), by the one writer and reader of io/checkpoint_file.h. */
#include <turgor/core/log.h>
#include <turgor/io/checkpoint_file.h>
#include <turgor/parallel/rank_reductions.h>
#include <turgor/run/time_run.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace turgor {

/* Format 5: declared state (named datasets, rows in the order of their rank-free keys, checksums),
   a fine run's integrator history with its particles; 4: that history as a table of state entries;
   3 and older: positional blobs per rank. Older formats are refused. */
static const PetscInt kCheckpointVersion = 5;

/* The run's numbering of its entities: the mode's (particles, bars, cells, material points), and the
   state's entries by StateOrder. */
class TimeRun::Numbering : public StateNumbering {
public:
  Numbering(const TimeRun &run, std::vector<PetscInt> order) : run_(run), order_(std::move(order)) { }
  std::uint64_t Id(StateEntity e, PetscInt l) const override { return e == StateEntity::StateEntry ? (std::uint64_t)order_[l] : run_.EntityId(e, l); }
  PetscInt      Local(StateEntity e, std::uint64_t id) const override { return e == StateEntity::StateEntry ? -1 : run_.EntityLocal(e, id); }
  bool          Owned(StateEntity e, PetscInt l) const override { return e == StateEntity::StateEntry ? true : run_.EntityOwned(e, l); }
  std::uint64_t Layout() const override { return run_.LayoutHash(); }

private:
  const TimeRun        &run_;
  std::vector<PetscInt> order_;
};

/* Each local entry's index in the rank-free order of the state (StateOrder; else the global index). */
static PetscErrorCode StateIds(Vec U, IS order, std::vector<PetscInt> &ids)
{
  PetscInt n, first;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(U, &n));
  ids.resize((size_t)n);
  if (order) {
    const PetscInt *idx;
    PetscCall(ISGetIndices(order, &idx));
    std::copy(idx, idx + n, ids.begin());
    PetscCall(ISRestoreIndices(order, &idx));
  } else {
    PetscCall(VecGetOwnershipRange(U, &first, NULL));
    for (PetscInt l = 0; l < n; l++) ids[l] = first + l;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::uint64_t TimeRun::LayoutHash() const
{
  PetscInt n = 0, first = 0;
  if (U_) {
    (void)VecGetLocalSize(U_, &n);
    (void)VecGetOwnershipRange(U_, &first, NULL);
  }
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint64_t v : {(std::uint64_t)n, (std::uint64_t)first}) h = (h ^ v) * 1099511628211ull;
  return h;
}

PetscErrorCode TimeRun::DeclareAll(std::deque<StateDeclaration> &decls)
{
  PetscFunctionBeginUser;
  decls.emplace_back("run");
  StateDeclaration &r = decls.back();
  r.Scalar("time", &record_.time, Combine::Owner);
  r.Scalar("step", &record_.step, Combine::Owner);
  r.Scalar("next_step_size", &record_.dt, Combine::Owner);
  r.Scalar("first_step_size", &record_.first_step, Combine::Owner);
  r.Scalar("next_sample", &record_.sample, Combine::Owner);
  r.Scalar("next_snapshot", &record_.snapshot, Combine::Owner);
  r.Scalar("schedule_end_time", &record_.t_final, Combine::Owner);
  r.Scalar("schedule_samples", &record_.samples, Combine::Owner);
  r.Scalar("schedule_snapshots", &record_.snapshots, Combine::Owner);
  if (!DeclaresSolution()) {
    decls.emplace_back("solution");
    decls.back()
      .Table("entries", StateEntity::StateEntry)
      .Rows([this] { return solution_view_.size; })
      .Column(
        "value", 1, [this](size_t r, PetscReal *out) { *out = solution_view_.data[r]; },
        [this](size_t r, const PetscReal *in) { solution_view_.data[r] = *in; });
  }
  decls.emplace_back("integrator");
  PetscCall(integrator_.Declare(ts_, decls.back(), [this](std::vector<PetscReal> &v, PetscInt n) { return KeepStateVector(v, n); }));
  PetscCall(DeclareState(decls));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::OpenSeries(CsvWriter &csv, const std::string &file, const std::vector<std::string> &columns)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank != 0 || !out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  series_.push_back({file, &csv});
  const std::string path = out_.dir + "/" + file;
  for (const auto &ft : restart_text_)
    if (ft.first == file) {
      PetscCall(csv.Restore(PETSC_COMM_SELF, path, columns, ft.second));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  PetscCall(csv.Open(PETSC_COMM_SELF, path, columns));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The integrator as a checkpoint names it: type, and the RK scheme. */
static PetscErrorCode IntegratorName(TS ts, std::string *name)
{
  TSType    type;
  PetscBool is_rk;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts, &type));
  *name = type ? type : "";
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is_rk));
  if (is_rk) {
    TSRKType rk;
    PetscCall(TSRKGetType(ts, &rk));
    *name += std::string(" ") + rk;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every -checkpoint_interval of simulated time, or -checkpoint_wall_interval of wall time (rank 0's
   clock decides, for all ranks). */
PetscErrorCode TimeRun::CheckpointDue(PetscReal t, PetscBool *due)
{
  PetscFunctionBeginUser;
  *due = PETSC_FALSE;
  if (ckpt_interval_ > 0 && t >= ckpt_next_ * (1 - 1e-12)) *due = PETSC_TRUE;
  if (ckpt_wall_ > 0) {
    PetscLogDouble now;
    int            w;
    PetscCall(PetscTime(&now));
    if (ckpt_wall_last_ == 0) ckpt_wall_last_ = now;
    w = now - ckpt_wall_last_ >= ckpt_wall_;
    PetscCallMPI(MPI_Bcast(&w, 1, MPI_INT, 0, comm_));
    if (w) *due = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* checkpoint_<step>.h5 in the output directory, written as a temporary file and renamed (a crash
   while writing leaves the previous checkpoints whole), then linked as checkpoint.h5 (the latest,
   also by a rename). Attributes: the format version, mode, ranks, integrator and step-size
   controller; texts: the scene's fingerprint, and every CSV time series as written so far; state:
   every declaration (DeclareAll). */
PetscErrorCode TimeRun::WriteCheckpoint(PetscReal t, PetscInt step)
{
  PetscLogDouble t0, t1;
  PetscMPIInt    rank, size;
  char           name[64];
  PetscFunctionBeginUser;
  if (!out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(ev_ckpt_write_, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(PetscSNPrintf(name, sizeof name, "checkpoint_%08" PetscInt_FMT ".h5", step));
  const std::string path = out_.dir + "/" + name, tmp = path + ".tmp", latest = out_.dir + "/checkpoint.h5";
  /* what the run declares, as it is now */
  record_.time = t, record_.step = step, record_.t_final = t_final_, record_.samples = out_.samples, record_.snapshots = out_.snapshots;
  record_.first_step = dt_start_;
  PetscCall(TSGetTimeStep(ts_, &record_.dt));
  sampler_.Position(&record_.sample, &record_.snapshot);
  /* the declarations read U's own array while the file is written (no copy: 32 B a particle at
     the checkpoint's peak), given back on every path out of here */
  struct ReadArray {
    Vec                    v;
    const PetscScalar     *a = nullptr;
    TimeRun::SolutionSpan *view;
    PetscErrorCode         Release()
    {
      *view                  = TimeRun::SolutionSpan();
      const PetscErrorCode e = a ? VecRestoreArrayRead(v, &a) : PETSC_SUCCESS;
      a                      = nullptr;
      return e;
    }
    ~ReadArray() { (void)Release(); }
  } held{U_, nullptr, &solution_view_};
  {
    PetscInt n;
    PetscCall(VecGetLocalSize(U_, &n));
    PetscCall(VecGetArrayRead(U_, &held.a));
    solution_view_ = {const_cast<PetscReal *>(held.a), (size_t)n}; /* read only: a write declares, the getters read */
  }
  std::vector<PetscInt> ids;
  {
    IS order;
    PetscCall(StateOrder(&order));
    PetscCall(StateIds(U_, order, ids));
    PetscCall(ISDestroy(&order));
  }
  std::deque<StateDeclaration> decls;
  PetscCall(DeclareAll(decls));
  std::vector<StateDeclaration *> all;
  for (StateDeclaration &d : decls) all.push_back(&d);
  const Numbering numbering(*this, std::move(ids));

  CheckpointWriter w;
  writing_ = "the checkpoint " + tmp;
  PetscCall(InterruptWhileWriting(tmp));
  w.BetweenDeclarations([this, &tmp] { return InterruptWhileWriting(tmp); });
  PetscCall(w.Open(comm_, tmp));
  {
    std::string integrator;
    TSAdapt     adapt;
    TSAdaptType adapt_type;
    PetscCall(IntegratorName(ts_, &integrator));
    PetscCall(TSGetAdapt(ts_, &adapt));
    PetscCall(TSAdaptGetType(adapt, &adapt_type));
    PetscCall(w.Attribute("format_version", kCheckpointVersion));
    PetscCall(w.Attribute("mode", mode_));
    PetscCall(w.Attribute("ranks", (PetscInt)size));
    PetscCall(w.Attribute("integrator", integrator));
    PetscCall(w.Attribute("adapt_type", adapt_type ? adapt_type : ""));
  }
  {
    std::vector<std::pair<std::string, std::string>> fp;
    std::string                                      text;
    PetscCall(CheckpointFingerprint(fp));
    for (auto &kv : fp) text += kv.first + "=" + kv.second + "\n";
    PetscCall(w.Text("fingerprint", text));
    PetscCall(w.Text("parameters", params_.Text()));
  }
  {
    /* the time series so far (rank 0 writes them): a restart writes them again and goes on */
    std::string files;
    PetscCall(CheckOutputs(SeriesStep::Flush)); /* written whole, or the run stops here */
    for (auto &fc : series_) files += fc.first + "\n";
    PetscCall(BroadcastString(comm_, &files));
    PetscCall(w.Text("series", files));
    size_t k = 0;
    for (size_t a = 0, b; (b = files.find('\n', a)) != std::string::npos; a = b + 1, k++) {
      std::string text;
      if (rank == 0) PetscCall(series_[k].second->Contents(&text));
      PetscCall(w.Text(files.substr(a, b - a), text));
    }
  }
  PetscCall(w.State(all, numbering));
  PetscCall(w.Close());
  PetscCall(held.Release());
  PetscReal bytes  = 0;
  int       failed = 0;
  if (rank == 0) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (!ec) {
      const std::string link = latest + ".tmp";
      fs::remove(link, ec);
      fs::create_hard_link(path, link, ec);
      if (ec) fs::copy_file(path, link, fs::copy_options::overwrite_existing, ec);
      if (!ec) fs::rename(link, latest, ec);
    }
    failed = ec ? 1 : 0;
    if (!failed) bytes = (PetscReal)fs::file_size(path, ec);
    if (!failed) { /* the oldest beyond -checkpoint_keep go (checkpoint.h5 links the latest) */
      ckpt_kept_.push_back(path);
      while (ckpt_keep_ > 0 && (PetscInt)ckpt_kept_.size() > ckpt_keep_) {
        fs::remove(ckpt_kept_.front(), ec);
        ckpt_kept_.pop_front();
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm_));
  PetscCheck(!failed, comm_, PETSC_ERR_FILE_WRITE, "Checkpoint: cannot rename %s to %s and link it as %s", tmp.c_str(), path.c_str(), latest.c_str());
  PetscCallMPI(MPI_Bcast(&bytes, 1, MPIU_REAL, 0, comm_));
  PetscCall(PetscTime(&t1));
  if (step == ckpt_last_step_ + 1 && ckpt_count_ > 0 && !ckpt_every_step_warned_) { /* checkpoints as many as steps */
    ckpt_every_step_warned_ = true;
    PetscCall(PetscPrintf(comm_,
                          "WARNING: a checkpoint at every step (steps %" PetscInt_FMT " and %" PetscInt_FMT
                          "): -checkpoint_interval %g µs or -checkpoint_wall_interval %g s is shorter than a step or a checkpoint's writing (%.3g s); "
                          "only the last %" PetscInt_FMT " are kept (-checkpoint_keep)\n",
                          ckpt_last_step_, step, (double)ckpt_interval_, (double)ckpt_wall_, t1 - t0, ckpt_keep_));
  }
  ckpt_seconds_ += t1 - t0;
  ckpt_bytes_     = bytes;
  ckpt_wall_last_ = t1;
  ckpt_last_step_ = step;
  ckpt_last_file_ = path;
  writing_.clear();
  ckpt_count_++;
  if (ckpt_interval_ > 0) ckpt_next_ = ckpt_interval_ * (std::floor(t / ckpt_interval_ * (1 + 1e-12)) + 1); /* the next multiple after t */
  PetscCall(PetscInfo(ts_, "Checkpoint %s at t = %g (step %" PetscInt_FMT "): %.0f bytes in %.3f s\n", path.c_str(), (double)t, step, (double)bytes, t1 - t0));
  PetscCall(PetscLogEventEnd(ev_ckpt_write_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The first message of an error raised while the checkpoint is read (the read errors are
   reported as one message naming the option and the file). */
static PetscErrorCode KeepFirstError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess,
                                     void *ctx)
{
  std::string *first = (std::string *)ctx;
  if (!first->empty()) return n;
  if (mess && std::strstr(mess, kFailedOnAnotherRank)) return n; /* AgreeOnError's: the failing rank's message is the one to report */
  /* a state that does not fit this run or a damaged dataset (FILE_UNEXPECTED), or a file that cannot be read */
  *first = std::string(n == PETSC_ERR_FILE_UNEXPECTED ? "U:" : "R:") + (mess && mess[0] ? mess : std::string("error in ") + (fun ? fun : "?"));
  return n;
}

/* Every check that does not need the state read, then the state. A problem with the file's
   contents (another scene, a value out of range) goes to *problem; errors are a file that cannot
   be read or does not fit. */
PetscErrorCode TimeRun::ReadCheckpointFile(CheckpointReader &file, std::string *problem)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  {
    bool     has;
    PetscInt version;
    PetscCall(file.HasAttribute("format_version", &has));
    if (!has) {
      *problem = "not a turgor checkpoint (no format_version)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(file.Attribute("format_version", &version));
    if (version != kCheckpointVersion) {
      *problem = "checkpoint format version " + std::to_string((long long)version) + "; this turgor reads version " +
                 std::to_string((long long)kCheckpointVersion) +
                 (version < kCheckpointVersion ? " (older checkpoints cannot be continued: run again from the start)" : "");
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    std::string mode, theirs, ours, adapt_theirs;
    PetscCall(file.Attribute("mode", &mode));
    if (mode != mode_) {
      *problem = "written by -mode " + mode + ", this run is -mode " + mode_;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(IntegratorName(ts_, &ours));
    PetscCall(file.Attribute("integrator", &theirs));
    if (theirs != ours) {
      *problem = "integrated with -ts_type " + theirs + ", this run with " + ours + " (give the same integrator)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    TSAdapt     adapt;
    TSAdaptType adapt_type;
    PetscCall(TSGetAdapt(ts_, &adapt));
    PetscCall(TSAdaptGetType(adapt, &adapt_type));
    PetscCall(file.Attribute("adapt_type", &adapt_theirs));
    if (adapt_theirs != (adapt_type ? adapt_type : "")) {
      *problem = "integrated with -ts_adapt_type " + adapt_theirs + ", this run with " + adapt_type + " (give the same step-size controller)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    std::vector<std::pair<std::string, std::string>> fp;
    std::string                                      text, diff;
    PetscCall(CheckpointFingerprint(fp));
    PetscCall(file.Text("fingerprint", &text));
    for (auto &kv : fp) {
      std::string       theirs = "(none)";
      const std::string key    = kv.first + "=";
      for (size_t a = 0, b; (b = text.find('\n', a)) != std::string::npos; a = b + 1)
        if (text.compare(a, key.size(), key) == 0) theirs = text.substr(a + key.size(), b - a - key.size());
      if (theirs != kv.second) diff += (diff.empty() ? "" : "; ") + kv.first + " " + theirs + " in the checkpoint, " + kv.second + " in this scene";
    }
    if (!diff.empty()) {
      *problem = "the checkpoint is from another scene: " + diff + " (give the scene options of the run that wrote it)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    /* every physics parameter as the run that wrote it had it, but those -restart_allow names */
    std::string text, listed, names;
    PetscCall(file.Text("parameters", &text));
    restart_changed_.clear();
    const std::vector<std::string> diff = ParameterList::Differences(ParameterList::FromText(text), params_, restart_allow_, &restart_changed_);
    for (const std::string &d : diff) {
      listed += (listed.empty() ? "" : "; ") + d;
      const std::string n = d.substr(1, d.find(':') - 1);
      names += (names.empty() ? "" : ",") + n;
    }
    if (!diff.empty()) {
      *problem = "the physics differs from the checkpoint's run: " + listed + " (give the options of the run that wrote it, or -restart_allow " + names +
                 " to change them on purpose)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  /* the declarations, and whether this run holds what the writing run held */
  std::vector<PetscInt> ids;
  {
    IS order;
    PetscCall(StateOrder(&order));
    PetscCall(StateIds(U_, order, ids));
    PetscCall(ISDestroy(&order));
  }
  const Numbering numbering(*this, std::move(ids));
  PetscInt        writers;
  bool            same;
  PetscCall(file.Layouts(numbering, &writers, &same));
  if (!same) {
    std::string why;
    if (!RestartsOnOtherRanks(&why)) {
      *problem = "written on " + std::to_string((long long)writers) + " MPI ranks with another distribution of the state than this run's " +
                 std::to_string((long long)size) + " (continue on the same number of ranks and distribution: " + why + ")";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(BeforeStateRead());
  {
    PetscInt n;
    PetscCall(VecGetLocalSize(U_, &n));
    solution_.assign((size_t)n, 0.0);
    solution_view_ = {solution_.data(), solution_.size()};
  }
  std::deque<StateDeclaration> decls;
  PetscCall(DeclareAll(decls));
  std::vector<StateDeclaration *> all;
  for (StateDeclaration &d : decls) all.push_back(&d);
  PetscCall(file.State(all, numbering));
  /* the run's place, checked before it is used */
  const RunRecord &r = record_;
  if (!(std::isfinite(r.time) && r.time >= 0 && std::isfinite(r.dt) && r.dt > 0 && r.step >= 0 && (r.step > 0 || r.time == 0) && std::isfinite(r.t_final) &&
        r.t_final > 0 && r.samples >= 1 && r.snapshots >= 0 && r.sample >= 0 && r.sample <= r.samples + 1 && r.snapshot >= 0 &&
        r.snapshot <= r.snapshots + 1)) {
    char buf[400];
    PetscCall(PetscSNPrintf(buf, sizeof buf,
                            "its run record is out of range (time %g, step %" PetscInt_FMT ", next step size %g, schedule %g µs with %" PetscInt_FMT
                            " samples and %" PetscInt_FMT " snapshots, next %" PetscInt_FMT " and %" PetscInt_FMT "): the file was edited or damaged",
                            (double)r.time, r.step, (double)r.dt, (double)r.t_final, r.samples, r.snapshots, r.sample, r.snapshot));
    *problem = buf;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!(r.time < t_final_)) {
    *problem = "written at t = " + std::to_string((double)r.time) + " µs, not before -ts_max_time = " + std::to_string((double)t_final_) +
               " µs: nothing to continue";
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  {
    PetscScalar *u;
    PetscCall(VecGetArray(U_, &u));
    std::copy(solution_.begin(), solution_.end(), u);
    PetscCall(VecRestoreArray(U_, &u));
    std::vector<PetscReal>().swap(solution_);
    solution_view_ = SolutionSpan();
  }
  PetscCall(TSSetTime(ts_, r.time));
  PetscCall(TSSetStepNumber(ts_, r.step));
  {
    /* the checkpoint's next step, or this run's where its step options were changed on purpose
       (-restart_allow ts_dt, or fine_dt_safety: it applies from the restart on) */
    /* a fixed step follows this run's options (-fine_dt_safety, -ts_dt, or the physics it derives
       from, changed on purpose); an adaptive one goes on from the checkpoint's unless -ts_dt changed */
    bool changed = false;
    if (fit_fixed_) changed = r.first_step != dt_start_;
    else
      for (const std::string &c : restart_changed_) changed = changed || c.compare(0, 7, "-ts_dt:") == 0;
    PetscCall(TSSetTimeStep(ts_, changed ? dt_start_ : r.dt));
    if (fit_fixed_ && (changed || r.t_final != t_final_)) PetscCall(FitFixedSteps(r.time, r.step)); /* whole steps to this run's end */
    if (changed) {
      PetscReal dt;
      PetscCall(TSGetTimeStep(ts_, &dt));
      PetscCall(PetscPrintf(comm_, "Restart at t = %g µs: the step size is this run's, %g µs (the checkpoint's next step was %g µs)\n", (double)r.time,
                            (double)dt, (double)r.dt));
    }
  }
  PetscCall(integrator_.Restore(ts_));
  {
    /* another -ts_max_time or sample count (a run extended): the samples follow this run's schedule
       from the first one after t (the rows already written stay) */
    PetscInt sample = r.sample, snapshot = r.snapshot;
    if (r.t_final != t_final_ || r.samples != out_.samples || r.snapshots != out_.snapshots) {
      const PetscReal u = (r.time + 1e-9 * t_final_) / t_final_; /* the sampler's tolerance */
      sample            = (PetscInt)std::floor(u * out_.samples) + 1;
      snapshot          = out_.snapshots > 0 ? (PetscInt)std::floor(u * out_.snapshots) + 1 : 0;
      PetscCall(PetscPrintf(comm_,
                            "Restart at t = %g µs: -ts_max_time or the sample counts differ from the checkpoint's run (%g µs, %" PetscInt_FMT
                            " samples): the samples continue on this run's schedule\n",
                            (double)r.time, (double)r.t_final, r.samples));
    }
    sampler_.SetPosition(sample, snapshot);
  }
  PetscCall(AfterStateRead(r.time, U_, file.Matched()));
  {
    /* the time series as they were at the checkpoint (OpenSeries writes them again) */
    std::string files;
    PetscCall(file.Text("series", &files));
    restart_text_.clear();
    for (size_t a = 0, b; (b = files.find('\n', a)) != std::string::npos; a = b + 1) {
      std::string text;
      PetscCall(file.Text(files.substr(a, b - a), &text));
      restart_text_.push_back({files.substr(a, b - a), text});
    }
  }
  restart_step_   = r.step;
  ckpt_last_step_ = r.step;
  t_last_         = r.time;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -restart: the file must exist, be a whole checkpoint of this format, mode, integrator and scene,
   and the output directory must not hold another run's time series (unless -output_overwrite);
   anything else is refused naming the option and the file. */
PetscErrorCode TimeRun::ReadCheckpoint()
{
  const char *file = restart_file_.c_str();
  PetscMPIInt rank;
  int         exists = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_ckpt_read_, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    std::error_code ec;
    exists = std::filesystem::is_regular_file(restart_file_, ec) ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, comm_));
  PetscCheck(exists, comm_, PETSC_ERR_FILE_OPEN, "Option -restart %s: no such checkpoint file", file);
  std::string      first, problem;
  CheckpointReader reader;
  H5E_auto2_t      hfunc;
  void            *hdata;
  H5Eget_auto2(H5E_DEFAULT, &hfunc, &hdata);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's own error stack would bury the message */
  PetscCall(PetscPushErrorHandler(KeepFirstError, &first));
  reader.SetReadRows(restart_read_rows_);
  PetscErrorCode ierr = reader.Open(comm_, file);
  if (!ierr) ierr = ReadCheckpointFile(reader, &problem);
  (void)reader.Close();
  PetscCall(PetscPopErrorHandler());
  H5Eset_auto2(H5E_DEFAULT, hfunc, hdata);
  {
    int bad = ierr ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_));
    std::string message = first.size() > 2 ? first.substr(2) : std::string("read error on another rank");
    const bool  unfit   = first.compare(0, 2, "U:") == 0;
    if (bad) { /* the first rank's message, on every rank */
      int has = !first.empty(), any;
      PetscCallMPI(MPI_Allreduce(&has, &any, 1, MPI_INT, MPI_MAX, comm_));
      PetscMPIInt from = has ? rank : PETSC_MPI_INT_MAX, root;
      PetscCallMPI(MPI_Allreduce(&from, &root, 1, MPI_INT, MPI_MIN, comm_));
      if (any) {
        std::vector<char> buf(message.begin(), message.end());
        PetscMPIInt       len = (PetscMPIInt)buf.size();
        PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, root, comm_));
        buf.resize((size_t)len);
        PetscCallMPI(MPI_Bcast(buf.data(), len, MPI_CHAR, root, comm_));
        message.assign(buf.begin(), buf.end());
      }
    }
    PetscCheck(!bad, comm_, PETSC_ERR_FILE_READ, "Option -restart %s: %s: %s", file,
               unfit ? "the checkpoint does not fit this run, or was edited or damaged"
                     : "cannot read the checkpoint (truncated, damaged or not a turgor checkpoint)",
               message.c_str());
  }
  PetscCheck(problem.empty(), comm_, PETSC_ERR_ARG_INCOMP, "Option -restart %s: %s", file, problem.c_str());
  {
    /* the output directory: its time series must be this run's (their rows up to the checkpoint
       are the checkpoint's), or absent; -output_overwrite replaces another run's */
    std::string others;
    if (rank == 0 && out_.ready)
      for (const auto &ft : restart_text_) {
        const std::string path = out_.dir + "/" + ft.first;
        std::ifstream     in(path, std::ios::binary);
        if (!in) continue;
        std::string have((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (have.compare(0, ft.second.size(), ft.second) != 0) others += (others.empty() ? "" : ", ") + ft.first;
      }
    PetscCall(BroadcastString(comm_, &others));
    if (!others.empty() && !out_.overwrite) out_.ready = false; /* the other run's summary.json stays: this run writes nothing there */
    PetscCheck(others.empty() || out_.overwrite, comm_, PETSC_ERR_ARG_INCOMP,
               "Option -restart %s: -output_dir %s holds another run's outputs (%s: their rows up to the checkpoint are not the checkpoint's); give "
               "-output_overwrite to replace them, or another -output_dir",
               file, out_.dir.c_str(), others.c_str());
  }
  PetscCall(PetscLogEventEnd(ev_ckpt_read_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
