// Linked into the sanitizer build's tests and PETSc plugin when PETSc is built in (CMakeLists.txt):
// PETSc's PetscOptionsBegin_Private(), with what it allocates left out of LeakSanitizer's check.
// Every PETSc XSetFromOptions() reads its options in a block that begins by copying the block's
// title and prefix (PetscOptionsBegin_Private) and ends by freeing them (PetscOptionsEnd).
// On a bad option (an unknown -ksp_type, which the tests give on purpose) PETSc 3.18 returns
// from inside the block, and the copies are lost: PETSc's own leak, 32 bytes per bad option.
// LeakSanitizer cannot tell those bytes from a PETSc object of ours left undestroyed, since its
// unwinder stops in PetscMallocAlign (Debian's PETSc has no frame pointers), so no entry of
// tools/lsan.supp can name them. The copies are all this call allocates (besides PETSc's
// process-wide list of help already printed); a Vec, Mat, KSP or communicator that our code
// forgets to free is still reported. PETSc calls this function through its PLT, so the
// definition it reaches is the test executable's (-Wl,--export-dynamic-symbol), or the PETSc
// plugin's, which comes before PETSc in the plugin's own scope; RTLD_NEXT is PETSc's, after it.
#include <dlfcn.h>
#include <petscsys.h>
#include <sanitizer/lsan_interface.h>

extern "C" PetscErrorCode PetscOptionsBegin_Private(PetscOptionItems* items, MPI_Comm comm, const char prefix[],
                                                    const char title[], const char mansec[]) {
  using Begin = PetscErrorCode (*)(PetscOptionItems*, MPI_Comm, const char[], const char[], const char[]);
  static const Begin petsc_begin = reinterpret_cast<Begin>(dlsym(RTLD_NEXT, "PetscOptionsBegin_Private"));
  __lsan::ScopedDisabler not_checked;
  return petsc_begin(items, comm, prefix, title, mansec);
}
