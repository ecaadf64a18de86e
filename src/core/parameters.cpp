#include <turgor/core/parameters.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace turgor {

void ParameterList::Set(const std::string &option, const std::string &value)
{
  for (auto &kv : items_)
    if (kv.first == option) {
      kv.second = value;
      return;
    }
  items_.push_back({option, value});
}

void ParameterList::Merge(const ParameterList &other)
{
  for (const auto &kv : other.items_) Set(kv.first, kv.second);
}

std::string ParameterList::Text() const
{
  std::string t;
  for (const auto &kv : items_) t += kv.first + "=" + kv.second + "\n";
  return t;
}

ParameterList ParameterList::FromText(const std::string &text)
{
  ParameterList l;
  for (size_t a = 0, b; (b = text.find('\n', a)) != std::string::npos; a = b + 1) {
    const size_t eq = text.find('=', a);
    if (eq == std::string::npos || eq > b) continue;
    l.Set(text.substr(a, eq - a), text.substr(eq + 1, b - eq - 1));
  }
  return l;
}

/* Equal values: the same text, or the same numbers however written (0.3 and 3e-1). */
static bool SameValue(const std::string &a, const std::string &b)
{
  if (a == b) return true;
  auto numbers = [](const std::string &s, std::vector<double> &v) {
    const char *p = s.c_str();
    while (*p) {
      char        *end;
      const double x = std::strtod(p, &end);
      if (end == p) return false;
      v.push_back(x);
      p = end;
      if (*p == ',') p++;
      else if (*p) return false;
    }
    return !v.empty();
  };
  std::vector<double> x, y;
  return numbers(a, x) && numbers(b, y) && x == y;
}

std::vector<std::string> ParameterList::Differences(const ParameterList &theirs, const ParameterList &ours, const std::vector<std::string> &allowed,
                                                    std::vector<std::string> *changed)
{
  std::vector<std::string> names, out;
  for (const auto &kv : theirs.items_) names.push_back(kv.first);
  for (const auto &kv : ours.items_) names.push_back(kv.first);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  auto find = [](const ParameterList &l, const std::string &n) -> std::string {
    for (const auto &kv : l.items_)
      if (kv.first == n) return kv.second;
    return "";
  };
  for (const std::string &n : names) {
    const std::string a = find(theirs, n), b = find(ours, n);
    if (SameValue(a, b)) continue;
    const std::string line = n + ": " + (a.empty() ? std::string("not set") : a) + " in the checkpoint, " + (b.empty() ? std::string("not set") : b) + " now";
    const std::string bare = n.size() > 1 ? n.substr(1) : n;
    if (std::find(allowed.begin(), allowed.end(), bare) != allowed.end() || std::find(allowed.begin(), allowed.end(), n) != allowed.end()) {
      if (changed) changed->push_back(line);
    } else out.push_back(line);
  }
  return out;
}

/* The shortest decimal that reads back as the same double (0.3, not 0.29999999999999999). */
std::string ParameterValue(PetscReal v)
{
  char buf[40];
  for (int digits = 15; digits <= 17; digits++) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, (double)v);
    if (std::strtod(buf, NULL) == (double)v) break;
  }
  return buf;
}

std::string ParameterValue(const PetscReal *v, PetscInt n)
{
  std::string s;
  for (PetscInt k = 0; k < n; k++) s += (k ? "," : "") + ParameterValue(v[k]);
  return s;
}

std::string ParameterValue(PetscInt v)
{
  return std::to_string((long long)v);
}

std::string ParameterValue(const PetscInt *v, PetscInt n)
{
  std::string s;
  for (PetscInt k = 0; k < n; k++) s += (k ? "," : "") + ParameterValue(v[k]);
  return s;
}

/* The option's full name: the block's prefix after the '-' */
static std::string FullName(PetscOptionItems *items, const char opt[])
{
  const char *prefix = items->prefix;
  return "-" + std::string(prefix ? prefix : "") + std::string(opt[0] == '-' ? opt + 1 : opt);
}

PetscErrorCode TurgorOptionsReal_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscReal current,
                                         PetscReal *value, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal_Private(items, opt, text, man, current, value, set));
  if (list) list->Set(FullName(items, opt), ParameterValue(*value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsInt_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscInt current,
                                        PetscInt *value, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsInt_Private(items, opt, text, man, current, value, set, PETSC_MIN_INT, PETSC_MAX_INT));
  if (list) list->Set(FullName(items, opt), ParameterValue(*value));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsBool_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscBool current,
                                         PetscBool *value, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsBool_Private(items, opt, text, man, current, value, set));
  if (list) list->Set(FullName(items, opt), *value ? "true" : "false");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsString_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                           const char current[], char value[], size_t len, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsString_Private(items, opt, text, man, current, value, len, set));
  if (list) list->Set(FullName(items, opt), value);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsEList_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                          const char *const *names, PetscInt n, const char current[], PetscInt *value, PetscBool *set)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsEList_Private(items, opt, text, man, names, n, current, value, set));
  if (list) list->Set(FullName(items, opt), *value >= 0 && *value < n ? names[*value] : "?");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsRealArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                              PetscReal value[], PetscInt *n, PetscBool *set)
{
  PetscBool given = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsRealArray_Private(items, opt, text, man, value, n, &given));
  if (list) list->Set(FullName(items, opt), given ? ParameterValue(value, *n) : "default");
  if (set) *set = given;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsIntArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                             PetscInt value[], PetscInt *n, PetscBool *set)
{
  PetscBool given = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsIntArray_Private(items, opt, text, man, value, n, &given));
  if (list) list->Set(FullName(items, opt), given ? ParameterValue(value, *n) : "default");
  if (set) *set = given;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsStringArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                                char *value[], PetscInt *n, PetscBool *set)
{
  PetscBool given = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsStringArray_Private(items, opt, text, man, value, n, &given));
  std::string s = "default";
  if (given) {
    s.clear();
    for (PetscInt k = 0; k < *n; k++) s += (k ? "," : "") + std::string(value[k] ? value[k] : "");
  }
  if (list) list->Set(FullName(items, opt), s);
  if (set) *set = given;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TurgorOptionsRecord_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const std::string &value)
{
  PetscFunctionBeginUser;
  if (list) list->Set(FullName(items, opt), value);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
