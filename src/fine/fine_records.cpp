#include <turgor/fine/fine_records.h>
#include <turgor/parallel/rank_reductions.h>
#include <cmath>

namespace turgor {

PetscErrorCode FineRecords::SetUp(MPI_Comm comm, bool energy, PetscReal tolerance, bool distributed, ForceModel &model, const Controls &controls,
                                  const ParticleSet &P, const PetscReal *x0, const PetscReal *v0)
{
  PetscFunctionBeginUser;
  comm_        = comm;
  tolerance_   = tolerance;
  energy_on_   = energy;
  distributed_ = distributed;
  model_       = &model;
  if (energy_on_) {
    PetscCall(energy_.SetUp(model, controls, P));
    PetscCall(energy_.Start(comm_, 0, x0, v0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRecords::EnergyRow(PetscReal t, const PetscReal *x, const PetscReal *v)
{
  std::vector<PetscReal> row;
  PetscReal              rel;
  PetscFunctionBeginUser;
  PetscCall(energy_.Row(comm_, x, v, row, &rel));
  row.insert(row.begin(), t);
  if (energy_csv_.IsOpen()) PetscCall(energy_csv_.Row(row));
  /* every rank has the row (a sum over ranks): all fail together */
  PetscCheck(!(tolerance_ > 0) || std::fabs(rel) <= tolerance_, comm_, PETSC_ERR_NOT_CONVERGED,
             "Energy balance: residual %g at t = %g µs, %.3g of the work done on the tissue (or of the energy in play), above -fine_energy_tolerance %g: "
             "energy is created or lost that no term accounts for -- an integration error (halving -fine_dt_safety cuts Verlet's about 4x) or an "
             "unstable step; energy.csv has the balance up to here (-fine_energy_tolerance 0: no check)",
             (double)row[row.size() - 2], (double)t, (double)rel, (double)tolerance_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRecords::Open(const OpenSeries &open, PetscReal t_final, PetscInt samples, bool restarted, const PetscReal *x0, const PetscReal *v0)
{
  PetscFunctionBeginUser;
  std::vector<std::pair<std::string, std::vector<std::string>>> files;
  model_->RecordFiles(files);
  record_names_.clear();
  record_csv_.clear();
  for (auto &f : files) {
    record_names_.push_back(f.first);
    record_csv_.push_back(std::make_unique<CsvWriter>());
    PetscCall(open(*record_csv_.back(), f.first, f.second));
  }
  if (!energy_on_) PetscFunctionReturn(PETSC_SUCCESS);
  std::vector<std::string> columns = {"time"};
  for (const std::string &c : energy_.Columns()) columns.push_back(c);
  energy_every_ = t_final / std::max<PetscInt>(samples, 1);
  PetscCall(open(energy_csv_, "energy.csv", columns));
  if (restarted) PetscFunctionReturn(PETSC_SUCCESS); /* continued: energy_next_ and the sums come from the checkpoint */
  energy_next_ = energy_every_;
  PetscCall(EnergyRow(0, x0, v0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRecords::AfterStep(PetscReal t, const PetscReal *x, const PetscReal *v, PetscReal t_final)
{
  PetscFunctionBeginUser;
  if (!record_csv_.empty()) {
    std::vector<std::pair<std::string, std::vector<std::string>>> rows;
    model_->TakeRecords(rows);
    auto write = [this](const std::string &file, const std::vector<std::string> &cells) {
      PetscFunctionBeginUser;
      for (size_t k = 0; k < record_names_.size(); k++)
        if (record_names_[k] == file && record_csv_[k]->IsOpen()) PetscCall(record_csv_[k]->RowText(cells));
      PetscFunctionReturn(PETSC_SUCCESS);
    };
    if (distributed_) { /* every rank's rows (file, cells...) to rank 0, which writes them, one rank's at a time */
      TextRows mine;
      for (auto &r : rows) {
        mine.push_back({std::move(r.first)});
        for (std::string &c : r.second) mine.back().push_back(std::move(c));
      }
      rows.clear();
      PetscCall(ForEachRowOnFirstRank(comm_, mine, [&write](std::vector<std::string> &row) {
        const std::string file = row.front();
        row.erase(row.begin());
        return write(file, row);
      }));
    } else
      for (auto &r : rows) PetscCall(write(r.first, r.second));
  }
  if (energy_on_) {
    PetscCall(energy_.Step(t, x, v));
    if (t >= energy_next_ * (1 - 1e-12) || t >= t_final * (1 - 1e-12)) {
      PetscCall(EnergyRow(t, x, v));
      while (energy_next_ <= t * (1 + 1e-12)) energy_next_ += energy_every_;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void FineRecords::DeclareState(std::deque<StateDeclaration> &decls)
{
  if (!energy_on_) return;
  decls.emplace_back("energy");
  decls.back().Scalar("next_row", &energy_next_, Combine::Owner);
  energy_.DeclareState(decls.back());
}

PetscErrorCode FineRecords::AddSummary(JsonObject &js) const
{
  PetscFunctionBeginUser;
  if (!energy_on_) PetscFunctionReturn(PETSC_SUCCESS);
  PetscReal wext = energy_.ExternalWork();
  PetscCall(SumOverRanks(comm_, &wext));
  js.Set("energy_residual_max", energy_.LargestRelativeResidual());
  js.Set("energy_external_work", wext);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
