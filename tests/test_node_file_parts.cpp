static const char help[] = "Node files read in parts on several ranks: each rank's part against the whole file's tissue, and the same errors.\n";
/* Run on several ranks (tests/distributed.cmake: 2, 3 and 6). The first rank writes node files whose
   byte ranges end in awkward places — CRLF line ends, no final line break, comments and blank lines
   between cells, a comment line longer than a rank's range, one cell on many ranks, ids from 1000, an
   open cell last — then every rank reads each file in parts (PrepareParts on all ranks), builds the
   part of its range and checks it against the whole file's tissue read on its own
   (CheckPolygonPart). Then files with an error near each range's start: the parts' error names the
   same line and cell as the whole reader's. */
#include "tissue_parts_util.h"
#include <turgor/parallel/rank_reductions.h>
#include <turgor/parallel/tissue_placement.h>
#include <turgor/tissue/node_file.h>
#include <cstdio>
#include <string>

using namespace turgor;

/* cells x cells squares of side 8 at a pitch of 10, `nodes` nodes per side, in file order row by row */
static std::vector<std::vector<Point2>> Squares(int cells, int nodes)
{
  std::vector<std::vector<Point2>> out;
  for (int j = 0; j < cells; j++)
    for (int i = 0; i < cells; i++) {
      std::vector<Point2> p;
      const double        x0 = 10.0 * i, y0 = 10.0 * j, s = 8.0;
      for (int t = 0; t < nodes; t++) p.push_back({x0 + s * t / nodes, y0});
      for (int t = 0; t < nodes; t++) p.push_back({x0 + s, y0 + s * t / nodes});
      for (int t = 0; t < nodes; t++) p.push_back({x0 + s - s * t / nodes, y0 + s});
      for (int t = 0; t < nodes; t++) p.push_back({x0, y0 + s - s * t / nodes});
      out.push_back(p);
    }
  return out;
}

struct Variant {
  const char *name;
  int         cells, nodes;
  const char *eol;
  bool        final_break, comments;
  size_t      long_comment; /* characters of a comment line after the first cell (0: none) */
  int         id0;
  bool        open_last;
};

