#include <turgor/fine/particle_output.h>
#include <petscdmswarm.h>

namespace turgor {

PetscErrorCode CreateParticleSwarm(MPI_Comm comm, const ParticleSet &P, PetscInt n_local, DM *swarm)
{
  PetscInt   *kind, *cell;
  PetscInt64 *pid;
  PetscFunctionBeginUser;
  PetscCall(DMCreate(comm, swarm));
  PetscCall(PetscObjectSetName((PetscObject)*swarm, "tissue"));
  PetscCall(DMSetType(*swarm, DMSWARM));
  PetscCall(DMSetDimension(*swarm, 2));
  PetscCall(DMSwarmSetType(*swarm, DMSWARM_BASIC));
  PetscCall(DMSwarmRegisterPetscDatatypeField(*swarm, "kind", 1, PETSC_INT));
  PetscCall(DMSwarmRegisterPetscDatatypeField(*swarm, "cell", 1, PETSC_INT));
  PetscCall(DMSwarmFinalizeFieldRegister(*swarm));
  PetscCall(DMSwarmSetLocalSizes(*swarm, n_local, 0));
  PetscCall(DMSwarmGetField(*swarm, "kind", NULL, NULL, (void **)&kind));
  PetscCall(DMSwarmGetField(*swarm, "cell", NULL, NULL, (void **)&cell));
  PetscCall(DMSwarmGetField(*swarm, DMSwarmField_pid, NULL, NULL, (void **)&pid));
  for (PetscInt i = 0; i < n_local; i++) { /* the owned particles come first */
    kind[i] = P.kind[i];
    cell[i] = P.cell[i];
    pid[i]  = P.gid[i];
  }
  PetscCall(DMSwarmRestoreField(*swarm, DMSwarmField_pid, NULL, NULL, (void **)&pid));
  PetscCall(DMSwarmRestoreField(*swarm, "cell", NULL, NULL, (void **)&cell));
  PetscCall(DMSwarmRestoreField(*swarm, "kind", NULL, NULL, (void **)&kind));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AddTermSnapshotFields(ForceModel &model, const ParticleSet &P, const ParticleSnapshotWriter &writer, const PetscReal *x, const PetscReal *v,
                                     ParticleSnapshotWriter::Fields *fields)
{
  std::vector<TermField>    terms;
  std::vector<TermSegments> segs;
  PetscFunctionBeginUser;
  PetscCall(model.OutputFields(x, v, terms));
  PetscCall(model.OutputSegments(x, v, segs));
  for (TermSegments &g : segs) {
    ParticleSnapshotWriter::Segments w{g.name, std::move(g.xy), std::move(g.id), {}};
    for (TermField &f : g.fields) w.fields.push_back({f.name, f.unit, std::move(f.values), 1});
    fields->segments.push_back(std::move(w));
  }
  /* this rank's bars and closed cells (they come first: particles.h) */
  size_t closed = 0;
  for (size_t c = 0; c < P.OwnedPolygons(); c++) closed += !P.polygons[c].open && P.polygons[c].nodes.size() >= 3;
  for (TermField &f : terms) {
    if (f.where == TermField::CELL && writer.Cells() == 0) continue; /* no cells grid on any rank (the square grid) */
    f.values.resize(f.where == TermField::CELL ? closed : P.OwnedSprings());
    (f.where == TermField::CELL ? fields->cells : fields->bars).push_back({f.name, f.unit, std::move(f.values), 1});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
