#include <turgor/io/xdmf.h>

namespace turgor {

std::string XdmfDims(long long n, long long m)
{
  return m > 0 ? std::to_string(n) + " " + std::to_string(m) : std::to_string(n);
}

std::string XdmfSnapshotPath(size_t k, const std::string &name)
{
  char group[32];
  std::snprintf(group, sizeof group, "/snapshot_%04zu/", k);
  return group + name;
}

PetscErrorCode XdmfWriter::Open(MPI_Comm comm, const std::string &path, const std::string &h5, const char units[])
{
  PetscFunctionBeginUser;
  PetscCall(Close());
  comm_ = comm;
  h5_   = h5;
  PetscCall(PetscFOpen(comm_, path.c_str(), "w", &fp_));
  PetscCall(PetscFPrintf(comm_, fp_,
                         "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
                         "  <Information Name=\"units\" Value=\"%s\"/>\n",
                         units));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::BeginCollection(const std::string &name)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::BeginGrid(const std::string &name, size_t k, PetscReal time)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "   <Grid Name=\"%s_%04zu\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", name.c_str(), k, (double)time));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::DataItem(const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "     <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n", data.dims.c_str(),
                         data.integer ? "Int" : "Float", data.integer ? (int)sizeof(PetscInt) : (int)sizeof(PetscReal), h5_.c_str(), data.path.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Topology(const char type[], long long elements, long long nodes_per_element, const XdmfData &data)
{
  PetscFunctionBeginUser;
  if (nodes_per_element > 0)
    PetscCall(
      PetscFPrintf(comm_, fp_, "    <Topology TopologyType=\"%s\" NumberOfElements=\"%lld\" NodesPerElement=\"%lld\">\n", type, elements, nodes_per_element));
  else PetscCall(PetscFPrintf(comm_, fp_, "    <Topology TopologyType=\"%s\" NumberOfElements=\"%lld\">\n", type, elements));
  PetscCall(DataItem(data));
  PetscCall(PetscFPrintf(comm_, fp_, "    </Topology>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Geometry(const char type[], const char unit[], const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "    <Geometry GeometryType=\"%s\">\n     <Information Name=\"unit\" Value=\"%s\"/>\n", type, unit));
  PetscCall(DataItem(data));
  PetscCall(PetscFPrintf(comm_, fp_, "    </Geometry>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Attribute(const std::string &name, const char type[], const char center[], const char info_name[], const std::string &info,
                                     const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n     <Information Name=\"%s\" Value=\"%s\"/>\n",
                         name.c_str(), type, center, info_name, info.c_str()));
  PetscCall(DataItem(data));
  PetscCall(PetscFPrintf(comm_, fp_, "    </Attribute>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::EndGrid()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "   </Grid>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::EndCollection()
{
  PetscFunctionBeginUser;
  PetscCall(PetscFPrintf(comm_, fp_, "  </Grid>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Close()
{
  PetscFunctionBeginUser;
  if (comm_ != MPI_COMM_NULL) {
    PetscCall(PetscFPrintf(comm_, fp_, " </Domain>\n</Xdmf>\n"));
    PetscCall(PetscFClose(comm_, fp_));
  }
  comm_ = MPI_COMM_NULL;
  fp_   = nullptr;
  PetscFunctionReturn(PETSC_SUCCESS);
}

XdmfWriter::~XdmfWriter()
{
  if (comm_ != MPI_COMM_NULL) PetscCallVoid(PetscFClose(comm_, fp_)); /* an error left the file unfinished */
}

} // namespace turgor