static PetscErrorCode Write(const Variant &v, const std::string &path, int bad_line = -1, int bad_kind = 0)
{
  PetscFunctionBeginUser;
  FILE *f = std::fopen(path.c_str(), "wb");
  TG_CHECK(f, "cannot write %s", path.c_str());
  const auto  cells = Squares(v.cells, v.nodes);
  int         line  = 0;
  std::string text;
  auto        put = [&](const std::string &s) {
    line++;
    text += s + v.eol;
  };
  put("# test_node_file_parts: " + std::string(v.name));
  for (size_t c = 0; c < cells.size(); c++) {
    if (v.comments && c % 2 == 1) put(""), put("  # cell " + std::to_string(c));
    for (size_t k = 0; k < cells[c].size(); k++) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "%.17g %.17g %d", cells[c][k][0], cells[c][k][1], v.id0 + (int)c);
      if (line + 1 == bad_line && bad_kind == 1) std::snprintf(buf, sizeof buf, "%.17g oops %d", cells[c][k][0], v.id0 + (int)c);
      if (line + 1 == bad_line && bad_kind == 2) std::snprintf(buf, sizeof buf, "%.17g %.17g %d", cells[c][k][0], cells[c][k][1], v.id0 + (int)c + 7);
      put(buf);
    }
    if (c == 0 && v.long_comment) put("#" + std::string(v.long_comment, 'x'));
  }
  if (!v.final_break) text.resize(text.size() - std::strlen(v.eol));
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  TG_CHECK(std::fclose(f) == 0 && written, "cannot write %s", path.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  const Variant variants[] = {
    {"plain",          6, 3, "\n",   true,  false, 0,    0,    false},
    {"crlf",           6, 3, "\r\n", true,  true,  0,    3,    false},
    {"no final break", 5, 2, "\n",   false, true,  0,    1000, true },
    {"long comment",   4, 2, "\n",   true,  false, 3000, 0,    false},
    {"one cell",       1, 4, "\n",   false, true,  0,    42,   true },
  };
  const std::string path = "node_file_parts_" + std::to_string(size) + ".nodes";
  for (const Variant &v : variants) {
    PetscCall(AgreeOnError(PETSC_COMM_WORLD, rank == 0 ? Write(v, path) : PETSC_SUCCESS, "writing the node file"));
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    for (PetscReal h : {0.0, 3.0}) {
      NodeFileGenerator G;
      G.spec.path       = path;
      G.poly.bar_length = h;
      if (v.open_last) G.spec.open_cells = {(PetscInt)(v.id0 + v.cells * v.cells - 1)};
      Tissue W;
      PetscCall(GenerateNodeFileTissue(PETSC_COMM_SELF, G.spec, G.poly, &W));
      PetscCall(G.PrepareParts(PETSC_COMM_WORLD));
      PetscInt c0, c1;
      PetscCall(TissuePlacement::OwnedRange(PETSC_COMM_WORLD, G.NumCellsOfParts(), &c0, &c1));
      std::vector<char> seen(W.particles.n, 0), seen_spring(W.particles.springs.size(), 0);
      PetscCall(CheckPolygonPart(G, W, c0, c1, 4.0, &seen, &seen_spring));
      /* the parts cover the tissue: every node in some rank's part */
      std::vector<int> any(seen.begin(), seen.end());
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, any.data(), (PetscMPIInt)any.size(), MPI_INT, MPI_MAX, PETSC_COMM_WORLD));
      for (size_t g = 0; g < any.size(); g++) TG_CHECK(any[g], "%s: node %zu in no rank's part", v.name, g);
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s (%d cells): the parts on %d ranks as the whole file\n", v.name, v.cells * v.cells, size));
  }
  /* errors: a malformed line, or an id out of order, at lines spread over the file; the message
     of the parts (on every rank) is the whole reader's */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  const Variant &v         = variants[1];
  const int      lines     = 1 + v.cells * v.cells * 4 * v.nodes + v.cells * v.cells; /* (about) */
  int            failed[3] = {0, 0, 0};                                               /* files refused, of each kind */
  for (int kind = 1; kind <= 2; kind++)
    for (int bad = 2; bad < lines; bad += lines / 7) {
      PetscCall(AgreeOnError(PETSC_COMM_WORLD, rank == 0 ? Write(v, path, bad, kind) : PETSC_SUCCESS, "writing the node file"));
      PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
      NodeFileGenerator G;
      G.spec.path = path;
      Tissue      W;
      std::string whole, parts;
      auto        message = [](PetscErrorCode e, std::string *out) {
        char *text = NULL;
        PetscFunctionBeginUser;
        if (e) PetscCall(PetscErrorMessage(e, NULL, &text));
        *out = text ? text : "";
        PetscFunctionReturn(PETSC_SUCCESS);
      };
      const PetscErrorCode e1 = GenerateNodeFileTissue(PETSC_COMM_SELF, G.spec, G.poly, &W);
      PetscCall(message(e1, &whole));
      const PetscErrorCode e2 = G.PrepareParts(PETSC_COMM_WORLD);
      PetscCall(message(e2, &parts));
      TG_CHECK((e1 != 0) == (e2 != 0) && whole == parts, "line %d: the whole reader says '%s', the parts '%s'", bad, whole.c_str(), parts.c_str());
      failed[kind] += e1 != 0;
    }
  PetscCall(PetscPopErrorHandler());
  TG_CHECK(failed[1] >= 5 && failed[2] >= 5, "only %d malformed and %d out-of-order files refused", failed[1], failed[2]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "errors at lines across the file (%d malformed, %d ids out of order): the parts name them as the whole reader on %d ranks\n", failed[1],
                        failed[2], size));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_node_file_parts: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
