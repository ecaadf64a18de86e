#include <turgor/coarse/gmsh_check.h>
#include <turgor/core/errors.h>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

namespace turgor {

namespace {

/* A line-oriented reader that knows which line it is on, for the messages. */
class GmshLines {
public:
  explicit GmshLines(std::istream &in) : in_(in) { }
  bool Next(std::string *line)
  {
    if (!std::getline(in_, *line)) return false;
    line_++;
    if (!line->empty() && line->back() == '\r') line->pop_back();
    return true;
  }
  long Line() const { return line_; }

private:
  std::istream &in_;
  long          line_ = 0;
};

std::vector<long long> Numbers(const std::string &line)
{
  std::istringstream     s(line);
  std::vector<long long> v;
  long long              x;
  while (s >> x) v.push_back(x);
  return v;
}

std::string At(const GmshLines &r, const std::string &what)
{
  return "line " + std::to_string(r.Line()) + ": " + what;
}

/* "" when the file is usable by PETSc's reader as far as node references go, else why not */
std::string Check(std::istream &in)
{
  GmshLines                     r(in);
  std::string                   line;
  double                        version = 0;
  bool                          binary = false, have_nodes = false, have_elements = false;
  std::unordered_set<long long> nodes;
  while (r.Next(&line)) {
    if (line == "$MeshFormat") {
      if (!r.Next(&line)) return At(r, "the file ends inside $MeshFormat");
      std::istringstream s(line);
      int                type = 0;
      s >> version >> type;
      binary = type != 0;
      if (binary) return ""; /* PETSc reads binary files; this check does not */
      if (version < 2 || version >= 5 || (version >= 3 && version < 4))
        return At(r, "format version " + std::to_string(version) + " (PETSc reads 2.2 and 4.1)");
    } else if (line == "$Nodes") {
      if (version == 0) return At(r, "$Nodes before $MeshFormat");
      have_nodes = true;
      if (!r.Next(&line)) return At(r, "the file ends inside $Nodes");
      const auto head = Numbers(line);
      if (version < 3) {
        if (head.size() != 1 || head[0] < 0) return At(r, "$Nodes: expected the number of nodes, got \"" + line + "\"");
        for (long long i = 0; i < head[0]; i++) {
          if (!r.Next(&line) || line == "$EndNodes") return At(r, "$Nodes announces " + std::to_string(head[0]) + " nodes and holds " + std::to_string(i));
          const auto v = Numbers(line);
          if (v.empty()) return At(r, "$Nodes: \"" + line + "\" is not a node");
          nodes.insert(v[0]);
        }
      } else {
        if (head.size() != 4) return At(r, "$Nodes: expected numEntityBlocks numNodes minNodeTag maxNodeTag, got \"" + line + "\"");
        for (long long b = 0; b < head[0]; b++) {
          if (!r.Next(&line)) return At(r, "the file ends inside $Nodes");
          const auto block = Numbers(line);
          if (block.size() != 4) return At(r, "$Nodes: expected entityDim entityTag parametric numNodesInBlock, got \"" + line + "\"");
          for (long long i = 0; i < block[3]; i++) {
            if (!r.Next(&line)) return At(r, "the file ends inside $Nodes");
            const auto v = Numbers(line);
            if (v.size() != 1) return At(r, "$Nodes: expected a node tag, got \"" + line + "\"");
            nodes.insert(v[0]);
          }
          for (long long i = 0; i < block[3]; i++)
            if (!r.Next(&line)) return At(r, "the file ends inside $Nodes");
        }
        if ((long long)nodes.size() != head[1])
          return At(r, "$Nodes announces " + std::to_string(head[1]) + " nodes and holds " + std::to_string(nodes.size()));
      }
      if (!r.Next(&line) || line != "$EndNodes") return At(r, "expected $EndNodes");
    } else if (line == "$Elements") {
      if (!have_nodes) return At(r, "$Elements before $Nodes");
      have_elements = true;
      if (!r.Next(&line)) return At(r, "the file ends inside $Elements");
      const auto head = Numbers(line);
      /* one element per line in both formats: 2.2 "tag type ntags tags... nodes...", 4.1 "tag nodes..." */
      auto element = [&](const std::string &l, size_t first_node) -> std::string {
        const auto v = Numbers(l);
        if (v.size() <= first_node) return At(r, "$Elements: \"" + l + "\" is not an element");
        for (size_t i = first_node; i < v.size(); i++)
          if (!nodes.count(v[i]))
            return At(r, "element " + std::to_string(v[0]) + " refers to node " + std::to_string(v[i]) + ", which $Nodes does not define");
        return "";
      };
      if (version < 3) {
        if (head.size() != 1 || head[0] < 0) return At(r, "$Elements: expected the number of elements, got \"" + line + "\"");
        for (long long i = 0; i < head[0]; i++) {
          if (!r.Next(&line) || line == "$EndElements")
            return At(r, "$Elements announces " + std::to_string(head[0]) + " elements and holds " + std::to_string(i));
          const auto v = Numbers(line);
          if (v.size() < 3) return At(r, "$Elements: \"" + line + "\" is not an element");
          const std::string why = element(line, 3 + (size_t)v[2]);
          if (!why.empty()) return why;
        }
      } else {
        if (head.size() != 4) return At(r, "$Elements: expected numEntityBlocks numElements minElementTag maxElementTag, got \"" + line + "\"");
        for (long long b = 0; b < head[0]; b++) {
          if (!r.Next(&line)) return At(r, "the file ends inside $Elements");
          const auto block = Numbers(line);
          if (block.size() != 4) return At(r, "$Elements: expected entityDim entityTag elementType numElementsInBlock, got \"" + line + "\"");
          for (long long i = 0; i < block[3]; i++) {
            if (!r.Next(&line)) return At(r, "the file ends inside $Elements");
            const std::string why = element(line, 1);
            if (!why.empty()) return why;
          }
        }
      }
      if (!r.Next(&line) || line != "$EndElements") return At(r, "expected $EndElements");
    }
  }
  if (version == 0) return "no $MeshFormat section (not a Gmsh file?)";
  if (!have_nodes) return "no $Nodes section";
  if (!have_elements) return "no $Elements section";
  return "";
}

} // namespace

PetscErrorCode CheckGmshFile(MPI_Comm comm, const char option[], const char path[])
{
  PetscMPIInt rank;
  std::string why, msg;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::ifstream in(path);
    if (!in) why = "cannot be opened for reading";
    else {
      try {
        why = Check(in);
      } catch (const std::exception &e) {
        why = e.what();
      }
    }
  }
  PetscCall(FirstMessage(comm, why, &msg));
  PetscCheck(msg.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "Option %s = %s: %s", option, path, msg.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
