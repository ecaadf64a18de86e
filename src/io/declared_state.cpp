#include <turgor/io/declared_state.h>

namespace turgor {

const char *StateEntityName(StateEntity e)
{
  switch (e) {
  case StateEntity::Rank:
    return "rank";
  case StateEntity::Particle:
    return "particle";
  case StateEntity::Bar:
    return "bar";
  case StateEntity::Cell:
    return "cell";
  case StateEntity::MaterialPoint:
    return "material point";
  case StateEntity::StateEntry:
    return "state entry";
  }
  return "?";
}

StateTable &StateTable::Rows(std::function<size_t()> count, std::function<PetscInt(size_t)> local, std::function<bool(size_t)> owned)
{
  count_ = std::move(count);
  local_ = std::move(local);
  owned_ = std::move(owned);
  return *this;
}

StateTable &StateTable::Records(std::function<size_t()> count, std::function<std::uint64_t(size_t)> key, std::function<void(size_t)> resize,
                                const std::string &anchor)
{
  count_  = std::move(count);
  key_    = std::move(key);
  resize_ = std::move(resize);
  anchor_ = anchor;
  return *this;
}

int StateTable::AnchorColumn() const
{
  for (size_t c = 0; c < columns_.size(); c++)
    if (columns_[c].name == anchor_) return (int)c;
  return -1;
}

StateColumn StateTable::Real1(const std::string &name, std::function<PetscReal(size_t)> get, std::function<void(size_t, PetscReal)> set, Combine c)
{
  StateColumn col;
  col.name    = name;
  col.combine = c;
  col.get     = [get](size_t r, PetscReal *v) { v[0] = get(r); };
  col.set     = [set](size_t r, const PetscReal *v) { set(r, v[0]); };
  return col;
}

StateTable &StateTable::Add(StateColumn col)
{
  columns_.push_back(std::move(col));
  return *this;
}

StateTable &StateTable::Column(const std::string &name, std::vector<PetscReal> &v, int width, Combine c)
{
  return Column(
    name, width, [&v, width](size_t r, PetscReal *out) { std::copy(v.begin() + r * width, v.begin() + (r + 1) * width, out); },
    [&v, width](size_t r, const PetscReal *in) { std::copy(in, in + width, v.begin() + r * width); }, c);
}

StateTable &StateTable::Column(const std::string &name, std::vector<PetscInt> &v, int width, Combine c)
{
  return Column(
    name, width,
    [&v, width](size_t r, PetscReal *out) {
      for (int k = 0; k < width; k++) out[k] = (PetscReal)v[r * width + k];
    },
    [&v, width](size_t r, const PetscReal *in) {
      for (int k = 0; k < width; k++) v[r * width + k] = (PetscInt)in[k];
    },
    c, true);
}

StateTable &StateTable::Column(const std::string &name, int width, std::function<void(size_t, PetscReal *)> get,
                               std::function<void(size_t, const PetscReal *)> set, Combine c, bool integer)
{
  StateColumn col;
  col.name    = name;
  col.width   = width;
  col.integer = integer;
  col.combine = c;
  col.get     = std::move(get);
  col.set     = std::move(set);
  return Add(std::move(col));
}

StateTable &StateTable::Ragged(const std::string &name, std::function<void(size_t, std::vector<PetscReal> &)> get,
                               std::function<PetscErrorCode(size_t, const PetscReal *, size_t)> set, bool integer)
{
  StateColumn col;
  col.name       = name;
  col.width      = 0;
  col.integer    = integer;
  col.get_ragged = std::move(get);
  col.set_ragged = std::move(set);
  return Add(std::move(col));
}

StateTable &StateDeclaration::Scalars()
{
  for (StateTable &t : tables_)
    if (t.Entity() == StateEntity::Rank && t.Name() == "scalars") return t;
  tables_.emplace_front("scalars", StateEntity::Rank);
  tables_.front().Rows([] { return (size_t)1; });
  return tables_.front();
}

void StateDeclaration::Scalar(const std::string &name, PetscReal *v, Combine c)
{
  Scalars().Column(
    name, 1, [v](size_t, PetscReal *out) { out[0] = *v; }, [v](size_t, const PetscReal *in) { *v = in[0]; }, c);
}

void StateDeclaration::Scalar(const std::string &name, PetscInt *v, Combine c)
{
  Scalars().Column(
    name, 1, [v](size_t, PetscReal *out) { out[0] = (PetscReal)*v; }, [v](size_t, const PetscReal *in) { *v = (PetscInt)in[0]; }, c, true);
}

void StateDeclaration::Scalar(const std::string &name, bool *v, Combine c)
{
  Scalars().Column(
    name, 1, [v](size_t, PetscReal *out) { out[0] = *v ? 1 : 0; }, [v](size_t, const PetscReal *in) { *v = in[0] != 0; }, c, true);
}

void StateDeclaration::Scalar(const std::string &name, PetscBool *v, Combine c)
{
  Scalars().Column(
    name, 1, [v](size_t, PetscReal *out) { out[0] = *v ? 1 : 0; }, [v](size_t, const PetscReal *in) { *v = in[0] != 0 ? PETSC_TRUE : PETSC_FALSE; }, c, true);
}

void StateDeclaration::Vector(const std::string &name, std::vector<PetscReal> *v, Combine c)
{
  const int n = (int)v->size();
  if (n == 0) return; /* nothing to keep (a width of 0 would read as a ragged column) */
  Scalars().Column(
    name, n, [v, n](size_t, PetscReal *out) { std::copy(v->begin(), v->begin() + n, out); },
    [v, n](size_t, const PetscReal *in) { std::copy(in, in + n, v->begin()); }, c);
}

void StateDeclaration::Array(const std::string &name, PetscReal *v, int n, Combine c)
{
  if (n == 0) return;
  Scalars().Column(
    name, n, [v, n](size_t, PetscReal *out) { std::copy(v, v + n, out); }, [v, n](size_t, const PetscReal *in) { std::copy(in, in + n, v); }, c);
}

void StateDeclaration::Sequence(const std::string &name, std::vector<PetscReal> *v, Combine c)
{
  Sequence(
    name, [v](std::vector<PetscReal> &out) { out = *v; },
    [v](const PetscReal *in, size_t n) {
      v->assign(in, in + n);
      return PETSC_SUCCESS;
    },
    c);
}

void StateDeclaration::Sequence(const std::string &name, std::function<void(std::vector<PetscReal> &)> get,
                                std::function<PetscErrorCode(const PetscReal *, size_t)> set, Combine c)
{
  StateTable &t = Scalars();
  t.Ragged(
    name, [get](size_t, std::vector<PetscReal> &out) { get(out); }, [set](size_t, const PetscReal *in, size_t n) { return set(in, n); });
  t.SetLastCombine(c);
}

void StateDeclaration::Include(StateDeclaration &&part)
{
  for (StateTable &t : part.tables_) {
    tables_.push_back(std::move(t));
    tables_.back().Rename(part.name_ + "." + tables_.back().Name());
  }
  part.tables_.clear();
}

StateTable &StateDeclaration::Table(const std::string &name, StateEntity e)
{
  tables_.emplace_back(name, e);
  return tables_.back();
}

std::vector<std::string> NestedColumns(const StateDeclaration &d)
{
  std::vector<std::string> names;
  for (const StateTable &t : d.Tables()) {
    names.push_back(t.Name() + ".rows");
    for (const StateColumn &c : t.Columns()) names.push_back(t.Name() + "." + c.name);
  }
  return names;
}

PetscErrorCode PackNested(const StateDeclaration &d, std::vector<std::vector<PetscReal>> &columns)
{
  std::vector<PetscReal> buf;
  PetscFunctionBeginUser;
  columns.clear();
  for (const StateTable &t : d.Tables()) {
    const size_t n = t.Count();
    columns.push_back({(PetscReal)n});
    for (const StateColumn &c : t.Columns()) {
      std::vector<PetscReal> v;
      for (size_t r = 0; r < n; r++) {
        if (c.width > 0) {
          buf.resize((size_t)c.width);
          c.get(r, buf.data());
        } else {
          buf.clear();
          c.get_ragged(r, buf);
          v.push_back((PetscReal)buf.size());
        }
        v.insert(v.end(), buf.begin(), buf.end());
      }
      columns.push_back(std::move(v));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UnpackNested(StateDeclaration &d, const std::vector<std::vector<PetscReal>> &columns)
{
  size_t k = 0;
  PetscFunctionBeginUser;
  PetscCheck(columns.size() == NestedColumns(d).size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %zu parts of its state, %zu declared",
             d.Name().c_str(), columns.size(), NestedColumns(d).size());
  for (StateTable &t : d.Tables()) {
    const std::vector<PetscReal> &rows = columns[k++];
    PetscCheck(rows.size() == 1 && rows[0] >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s.rows is not a count", d.Name().c_str(), t.Name().c_str());
    const size_t n = (size_t)rows[0];
    if (t.IsRecords()) t.Resize(n);
    else
      PetscCheck(n == t.Count(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %zu rows of %s, this one has %zu", d.Name().c_str(), n, t.Name().c_str(),
                 t.Count());
    for (const StateColumn &c : t.Columns()) {
      const std::vector<PetscReal> &v  = columns[k++];
      size_t                        at = 0;
      for (size_t r = 0; r < n; r++) {
        size_t w = (size_t)c.width;
        if (c.width == 0) {
          PetscCheck(at < v.size() && v[at] >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s.%s is cut short", d.Name().c_str(), t.Name().c_str(),
                     c.name.c_str());
          w = (size_t)v[at++];
        }
        PetscCheck(at + w <= v.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s.%s is cut short", d.Name().c_str(), t.Name().c_str(),
                   c.name.c_str());
        if (c.width > 0) c.set(r, v.data() + at);
        else PetscCall(c.set_ragged(r, v.data() + at, w));
        at += w;
      }
      PetscCheck(at == v.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %s.%s has %zu values more than its rows", d.Name().c_str(), t.Name().c_str(),
                 c.name.c_str(), v.size() - at);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PackState(const StateDeclaration &d, std::vector<PetscReal> &out)
{
  std::vector<std::vector<PetscReal>> cols;
  PetscFunctionBeginUser;
  PetscCall(PackNested(d, cols));
  out.assign(1, (PetscReal)cols.size());
  for (const auto &c : cols) {
    out.push_back((PetscReal)c.size());
    out.insert(out.end(), c.begin(), c.end());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UnpackState(StateDeclaration &d, const PetscReal *in, size_t n)
{
  std::vector<std::vector<PetscReal>> cols;
  size_t                              at = 1;
  PetscFunctionBeginUser;
  PetscCheck(n >= 1, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: its state is empty", d.Name().c_str());
  cols.resize((size_t)in[0]);
  for (auto &c : cols) {
    PetscCheck(at < n && at + 1 + (size_t)in[at] <= n, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: its state is cut short", d.Name().c_str());
    c.assign(in + at + 1, in + at + 1 + (size_t)in[at]);
    at += 1 + c.size();
  }
  PetscCall(UnpackNested(d, cols));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
