/* Preloaded into the tests of a sanitized build (-DTURGOR_SANITIZE=ON, tests/CMakeLists.txt): a
   dlclose() that keeps every module mapped. Open MPI unloads its MCA components (and PMIx its
   plugins) in MPI_Finalize; what they allocated and never freed would then be reported by
   LeakSanitizer with "<unknown module>" frames, which no suppression can name. Kept mapped, those
   frames name the component (.../openmpi3/mca_*.so) and tests/sanitize/lsan.supp can suppress
   them. Built without the sanitizers: it is also preloaded into the unsanitized programs a test
   runs (sh, python, make, mpiexec). */
int dlclose(void *handle)
{
  (void)handle;
  return 0;
}
