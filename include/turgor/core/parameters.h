#pragma once
/* The physics parameters of a run, declared where they are read: an object reads each option that
   changes the physics through TurgorOptions*() inside its PetscOptionsBegin block instead of
   PetscOptions*(), which records the option's full name with the value in effect (given or
   default) in the ParameterList its owner hands down (none: nothing recorded, as in a test that
   configures one object). A checkpoint stores the run's parameters; a restart
   compares its own with them and names every option whose value differs (-restart_allow lets it
   on purpose). Options that do not change the physics (outputs, the end time, reports) are read
   with PetscOptions*() as before and may change freely. */
#include <turgor/core/petsc_compat.h>
#include <petscsys.h>
#include <string>
#include <utility>
#include <vector>

namespace turgor {

class ParameterList {
public:
  /* `option` with its leading '-' and full prefix ("-contact_friction"); a later value replaces an
     earlier one of the same option. */
  void                                                    Set(const std::string &option, const std::string &value);
  void                                                    Merge(const ParameterList &other);
  void                                                    Clear() { items_.clear(); }
  const std::vector<std::pair<std::string, std::string>> &Items() const { return items_; }
  /* "option=value" lines, and back */
  std::string          Text() const;
  static ParameterList FromText(const std::string &text);
  /* The options whose values differ between `ours` and `theirs` (or that one of them lacks), as
     "-opt: <theirs> in the checkpoint, <ours> now" (one string each), in option order. */
  static std::vector<std::string> Differences(const ParameterList &theirs, const ParameterList &ours, const std::vector<std::string> &allowed,
                                              std::vector<std::string> *changed);

private:
  std::vector<std::pair<std::string, std::string>> items_;
};

/* How a value reads in the list: reals to 17 digits, booleans true/false, lists comma-joined. */
std::string ParameterValue(PetscReal v);
std::string ParameterValue(const PetscReal *v, PetscInt n);
std::string ParameterValue(PetscInt v);
std::string ParameterValue(const PetscInt *v, PetscInt n);

/* PetscOptions*_Private and the record of the option (its name with the block's prefix) in `list`. */
PetscErrorCode TurgorOptionsReal_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscReal current,
                                         PetscReal *value, PetscBool *set);
PetscErrorCode TurgorOptionsInt_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscInt current,
                                        PetscInt *value, PetscBool *set);
PetscErrorCode TurgorOptionsBool_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[], PetscBool current,
                                         PetscBool *value, PetscBool *set);
PetscErrorCode TurgorOptionsString_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                           const char current[], char value[], size_t len, PetscBool *set);
PetscErrorCode TurgorOptionsEList_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                          const char *const *names, PetscInt n, const char current[], PetscInt *value, PetscBool *set);
PetscErrorCode TurgorOptionsRealArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                              PetscReal value[], PetscInt *n, PetscBool *set);
PetscErrorCode TurgorOptionsIntArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                             PetscInt value[], PetscInt *n, PetscBool *set);
PetscErrorCode TurgorOptionsStringArray_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const char text[], const char man[],
                                                char *value[], PetscInt *n, PetscBool *set);
/* A value an object fixes from its options in a way the options alone do not show (a list of
   names read as one string and split, say): recorded as `option` = value. */
PetscErrorCode TurgorOptionsRecord_Private(PetscOptionItems *items, ParameterList *list, const char opt[], const std::string &value);

} // namespace turgor

/* Inside a PetscOptionsBegin block (they use its PetscOptionsObject), with the list (a pointer, may be NULL) first. */
#define TurgorOptionsReal(list, opt, text, man, cur, value, set) turgor::TurgorOptionsReal_Private(PetscOptionsObject, list, opt, text, man, cur, value, set)
#define TurgorOptionsInt(list, opt, text, man, cur, value, set)  turgor::TurgorOptionsInt_Private(PetscOptionsObject, list, opt, text, man, cur, value, set)
#define TurgorOptionsBool(list, opt, text, man, cur, value, set) turgor::TurgorOptionsBool_Private(PetscOptionsObject, list, opt, text, man, cur, value, set)
#define TurgorOptionsString(list, opt, text, man, cur, value, len, set) \
  turgor::TurgorOptionsString_Private(PetscOptionsObject, list, opt, text, man, cur, value, len, set)
#define TurgorOptionsEList(list, opt, text, man, names, n, cur, value, set) \
  turgor::TurgorOptionsEList_Private(PetscOptionsObject, list, opt, text, man, names, n, cur, value, set)
#define TurgorOptionsRealArray(list, opt, text, man, value, n, set) \
  turgor::TurgorOptionsRealArray_Private(PetscOptionsObject, list, opt, text, man, value, n, set)
#define TurgorOptionsIntArray(list, opt, text, man, value, n, set) \
  turgor::TurgorOptionsIntArray_Private(PetscOptionsObject, list, opt, text, man, value, n, set)
#define TurgorOptionsStringArray(list, opt, text, man, value, n, set) \
  turgor::TurgorOptionsStringArray_Private(PetscOptionsObject, list, opt, text, man, value, n, set)
#define TurgorOptionsRecord(list, opt, value) turgor::TurgorOptionsRecord_Private(PetscOptionsObject, list, opt, value)
