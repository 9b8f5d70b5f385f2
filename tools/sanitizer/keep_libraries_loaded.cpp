// Linked into the executables of the sanitizer build only (CMakeLists.txt, CONTACTQP_SANITIZE):
// dlclose() that never unloads. OpenMPI (and the PMIx it starts) loads its components
// (mca_*.so) with dlopen in MPI_Init and unloads them in MPI_Finalize; the allocations they
// keep to the end of the process are then reported by LeakSanitizer at exit, when the
// component is gone, as frames of "<unknown module>": no suppression can name them, so a leak
// of OpenMPI's would fail every test that starts PETSc, or the suppressions would have to be
// blind. With every library left mapped, each frame names its library (mca_op_avx.so,
// libpmix.so, ...) and tools/lsan.supp suppresses exactly those; a leak of ours still fails.
// The executable's definition comes first in symbol lookup, before libasan's interceptor and
// libc (-Wl,--export-dynamic-symbol=dlclose puts it in the dynamic symbol table).
extern "C" int dlclose(void*) { return 0; }
