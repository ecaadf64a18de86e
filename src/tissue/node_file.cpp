/* -tissue_type node_file: cells of nodes and bars from the L-hyphen code's node file. */
#include <turgor/tissue/node_file.h>
#include <turgor/core/errors.h>
#include <turgor/core/options.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

namespace turgor {

/* What a node file may hold: a line "x y cellId" needs fewer than 80 characters (comments may be
   longer), and 1 GiB of such lines is about 20 million nodes, beyond what a fine run can hold on
   one node; a stream without line breaks (a device, a binary file) stops at these bounds. */
static const size_t    kMaxLineChars = 4096;
static const long long kMaxFileBytes = 1LL << 30;

/* A path that can be a node file: no directory, device or socket (a named pipe may be, it is read
   as a stream), and a regular file of at most kMaxFileBytes. */
static PetscErrorCode CheckNodeFilePath(MPI_Comm comm, const std::string &path)
{
  struct stat st;
  PetscFunctionBeginUser;
  PetscCheck(stat(path.c_str(), &st) == 0, comm, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: cannot open the file (%s)", path.c_str(),
             std::strerror(errno));
  const char *kind = S_ISDIR(st.st_mode)  ? "a directory"
                   : S_ISCHR(st.st_mode)  ? "a character device"
                   : S_ISBLK(st.st_mode)  ? "a block device"
                   : S_ISSOCK(st.st_mode) ? "a socket"
                                          : nullptr;
  PetscCheck(!kind, comm, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: is %s, not a file", path.c_str(), kind);
  PetscCheck(!S_ISREG(st.st_mode) || (long long)st.st_size <= kMaxFileBytes, comm, PETSC_ERR_FILE_UNEXPECTED,
             "Option -tissue_node_file = %s: the file has %lld bytes, more than the %lld bytes (1 GiB, about 20 million nodes) a node file may have",
             path.c_str(), (long long)st.st_size, kMaxFileBytes);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads a node file line by line within the bounds above. */
class NodeFileLines {
public:
  explicit NodeFileLines(const std::string &path) : f_(std::fopen(path.c_str(), "r")) { }
  ~NodeFileLines()
  {
    if (f_) std::fclose(f_);
  }
  NodeFileLines(const NodeFileLines &)            = delete;
  NodeFileLines &operator=(const NodeFileLines &) = delete;
  bool           Opened() const { return f_ != nullptr; }
  /* The next line (without its line break) in *line: true, or false at the end, on a read error,
     or at a bound (then Failure() says which). */
  bool Next(std::string *line)
  {
    line->clear();
    if (!f_ || failure_) return false;
    for (int c; (c = std::getc(f_)) != EOF;) {
      if (++bytes_ > kMaxFileBytes) failure_ = "more than 1 GiB (about 20 million nodes) read: a node file may not be larger";
      else if (c == '\0') failure_ = "a NUL byte: not a text file";
      else if (c == '\n') return true;
      else if (line->size() == kMaxLineChars) failure_ = "longer than 4096 characters: not a node file's line 'x y cellId'";
      if (failure_) return false;
      line->push_back((char)c);
    }
    if (std::ferror(f_)) failure_ = "read error";
    return !failure_ && !line->empty();
  }
  const char *Failure() const { return failure_; }

private:
  FILE       *f_;
  long long   bytes_   = 0;
  const char *failure_ = nullptr;
};

PetscErrorCode NodeFileSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char      buf[PETSC_MAX_PATH_LEN];
  PetscInt  ids[1025], n = 1025;
  PetscBool set_path, set_open;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buf, path.c_str(), sizeof buf));
  PetscOptionsBegin(comm, "tissue_", "Node-file tissue (-tissue_type node_file)", "turgor");
  PetscCall(TurgorOptionsString(params, "-node_file", "Node file: one node per line 'x y cellId', each cell's nodes together and in order around it",
                                "NodeFileSpec", buf, buf, sizeof buf, &set_path));
  PetscCall(TurgorOptionsReal(params, "-length_scale", "Length of one file unit [µm]", "NodeFileSpec", length_scale, &length_scale, NULL));
  PetscCall(TurgorOptionsIntArray(params, "-open_cells", "Cell ids (as in the file) that are open chains: no closing bar, no pressure", "NodeFileSpec", ids, &n,
                                  &set_open));
  PetscOptionsEnd();
  PetscCall(CheckNotEmpty(comm, "-tissue_node_file", "the path of a node file"));
  PetscCall(CheckNotEmpty(comm, "-tissue_open_cells", "cell ids id,id,..."));
  path = buf;
  PetscCheck(!path.empty(), comm, PETSC_ERR_ARG_WRONG, "Option -tissue_node_file: no file given (-tissue_type node_file needs one)");
  PetscCheck(std::isfinite(length_scale) && length_scale > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_length_scale = %g: must be finite and > 0",
             (double)length_scale);
  PetscCheck(!set_open || n < 1025, comm, PETSC_ERR_ARG_SIZ, "Option -tissue_open_cells: more than 1024 cells listed");
  if (set_open) open_cells.assign(ids, ids + n);
  for (size_t k = 0; k < open_cells.size(); k++) {
    PetscCheck(open_cells[k] >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_open_cells: cell id %" PetscInt_FMT " is negative", open_cells[k]);
    PetscCheck(std::find(open_cells.begin(), open_cells.begin() + k, open_cells[k]) == open_cells.begin() + k, comm, PETSC_ERR_ARG_WRONG,
               "Option -tissue_open_cells: cell %" PetscInt_FMT " is listed twice", open_cells[k]);
  }
  /* the file must exist now, before any allocation; it is read in Generate. Opening a FIFO waits for
     its writer: SIGINT/SIGTERM end that wait */
  PetscCall(CheckNodeFilePath(comm, path));
  InterruptibleCalls interruptible;
  std::ifstream      f(path);
  PetscCheck(!InterruptRequested(), comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: opening -tissue_node_file %s", path.c_str());
  PetscCheck(f.good(), comm, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: cannot open the file (%s)", path.c_str(), std::strerror(errno));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One line: 0 = blank or comment, 1 = a node, -1 = malformed. */
static int ParseNodeLine(const std::string &line, PetscReal *x, PetscReal *y, long long *id)
{
  const char *s = line.c_str();
  while (*s == ' ' || *s == '\t' || *s == '\r') s++;
  if (!*s || *s == '#') return 0;
  char *e;
  errno = 0;
  *x    = std::strtod(s, &e);
  if (e == s) return -1;
  s  = e;
  *y = std::strtod(s, &e);
  if (e == s) return -1;
  s   = e;
  *id = std::strtoll(s, &e, 10);
  if (e == s || errno) return -1;
  s = e;
  while (*s == ' ' || *s == '\t' || *s == '\r') s++;
  if (*s && *s != '#') return -1;
  return std::isfinite(*x) && std::isfinite(*y) ? 1 : -1;
}

PetscErrorCode GenerateNodeFileTissue(MPI_Comm comm, const NodeFileSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue)
{
  const char                         *fn = spec.path.c_str();
  std::vector<PolygonRing>            rings;
  std::vector<long long>              first_line; /* file line of each cell's first node */
  std::vector<std::vector<long long>> lines;      /* file line of each node */
  long long                           id0 = -1, lineno = 0;
  std::string                         line;
  PetscFunctionBeginUser;
  PetscCheck(!InterruptRequested(), comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: before reading -tissue_node_file %s", fn);
  PetscCall(CheckNodeFilePath(comm, spec.path));
  InterruptibleCalls interruptible;
  NodeFileLines      f(spec.path);
  PetscCheck(!InterruptRequested(), comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: opening -tissue_node_file %s", fn);
  PetscCheck(f.Opened(), comm, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: cannot open the file (%s)", fn, std::strerror(errno));
  while (f.Next(&line)) {
    PetscReal x, y;
    long long id;
    lineno++;
    PetscCheck(!InterruptRequested(), comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: reading -tissue_node_file %s at line %lld", fn, lineno);
    const int kind = ParseNodeLine(line, &x, &y, &id);
    if (kind == 0) continue;
    PetscCheck(kind > 0, comm, PETSC_ERR_FILE_UNEXPECTED,
               "Option -tissue_node_file = %s: line %lld: expected 'x y cellId' (two finite numbers and an integer), got '%s'", fn, lineno, line.c_str());
    PetscCheck(id >= 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: line %lld: cell id %lld is negative", fn, lineno, id);
    if (rings.empty()) id0 = id;
    const long long cur = id0 + (long long)rings.size() - 1;
    if (rings.empty() || id != cur) {
      PetscCheck(rings.empty() || id == cur + 1, comm, PETSC_ERR_FILE_UNEXPECTED,
                 "Option -tissue_node_file = %s: line %lld: cell id %lld follows cell %lld: ids must increase by one, each cell's nodes listed together", fn,
                 lineno, id, cur);
      rings.emplace_back();
      lines.emplace_back();
      first_line.push_back(lineno);
    }
    rings.back().points.push_back({x * spec.length_scale, y * spec.length_scale});
    lines.back().push_back(lineno);
  }
  PetscCheck(!InterruptRequested(), comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: reading -tissue_node_file %s at line %lld", fn,
             lineno + 1);
  PetscCheck(!f.Failure(), comm, PETSC_ERR_FILE_READ, "Option -tissue_node_file = %s: line %lld: %s", fn, lineno + 1, f.Failure());
  PetscCheck(!rings.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: no nodes in the file", fn);
  /* the forces multiply lengths (areas, moments): a tissue whose extent squared overflows (or whose
     scaled coordinates do) has no finite state */
  PetscReal lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
  for (const PolygonRing &R : rings)
    for (const Point2 &p : R.points)
      for (int d = 0; d < 2; d++) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  const PetscReal extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  PetscCheck(std::isfinite(extent * extent), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_node_file = %s with -tissue_length_scale %g: the tissue spans (%g, %g) to (%g, %g) µm, beyond double precision (its areas "
             "are not finite); give coordinates below 1e150 µm",
             fn, (double)spec.length_scale, (double)lo[0], (double)lo[1], (double)hi[0], (double)hi[1]);
  for (PetscInt id : spec.open_cells) {
    PetscCheck(id >= id0 && id < id0 + (long long)rings.size(), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -tissue_open_cells: cell %" PetscInt_FMT " is not in %s (its cells are %lld to %lld)", id, fn, id0, id0 + (long long)rings.size() - 1);
    rings[id - id0].open = true;
  }
  for (size_t c = 0; c < rings.size(); c++) {
    PolygonRing    &R  = rings[c];
    const long long id = id0 + (long long)c;
    const size_t    n  = R.points.size();
    PetscCheck(n >= (R.open ? 2u : 3u), comm, PETSC_ERR_FILE_UNEXPECTED,
               "Option -tissue_node_file = %s: line %lld: %s cell %lld has %zu node%s (needs at least %d)", fn, first_line[c], R.open ? "open" : "closed", id,
               n, n == 1 ? "" : "s", R.open ? 2 : 3);
    const size_t m = R.open ? n - 1 : n;
    for (size_t k = 0; k < m; k++) {
      const Point2 &a = R.points[k], &b = R.points[(k + 1) % n];
      PetscCheck(a[0] != b[0] || a[1] != b[1], comm, PETSC_ERR_FILE_UNEXPECTED,
                 "Option -tissue_node_file = %s: line %lld: cell %lld: zero-length bar from the node of line %lld to the node of line %lld (%g, %g)%s", fn,
                 lines[c][(k + 1) % n], id, lines[c][k], lines[c][(k + 1) % n], (double)a[0], (double)a[1],
                 k + 1 == n ? ": its first node is repeated at its end; list each node once" : "");
    }
    size_t e1, e2;
    if (FindSelfIntersection(R.points, R.open, &e1, &e2))
      SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED,
              "Option -tissue_node_file = %s: line %lld: cell %lld is not simple: its bar from line %lld to line %lld crosses or touches its bar from line "
              "%lld to line %lld",
              fn, first_line[c], id, lines[c][e1], lines[c][(e1 + 1) % n], lines[c][e2], lines[c][(e2 + 1) % n]);
    if (!R.open) {
      const PetscReal A = RingSignedArea(R.points);
      PetscCheck(A != 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: line %lld: closed cell %lld has zero area (-tissue_length_scale %g)",
                 fn, first_line[c], id, (double)spec.length_scale);
      if (A < 0) std::reverse(R.points.begin() + 1, R.points.end()); /* clockwise: the same polygon counter-clockwise, from the same first node */
    }
  }
  PetscCall(BuildPolygonTissue(comm, rings, poly, true, tissue));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WriteNodeFile(MPI_Comm comm, const std::string &path, const Tissue &tissue)
{
  const ParticleSet &P = tissue.particles;
  PetscFunctionBeginUser;
  FILE *f = std::fopen(path.c_str(), "w");
  PetscCheck(f, comm, PETSC_ERR_FILE_OPEN, "Cannot write the node file %s (%s)", path.c_str(), std::strerror(errno));
  std::string open;
  for (size_t c = 0; c < P.polygons.size(); c++)
    if (P.polygons[c].open) open += (open.empty() ? "" : ",") + std::to_string(c);
  std::fprintf(f, "# turgor node file: x y cellId, one node per line, each cell's nodes in order (closed cells counter-clockwise)\n");
  if (!open.empty()) std::fprintf(f, "# open cells (read with -tissue_open_cells %s)\n", open.c_str());
  for (size_t c = 0; c < P.polygons.size(); c++)
    for (PetscInt i : P.polygons[c].nodes) std::fprintf(f, "%.17g %.17g %zu\n", (double)tissue.X[2 * i], (double)tissue.X[2 * i + 1], c);
  const bool ok = !std::ferror(f);
  PetscCheck(std::fclose(f) == 0 && ok, comm, PETSC_ERR_FILE_WRITE, "Cannot write the node file %s", path.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A streaming pass over the file (nothing stored): nodes after subdivision and bars. Malformed lines
   are skipped here; Generate reports them. */
PetscErrorCode NodeFileGenerator::Estimate(PetscReal *particles, PetscReal *springs) const
{
  PetscCheck(!InterruptRequested(), PETSC_COMM_SELF, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: before reading -tissue_node_file %s",
             spec.path.c_str());
  InterruptibleCalls interruptible;
  NodeFileLines      f(spec.path); /* a line beyond the bounds ends the estimate; Generate reports it */
  std::string        line;
  PetscReal          nodes = 0, first[2] = {0, 0}, prev[2] = {0, 0};
  long long          cur  = -1;
  auto               bars = [&](const PetscReal a[2], const PetscReal b[2]) {
    return BarsPerEdge(std::hypot(b[0] - a[0], b[1] - a[1]) * spec.length_scale, poly.bar_length);
  };
  PetscFunctionBeginUser;
  while (f.Next(&line)) {
    PetscReal x, y;
    long long id;
    PetscCheck(!InterruptRequested(), PETSC_COMM_SELF, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: reading -tissue_node_file %s",
               spec.path.c_str());
    if (ParseNodeLine(line, &x, &y, &id) <= 0) continue;
    const PetscReal p[2] = {x, y};
    if (id != cur) {
      if (cur >= 0) nodes += bars(prev, first) + 1; /* closing bar, or the last node of an open cell: an upper bound either way */
      cur      = id;
      first[0] = x;
      first[1] = y;
    } else nodes += bars(prev, p);
    prev[0] = x;
    prev[1] = y;
  }
  PetscCheck(!InterruptRequested(), PETSC_COMM_SELF, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during set-up: reading -tissue_node_file %s",
             spec.path.c_str());
  if (cur >= 0) nodes += bars(prev, first) + 1;
  *particles = nodes;
  *springs   = nodes;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string NodeFileGenerator::SizeOptions() const
{
  return "-tissue_node_file " + spec.path + BarLengthOption();
}

PetscErrorCode NodeFileGenerator::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "tissue node_file: %s x %g µm, %zu open cells, %s\n", spec.path.c_str(), (double)spec.length_scale,
                                   spec.open_cells.size(), PolygonDescription().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
