#include <turgor/tissue/tissue_generator.h>

namespace turgor {

PetscErrorCode TissueGeneratorRegister(const char name[], TissueGeneratorCreator create)
{
  return Registry<TissueGenerator>::Instance().Add(name, create);
}

PetscErrorCode TissueGeneratorCreate(MPI_Comm comm, const std::string &name, std::unique_ptr<TissueGenerator> *generator)
{
  return Registry<TissueGenerator>::Instance().Create(comm, name, "-tissue_type", "tissue generator", generator);
}

PetscErrorCode TissueSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char              buf[64];
  const std::string help = "Tissue generator: " + Registry<TissueGenerator>::Instance().Names();
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buf, type.c_str(), sizeof buf));
  PetscOptionsBegin(comm, "tissue_", "Tissue", "turgor");
  PetscCall(TurgorOptionsString(params, "-type", help.c_str(), "TissueSpec", buf, buf, sizeof buf, NULL));
  PetscOptionsEnd();
  type = buf;
  PetscCall(TissueGeneratorCreate(comm, type, &generator_));
  PetscCall(generator_->SetFromOptions(comm, params));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissueSpec::Generate(MPI_Comm comm, Tissue *tissue) const
{
  PetscFunctionBeginUser;
  PetscCheck(generator_, comm, PETSC_ERR_ORDER, "TissueSpec::SetFromOptions() must be called before Generate()");
  PetscCall(generator_->Generate(comm, tissue));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
