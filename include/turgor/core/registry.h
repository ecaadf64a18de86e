#pragma once
/* Named families of constructors on PETSc's PetscFunctionList, the mechanism behind TSRegister():
   physics terms, materials, tissue generators and run modes. Adding one is one new file plus one
   registration line in src/app/register_all.cpp; nothing else names the concrete types, and no
   code asks an object what it is.

   The lists are process-wide like PETSc's own type lists (TSList, ...): they are filled by
   TurgorRegisterAll() and emptied at PetscFinalize(). */
#include <turgor/core/petsc_compat.h>
#include <algorithm>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace turgor {

template <class Product>
class Registry {
public:
  using Creator = PetscErrorCode (*)(MPI_Comm, std::unique_ptr<Product> *);

  static Registry &Instance()
  {
    static Registry registry;
    return registry;
  }

  PetscErrorCode Add(const char name[], Creator create)
  {
    PetscFunctionBeginUser;
    if (!finalize_registered_) {
      PetscCall(PetscRegisterFinalize(Finalize));
      finalize_registered_ = true;
    }
    PetscCall(PetscFunctionListAdd(&list_, name, create));
    if (std::find(names_.begin(), names_.end(), name) == names_.end()) names_.push_back(name);
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  /* An unknown name is an error naming `option`, the value and the known names. */
  PetscErrorCode Create(MPI_Comm comm, const std::string &name, const char *option, const char *what, std::unique_ptr<Product> *out) const
  {
    Creator create = nullptr;
    PetscFunctionBeginUser;
    PetscCall(PetscFunctionListFind(list_, name.c_str(), &create));
    PetscCheck(create, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option %s: unknown %s '%s' (known: %s)", option, what, name.c_str(), Names().c_str());
    PetscCall(create(comm, out));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  bool Has(const std::string &name) const { return std::find(names_.begin(), names_.end(), name) != names_.end(); }

  /* "a, b, c" in registration order (for messages and -help). */
  std::string Names() const
  {
    std::string s;
    for (const std::string &n : names_) s += (s.empty() ? "" : ", ") + n;
    return s;
  }

private:
  static PetscErrorCode Finalize()
  {
    Registry &r = Instance();
    PetscFunctionBeginUser;
    PetscCall(PetscFunctionListDestroy(&r.list_));
    r.names_.clear();
    r.finalize_registered_ = false;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscFunctionList        list_ = nullptr;
  std::vector<std::string> names_;
  bool                     finalize_registered_ = false;
};

/* The creator of a default-constructed Concrete (constructed from the communicator if it takes one). */
template <class Product, class Concrete>
PetscErrorCode CreateInstance(MPI_Comm comm, std::unique_ptr<Product> *out)
{
  PetscFunctionBeginUser;
  if constexpr (std::is_constructible_v<Concrete, MPI_Comm>) *out = std::make_unique<Concrete>(comm);
  else *out = std::make_unique<Concrete>();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
