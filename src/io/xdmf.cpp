#include <turgor/io/xdmf.h>
#include <turgor/io/output.h>
#include <cstdarg>

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

/* printf into the file (rank 0); a failure is kept by the file, and Close() raises it */
PetscErrorCode XdmfWriter::Print(const char format[], ...)
{
  char    buf[1024];
  va_list ap;
  PetscFunctionBeginUser;
  if (!file_) PetscFunctionReturn(PETSC_SUCCESS);
  va_start(ap, format);
  const int n = std::vsnprintf(buf, sizeof buf, format, ap);
  va_end(ap);
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "XDMF: cannot format a line");
  if ((size_t)n < sizeof buf) file_->Write(buf);
  else {
    std::string big((size_t)n + 1, '\0');
    va_start(ap, format);
    (void)std::vsnprintf(&big[0], big.size(), format, ap);
    va_end(ap);
    big.resize((size_t)n);
    file_->Write(big);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Open(MPI_Comm comm, const std::string &path, const std::string &h5, const char units[])
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCall(Close());
  comm_ = comm;
  h5_   = h5;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    file_ = std::make_unique<OutputFile>();
    file_->Open(path);
  }
  PetscCall(Print("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
                  "  <Information Name=\"units\" Value=\"%s\"/>\n",
                  units));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::BeginCollection(const std::string &name)
{
  PetscFunctionBeginUser;
  PetscCall(Print("  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", name.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::BeginGrid(const std::string &name, size_t k, PetscReal time)
{
  PetscFunctionBeginUser;
  PetscCall(Print("   <Grid Name=\"%s_%04zu\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", name.c_str(), k, (double)time));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::DataItem(const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(Print("     <DataItem Dimensions=\"%s\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">%s:%s</DataItem>\n", data.dims.c_str(),
                  data.integer ? "Int" : "Float", data.integer ? (int)sizeof(PetscInt) : (int)sizeof(PetscReal), h5_.c_str(), data.path.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Topology(const char type[], long long elements, long long nodes_per_element, const XdmfData &data)
{
  PetscFunctionBeginUser;
  if (nodes_per_element > 0)
    PetscCall(Print("    <Topology TopologyType=\"%s\" NumberOfElements=\"%lld\" NodesPerElement=\"%lld\">\n", type, elements, nodes_per_element));
  else PetscCall(Print("    <Topology TopologyType=\"%s\" NumberOfElements=\"%lld\">\n", type, elements));
  PetscCall(DataItem(data));
  PetscCall(Print("    </Topology>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Geometry(const char type[], const char unit[], const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(Print("    <Geometry GeometryType=\"%s\">\n     <Information Name=\"unit\" Value=\"%s\"/>\n", type, unit));
  PetscCall(DataItem(data));
  PetscCall(Print("    </Geometry>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Attribute(const std::string &name, const char type[], const char center[], const char info_name[], const std::string &info,
                                     const XdmfData &data)
{
  PetscFunctionBeginUser;
  PetscCall(Print("    <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n     <Information Name=\"%s\" Value=\"%s\"/>\n", name.c_str(), type, center,
                  info_name, info.c_str()));
  PetscCall(DataItem(data));
  PetscCall(Print("    </Attribute>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::EndGrid()
{
  PetscFunctionBeginUser;
  PetscCall(Print("   </Grid>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::EndCollection()
{
  PetscFunctionBeginUser;
  PetscCall(Print("  </Grid>\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode XdmfWriter::Close()
{
  PetscFunctionBeginUser;
  if (comm_ == MPI_COMM_NULL) PetscFunctionReturn(PETSC_SUCCESS);
  const MPI_Comm comm = comm_;
  std::string    error;
  comm_ = MPI_COMM_NULL;
  if (file_) {
    PetscCall(Print(" </Domain>\n</Xdmf>\n"));
    file_->Close();
    error = file_->Error();
    file_.reset();
  }
  PetscCall(CheckOutputError(comm, error));
  PetscFunctionReturn(PETSC_SUCCESS);
}

XdmfWriter::~XdmfWriter() = default; /* an error left the file unfinished: closed unchecked */

} // namespace turgor
