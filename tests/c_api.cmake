# The C API (<turgor/turgor.h>): examples/c_api.c, a C99 program built with makefile.inc as a user's
# would be (mpicc -std=c99 -pedantic -Wall -Wextra -Werror: turgor.h, its only include, is C and
# compiles cleanly; linked with mpicxx), calls turgor's TS API from C to solve Robertson's problem
# (ROBER) with radauiia against the Test Set's reference, then runs -mode rve for 4 steps through
# TurgorRunMode() from options given on its command line. It prints "c_api: OK" only when both
# succeeded. An unknown -mode is a PETSc error returned to the C caller, not a crash.
turgor_add_test(c_api_example
  COMMAND sh -c "${EXAMPLES_MAKE} CFLAGS='-pedantic -Wall -Wextra -Wno-unused-parameter -Werror' c_api && ./c_api -path_steps 4 -path_tangents 0 -output_dir c_api_rve -output_overwrite"
  LABELS unit SETUP c_api PASS_REGEX "Done: 5 evaluations.*c_api: OK")
turgor_add_test(c_api_bad_mode COMMAND ${BAD} "Option -mode: unknown mode 'bogus'" ./c_api -mode bogus -output_dir c_api_bad -output_overwrite
  LABELS unit badinput TIMEOUT 60 REQUIRES c_api)
