#pragma once
/* XDMF (2.0) files that describe HDF5 datasets to ParaView (its Xdmf3 readers and its legacy XDMF
   reader): a Domain with the unit system, temporal collections of uniform grids, each grid a
   topology, a geometry and attributes, every DataItem a dataset of one HDF5 file. Units are
   <Information> elements: "units" on the Domain, "unit" on the geometry and on each attribute (an
   integer attribute says what its "values" mean instead). The first rank of the communicator
   writes; every rank calls. */
#include <turgor/core/petsc_compat.h>
#include <turgor/io/output.h>
#include <cstddef>
#include <memory>
#include <string>

namespace turgor {

/* A dataset of the HDF5 file as a DataItem: its dimensions ("N", "N 3"), reals or PetscInts (an IS),
   and its path in the file. */
struct XdmfData {
  std::string dims;
  bool        integer = false;
  std::string path;
};

/* "n", or "n m" when m > 0 */
std::string XdmfDims(long long n, long long m = 0);
/* The path of `name` in snapshot k's group: /snapshot_0003/name */
std::string XdmfSnapshotPath(size_t k, const std::string &name);

class XdmfWriter {
public:
  /* Start the file `path` (written anew): the Domain and its unit system `units`. `h5` is the HDF5
     file's name as the DataItems give it (relative to the XDMF file). */
  PetscErrorCode Open(MPI_Comm comm, const std::string &path, const std::string &h5, const char units[]);
  /* A temporal collection, and in it grid k of the series `name` (name_0003) at `time`. */
  PetscErrorCode BeginCollection(const std::string &name);
  PetscErrorCode BeginGrid(const std::string &name, size_t k, PetscReal time);
  /* `nodes_per_element` 0: not written (Mixed, Quadrilateral). */
  PetscErrorCode Topology(const char type[], long long elements, long long nodes_per_element, const XdmfData &data);
  PetscErrorCode Geometry(const char type[], const char unit[], const XdmfData &data);
  /* `info_name`: "unit" (its value the unit) or "values" (what an integer attribute's values mean). */
  PetscErrorCode Attribute(const std::string &name, const char type[], const char center[], const char info_name[], const std::string &info,
                           const XdmfData &data);
  PetscErrorCode EndGrid();
  PetscErrorCode EndCollection();
  /* Close the Domain and the file; a write that failed is an error on every rank (collective). */
  PetscErrorCode Close();
  XdmfWriter() = default;
  ~XdmfWriter();

private:
  PetscErrorCode DataItem(const XdmfData &data);
  PetscErrorCode Print(const char format[], ...) PETSC_ATTRIBUTE_FORMAT(2, 3);

  MPI_Comm                    comm_ = MPI_COMM_NULL;
  std::unique_ptr<OutputFile> file_; /* rank 0's */
  std::string                 h5_;
};

} // namespace turgor
