#include <turgor/core/yaml_check.h>
#include <cstdio>
#include <cstring>
#include <yaml.h>

namespace turgor {

/* true if `path` parses (or cannot be opened: PETSc reports that itself). */
static bool CheckOne(const char *path)
{
  FILE *fp = std::fopen(path, "rb");
  if (!fp) return true;
  yaml_parser_t parser;
  yaml_event_t  event;
  bool          ok = true, done = false;
  yaml_parser_initialize(&parser);
  yaml_parser_set_input_file(&parser, fp);
  while (!done) {
    if (!yaml_parser_parse(&parser, &event)) {
      std::fprintf(stderr, "%s:%lu:%lu: YAML error: %s%s%s\n", path, (unsigned long)parser.problem_mark.line + 1, (unsigned long)parser.problem_mark.column + 1,
                   parser.problem ? parser.problem : "cannot parse", parser.context ? " " : "", parser.context ? parser.context : "");
      ok = false;
      break;
    }
    done = event.type == YAML_STREAM_END_EVENT;
    yaml_event_delete(&event);
  }
  yaml_parser_delete(&parser);
  std::fclose(fp);
  return ok;
}

bool CheckYAMLScenes(int argc, char **argv)
{
  bool ok = true;
  for (int k = 1; k + 1 < argc; k++)
    if (!std::strcmp(argv[k], "-options_file_yaml")) ok = CheckOne(argv[k + 1]) && ok;
  return ok;
}

} // namespace turgor
