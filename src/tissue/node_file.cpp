/* -tissue_type node_file: cells of nodes and bars from the L-hyphen code's node file. */
#include <turgor/tissue/node_file.h>
#include <turgor/core/errors.h>
#include <turgor/core/options.h>
#include <turgor/parallel/rank_reductions.h>
#include <algorithm>
#include <climits>
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

/* Reads a node file line by line within the bounds above, from its start (a named pipe too) or from
   a byte offset (Seek), with each line's first byte's offset. */
class NodeFileLines {
public:
  explicit NodeFileLines(const std::string &path) : f_(std::fopen(path.c_str(), "rb")) { }
  ~NodeFileLines()
  {
    if (f_) std::fclose(f_);
  }
  NodeFileLines(const NodeFileLines &)            = delete;
  NodeFileLines &operator=(const NodeFileLines &) = delete;
  bool           Opened() const { return f_ != nullptr; }
  /* A regular file: go to byte pos. */
  bool Seek(std::uint64_t pos)
  {
    pos_ = pos;
    return f_ && fseeko(f_, (off_t)pos, SEEK_SET) == 0;
  }
  /* The byte at the current position (EOF at the end), consumed. */
  int Get()
  {
    const int c = std::getc(f_);
    if (c != EOF) pos_++;
    return c;
  }
  /* The next line (without its line break) in *line, its first byte's offset in *start: true, or
     false at the end, on a read error, or at a bound (then Failure() says which). newline(p) is
     called with the offset of each line break read. */
  template <class Newline>
  bool Next(std::string *line, std::uint64_t *start, Newline &&newline)
  {
    line->clear();
    *start = pos_;
    if (!f_ || failure_) return false;
    for (int c; (c = Get()) != EOF;) {
      if (++bytes_ > kMaxFileBytes) failure_ = "more than 1 GiB (about 20 million nodes) read: a node file may not be larger";
      else if (c == '\0') failure_ = "a NUL byte: not a text file";
      else if (c == '\n') {
        newline(pos_ - 1);
        return true;
      } else if (line->size() == kMaxLineChars) failure_ = "longer than 4096 characters: not a node file's line 'x y cellId'";
      if (failure_) return false;
      line->push_back((char)c);
    }
    if (std::ferror(f_)) failure_ = "read error";
    return !failure_ && !line->empty();
  }
  bool Next(std::string *line)
  {
    std::uint64_t start;
    return Next(line, &start, [](std::uint64_t) {});
  }
  std::uint64_t Position() const { return pos_; }
  const char   *Failure() const { return failure_; }

private:
  FILE         *f_;
  std::uint64_t pos_     = 0;
  long long     bytes_   = 0; /* read by Next */
  const char   *failure_ = nullptr;
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

/* The checks of one cell as read (its nodes in file order, R.open set; lines: the file line of each
   node): enough nodes, no zero-length bar, simple, a closed cell's area not zero; a clockwise closed
   cell is reversed (the same polygon counter-clockwise, from the same first node). The error's
   message, or an empty string. */
static std::string CheckCell(const char *fn, const NodeFileSpec &spec, long long id, const std::vector<long long> &lines, PolygonRing *ring)
{
  PolygonRing &R = *ring;
  const size_t n = R.points.size();
  char         msg[1024];
  if (n < (R.open ? 2u : 3u)) {
    std::snprintf(msg, sizeof msg, "Option -tissue_node_file = %s: line %lld: %s cell %lld has %zu node%s (needs at least %d)", fn, lines[0],
                  R.open ? "open" : "closed", id, n, n == 1 ? "" : "s", R.open ? 2 : 3);
    return msg;
  }
  const size_t m = R.open ? n - 1 : n;
  for (size_t k = 0; k < m; k++) {
    const Point2 &a = R.points[k], &b = R.points[(k + 1) % n];
    if (a[0] == b[0] && a[1] == b[1]) {
      std::snprintf(msg, sizeof msg,
                    "Option -tissue_node_file = %s: line %lld: cell %lld: zero-length bar from the node of line %lld to the node of line %lld (%g, %g)%s", fn,
                    lines[(k + 1) % n], id, lines[k], lines[(k + 1) % n], (double)a[0], (double)a[1],
                    k + 1 == n ? ": its first node is repeated at its end; list each node once" : "");
      return msg;
    }
  }
  size_t e1, e2;
  if (FindSelfIntersection(R.points, R.open, &e1, &e2)) {
    std::snprintf(msg, sizeof msg,
                  "Option -tissue_node_file = %s: line %lld: cell %lld is not simple: its bar from line %lld to line %lld crosses or touches its bar from "
                  "line %lld to line %lld",
                  fn, lines[0], id, lines[e1], lines[(e1 + 1) % n], lines[e2], lines[(e2 + 1) % n]);
    return msg;
  }
  if (!R.open) {
    const PetscReal A = RingSignedArea(R.points);
    if (A == 0) {
      std::snprintf(msg, sizeof msg, "Option -tissue_node_file = %s: line %lld: closed cell %lld has zero area (-tissue_length_scale %g)", fn, lines[0], id,
                    (double)spec.length_scale);
      return msg;
    }
    if (A < 0) std::reverse(R.points.begin() + 1, R.points.end());
  }
  return "";
}

PetscErrorCode GenerateNodeFileTissue(MPI_Comm comm, const NodeFileSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue)
{
  const char                         *fn = spec.path.c_str();
  std::vector<PolygonRing>            rings;
  std::vector<std::vector<long long>> lines; /* file line of each node */
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
    const std::string error = CheckCell(fn, spec, id0 + (long long)c, lines[c], &rings[c]);
    PetscCheck(error.empty(), comm, PETSC_ERR_FILE_UNEXPECTED, "%s", error.c_str());
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
   are skipped here; Generate reports them. After PrepareParts, its exact counts. */
PetscErrorCode NodeFileGenerator::Estimate(PetscReal *particles, PetscReal *springs) const
{
  if (!offset_.empty()) { /* read in parts (PrepareParts): the counts are known; no rank reads the whole file again */
    *particles = (PetscReal)node_start_.back();
    *springs   = (PetscReal)bar_start_.back();
    return PETSC_SUCCESS;
  }
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

PetscInt NodeFileGenerator::NumCellsOfParts() const
{
  struct stat st;
  if (poly.plates.Any() || poly.has_cut_box || stat(spec.path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return -1;
  return (PetscInt)offset_.size();
}

std::string NodeFileGenerator::PartsRefused() const
{
  if (poly.plates.Any() || poly.has_cut_box) return "with -tissue_plates or -tissue_cut_box numbers its cells only once the whole tissue is built";
  return "reads " + spec.path + " in parts only from a regular file (a named pipe cannot be read twice)";
}

namespace {

/* The id of the last node line that ends before `start` (a line's first byte), -1 if none: read
   backwards line by line from the line break before it. */
bool PreviousNodeId(NodeFileLines &f, std::uint64_t start, long long *id)
{
  std::string line;
  *id = -1;
  for (std::uint64_t end = start; end > 0;) { /* the line that ends with the break at end - 1 */
    std::uint64_t b = end - 1;
    while (b > 0) { /* its first byte: after the previous break */
      if (!f.Seek(b - 1)) return false;
      if (f.Get() == '\n') break;
      b--;
    }
    if (!f.Seek(b)) return false;
    line.clear();
    for (std::uint64_t k = b; k + 1 < end; k++) line.push_back((char)f.Get());
    PetscReal x, y;
    long long i;
    if (ParseNodeLine(line, &x, &y, &i) > 0) {
      *id = i;
      return true;
    }
    end = b;
  }
  return true;
}

/* A cell as read in PrepareParts: its nodes, their lines (counted from the range's start until the
   ranges' line counts are known), where its first line starts. */
struct ReadCell {
  long long              id;
  std::uint64_t          offset;
  PolygonRing            ring;
  std::vector<long long> lines;
};

/* What PrepareParts gathers of each cell to every rank */
struct CellEntry {
  std::uint64_t offset;
  std::int64_t  nodes, bars;
  PetscReal     box[4];
};

} // namespace

PetscErrorCode NodeFileGenerator::PrepareParts(MPI_Comm comm)
{
  const char   *fn = spec.path.c_str();
  PetscMPIInt   rank, size;
  PetscLogEvent ev;
  struct stat   st;
  PetscFunctionBeginUser;
  PetscCheck(NumCellsOfParts() >= 0, comm, PETSC_ERR_ARG_INCOMP, "-tissue_type node_file %s", PartsRefused().c_str());
  PetscCall(PetscLogEventRegister("TgNodeFileParts", PETSC_OBJECT_CLASSID, &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(StopIfInterrupted(comm, "set-up: reading -tissue_node_file in parts"));
  PetscCall(CheckNodeFilePath(comm, spec.path));
  PetscCheck(stat(fn, &st) == 0, comm, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: cannot open the file (%s)", fn, std::strerror(errno));
  const std::uint64_t bytes = (std::uint64_t)st.st_size, a = bytes * (std::uint64_t)rank / (std::uint64_t)size,
                      b = bytes * (std::uint64_t)(rank + 1) / (std::uint64_t)size;

  /* this rank's cells: those whose first node line starts in [a, b), each read to its last node */
  std::vector<ReadCell> cells;
  long long             newlines = 0, stop_line = -1; /* breaks in [a, b); the first error's line (counted here) */
  std::string           stop_text, line;
  int                   stop_kind = 0; /* 1 malformed, 2 negative id, 3 ids out of order, 4 a bound or read error */
  long long             stop_id = 0, stop_cur = 0;
  PetscReal             ext[4] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL}; /* -lo, hi of the points */
  {
    NodeFileLines f(spec.path);
    std::uint64_t first = a; /* the first line that starts at or after a */
    long long     prev = -1, local_line = 0;
    auto          count = [&](std::uint64_t p) {
      if (p >= a && p < b) newlines++;
      local_line++;
    };
    bool ok = f.Opened();
    if (ok && a > 0 && a < b) {
      ok = f.Seek(a - 1);
      if (ok && f.Get() != '\n')
        for (int c; (c = f.Get()) != EOF;)
          if (c == '\n') {
            count(f.Position() - 1);
            break;
          }
      first = f.Position();
      ok    = ok && PreviousNodeId(f, first, &prev) && f.Seek(first);
    } else ok = ok && f.Seek(a);
    auto started = [&]() { /* this rank's error, every rank's failure */
                           PetscFunctionBeginUser;
                           PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "Option -tissue_node_file = %s: cannot read it from byte %llu (%s)", fn,
                                      (unsigned long long)a, std::strerror(errno));
                           PetscFunctionReturn(PETSC_SUCCESS);
    };
    PetscCall(AgreeOnError(comm, started(), "reading -tissue_node_file"));
    /* the lines of this range; a line's number is the breaks before it plus one (those before a
       added once every rank has counted its own) */
    bool          skipping = true; /* the lines of the cell the previous range began */
    std::uint64_t start;
    while (a < b && stop_kind == 0) {
      const long long this_line = local_line + 1;
      if (!f.Next(&line, &start, count)) {
        if (f.Failure()) stop_kind = 4, stop_line = this_line, stop_text = f.Failure();
        break;
      }
      PetscReal x, y;
      long long id;
      const int kind = ParseNodeLine(line, &x, &y, &id);
      if (kind == 0) continue;
      if (kind < 0) {
        stop_kind = 1, stop_line = this_line, stop_text = line;
        break;
      }
      if (id < 0) {
        stop_kind = 2, stop_line = this_line, stop_id = id;
        break;
      }
      if (skipping && id == prev) continue;
      skipping                = false;
      const long long current = cells.empty() ? prev : cells.back().id;
      if (cells.empty() || id != current) {
        if (start >= b) break; /* the next range's cell */
        if (current >= 0 && id != current + 1) {
          stop_kind = 3, stop_line = this_line, stop_id = id, stop_cur = current;
          break;
        }
        cells.push_back({id, start, PolygonRing(), {}});
        cells.back().ring.open = std::find(spec.open_cells.begin(), spec.open_cells.end(), (PetscInt)id) != spec.open_cells.end();
      }
      const Point2 p = {x * spec.length_scale, y * spec.length_scale};
      cells.back().ring.points.push_back(p);
      cells.back().lines.push_back(this_line);
      ext[0] = std::max(ext[0], -p[0]), ext[1] = std::max(ext[1], -p[1]), ext[2] = std::max(ext[2], p[0]), ext[3] = std::max(ext[3], p[1]);
    }
    /* the breaks of [a, b) not yet read (a range that ended inside one long line) */
    for (int c; a < b && f.Position() < b && (c = f.Get()) != EOF;)
      if (c == '\n') count(f.Position() - 1);
  }
  /* the lines' numbers: the breaks before this range's start, plus one */
  long long before = 0;
  PetscCallMPI(MPI_Exscan(&newlines, &before, 1, MPI_LONG_LONG, MPI_SUM, comm));
  if (rank == 0) before = 0;
  /* the first error in the file, named alike on every rank */
  {
    long long first_stop = stop_kind ? before + stop_line : LLONG_MAX;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &first_stop, 1, MPI_LONG_LONG, MPI_MIN, comm));
    if (first_stop < LLONG_MAX) {
      char msg[4096 + 512] = "";
      int  mine            = stop_kind && before + stop_line == first_stop ? rank : size, from;
      PetscCallMPI(MPI_Allreduce(&mine, &from, 1, MPI_INT, MPI_MIN, comm));
      if (rank == from) {
        const long long L = first_stop;
        if (stop_kind == 1)
          std::snprintf(msg, sizeof msg, "Option -tissue_node_file = %s: line %lld: expected 'x y cellId' (two finite numbers and an integer), got '%s'", fn, L,
                        stop_text.c_str());
        else if (stop_kind == 2) std::snprintf(msg, sizeof msg, "Option -tissue_node_file = %s: line %lld: cell id %lld is negative", fn, L, stop_id);
        else if (stop_kind == 3)
          std::snprintf(msg, sizeof msg,
                        "Option -tissue_node_file = %s: line %lld: cell id %lld follows cell %lld: ids must increase by one, each cell's nodes listed together",
                        fn, L, stop_id, stop_cur);
        else std::snprintf(msg, sizeof msg, "Option -tissue_node_file = %s: line %lld: %s", fn, L, stop_text.c_str());
      }
      PetscCallMPI(MPI_Bcast(msg, (PetscMPIInt)sizeof msg, MPI_CHAR, from, comm));
      SETERRQ(comm, stop_kind == 4 ? PETSC_ERR_FILE_READ : PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
    }
  }
  for (ReadCell &c : cells)
    for (long long &l : c.lines) l += before;
  /* the whole file's checks, in the order Generate makes them */
  long long counts[2] = {(long long)cells.size(), cells.empty() ? LLONG_MAX : cells.front().id}; /* cells; the first id */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &counts[0], 1, MPI_LONG_LONG, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &counts[1], 1, MPI_LONG_LONG, MPI_MIN, comm));
  PetscCheck(counts[0] > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: no nodes in the file", fn);
  PetscCall(MaxOverRanks(comm, ext, 4));
  {
    const PetscReal extent = std::max(ext[2] + ext[0], ext[3] + ext[1]);
    PetscCheck(std::isfinite(extent * extent), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -tissue_node_file = %s with -tissue_length_scale %g: the tissue spans (%g, %g) to (%g, %g) µm, beyond double precision (its areas "
               "are not finite); give coordinates below 1e150 µm",
               fn, (double)spec.length_scale, (double)-ext[0], (double)-ext[1], (double)ext[2], (double)ext[3]);
  }
  id0_ = counts[1];
  for (PetscInt id : spec.open_cells)
    PetscCheck(id >= id0_ && id < id0_ + counts[0], comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -tissue_open_cells: cell %" PetscInt_FMT " is not in %s (its cells are %lld to %lld)", id, fn, id0_, id0_ + counts[0] - 1);
  /* each cell's checks (the first failing cell in the file named on every rank), nodes and box */
  std::vector<CellEntry> mine(cells.size());
  {
    long long   first_bad = LLONG_MAX;
    std::string error;
    for (size_t k = 0; k < cells.size(); k++) {
      ReadCell         &c = cells[k];
      const std::string e = CheckCell(fn, spec, c.id, c.lines, &c.ring);
      if (!e.empty()) {
        if (c.lines[0] < first_bad) first_bad = c.lines[0], error = e;
        continue;
      }
      CellEntry &E = mine[k];
      E.offset     = c.offset;
      E.nodes      = 0;
      E.box[0] = E.box[1] = PETSC_MAX_REAL;
      E.box[2] = E.box[3] = -PETSC_MAX_REAL;
      ForEachRingNode(c.ring, poly.bar_length, [&E](PetscReal x, PetscReal y) {
        E.nodes++;
        E.box[0] = std::min(E.box[0], x), E.box[1] = std::min(E.box[1], y), E.box[2] = std::max(E.box[2], x), E.box[3] = std::max(E.box[3], y);
      });
      E.bars = c.ring.open ? E.nodes - 1 : E.nodes;
    }
    long long bad = first_bad;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_LONG_LONG, MPI_MIN, comm));
    if (bad < LLONG_MAX) {
      char msg[2048] = "";
      int  me        = first_bad == bad ? rank : size, from;
      PetscCallMPI(MPI_Allreduce(&me, &from, 1, MPI_INT, MPI_MIN, comm));
      if (rank == from) std::snprintf(msg, sizeof msg, "%s", error.c_str());
      PetscCallMPI(MPI_Bcast(msg, (PetscMPIInt)sizeof msg, MPI_CHAR, from, comm));
      SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
    }
  }
  std::vector<ReadCell>().swap(cells);
  /* the index of every cell, on every rank */
  std::vector<CellEntry> all((size_t)counts[0]);
  {
    std::vector<PetscMPIInt> count(size), displ(size, 0);
    const PetscMPIInt        n = (PetscMPIInt)(mine.size() * sizeof(CellEntry));
    PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, count.data(), 1, MPI_INT, comm));
    for (PetscMPIInt r = 1; r < size; r++) displ[r] = displ[r - 1] + count[r - 1];
    PetscCallMPI(MPI_Allgatherv(mine.data(), n, MPI_BYTE, all.data(), count.data(), displ.data(), MPI_BYTE, comm));
  }
  const size_t C = all.size();
  offset_.resize(C), box_.resize(C), node_start_.assign(C + 1, 0), bar_start_.assign(C + 1, 0);
  std::vector<Point2> centre(C);
  lo_[0] = lo_[1] = PETSC_MAX_REAL;
  hi_[0] = hi_[1] = -PETSC_MAX_REAL;
  for (size_t c = 0; c < C; c++) {
    const CellEntry &E = all[c];
    offset_[c]         = E.offset;
    for (int d = 0; d < 4; d++) box_[c][d] = E.box[d];
    node_start_[c + 1] = node_start_[c] + (PetscInt)E.nodes;
    bar_start_[c + 1]  = bar_start_[c] + (PetscInt)E.bars;
    centre[c]          = {0.5 * (E.box[0] + E.box[2]), 0.5 * (E.box[1] + E.box[3])};
    for (int d = 0; d < 2; d++) lo_[d] = std::min(lo_[d], E.box[d]), hi_[d] = std::max(hi_[d], E.box[2 + d]);
  }
  const PetscReal box[4] = {lo_[0], lo_[1], hi_[0], hi_[1]};
  HilbertPlaces(centre, box, &place_); /* the space order: the Hilbert curve through the cells' boxes' centres */
  PetscCall(StopIfInterrupted(comm, "set-up: reading -tissue_node_file in parts"));
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NodeFileGenerator::GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const
{
  const size_t C  = offset_.size();
  const char  *fn = spec.path.c_str();
  PetscFunctionBeginUser;
  PetscCheck(C > 0 && place_.size() == C, comm, PETSC_ERR_ORDER, "NodeFileGenerator::PrepareParts() must come before GeneratePart()");
  PetscCheck(0 <= c0 && c0 <= c1 && c1 <= (PetscInt)C, comm, PETSC_ERR_ARG_OUTOFRANGE, "places [%" PetscInt_FMT ", %" PetscInt_FMT ") of a tissue of %zu cells",
             c0, c1, C);
  PetscCheck(distance >= 0 && std::isfinite(distance), comm, PETSC_ERR_ARG_OUTOFRANGE, "a part's distance must be finite and >= 0 (got %g)", (double)distance);
  PolygonPart T(part, poly.bar_radius);
  if (c0 < c1) {
    /* the box of the part's own cells; every cell whose box comes within the distance of it */
    PetscReal U[4] = {PETSC_MAX_REAL, PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
    for (size_t c = 0; c < C; c++)
      if (place_[c] >= c0 && place_[c] < c1)
        U[0] = std::min(U[0], box_[c][0]), U[1] = std::min(U[1], box_[c][1]), U[2] = std::max(U[2], box_[c][2]), U[3] = std::max(U[3], box_[c][3]);
    const PetscReal reach = distance + 1e-9 * (hi_[0] - lo_[0] + hi_[1] - lo_[1]); /* and the rounding of the halo's own measure */
    NodeFileLines   f(spec.path);
    std::string     line;
    PetscCheck(f.Opened(), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Option -tissue_node_file = %s: cannot open the file (%s)", fn, std::strerror(errno));
    for (size_t c = 0; c < C; c++) {
      const PetscReal dx = std::max((PetscReal)0, std::max(box_[c][0] - U[2], U[0] - box_[c][2]));
      const PetscReal dy = std::max((PetscReal)0, std::max(box_[c][1] - U[3], U[1] - box_[c][3]));
      if (!(place_[c] >= c0 && place_[c] < c1) && !(std::hypot(dx, dy) <= reach)) continue;
      /* the cell's lines, from its first to the next cell's */
      const long long id = id0_ + (long long)c;
      PolygonRing     R;
      R.open = std::find(spec.open_cells.begin(), spec.open_cells.end(), (PetscInt)id) != spec.open_cells.end();
      PetscCheck(f.Seek(offset_[c]), PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "Option -tissue_node_file = %s: cannot read it from byte %llu", fn,
                 (unsigned long long)offset_[c]);
      while (f.Next(&line)) {
        PetscReal x, y;
        long long i;
        const int kind = ParseNodeLine(line, &x, &y, &i);
        if (kind == 0) continue;
        if (kind < 0 || i != id) break;
        R.points.push_back({x * spec.length_scale, y * spec.length_scale});
      }
      PetscCheck(!f.Failure(), PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "Option -tissue_node_file = %s: cell %lld: %s", fn, id, f.Failure());
      const std::string error = CheckCell(fn, spec, id, std::vector<long long>(R.points.size() + 1, 0), &R); /* reverses a clockwise cell */
      PetscCheck(error.empty(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: cell %lld changed since the set-up read it", fn,
                 id);
      PetscCheck(T.Add(R, poly.node_mass, poly.bar_length, (PetscInt)c, node_start_[c], node_start_[c + 1] - node_start_[c], bar_start_[c],
                       bar_start_[c + 1] - bar_start_[c]),
                 PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "Option -tissue_node_file = %s: cell %lld changed since the set-up read it", fn, id);
    }
  }
  T.Finish(lo_, hi_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
