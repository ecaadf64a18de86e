#pragma once
/* Scenes are PETSc YAML options files; PETSc's message for one that does not parse has no line
   number. CheckYAMLScenes() parses every -options_file_yaml FILE of the command line with libyaml
   first and, on a syntax error, prints "FILE:LINE:COLUMN: problem" and returns false. Called before
   PetscInitialize (so it uses plain stdio); a file that cannot be opened is left to PETSc. */

namespace turgor {

bool CheckYAMLScenes(int argc, char **argv);

} // namespace turgor
