// strangebeta-mpi: the strangebeta command line with scans spread over MPI
// ranks (built only when MPI is found). Usage is the same as strangebeta:
//
//   mpirun -np K strangebeta-mpi landscape --grid 200 --out big.map --summary
//
// Every rank runs the command; scans are split across ranks (MpiBackend) and
// only rank 0 prints or writes anything. Other ranks' stdout and stderr go to
// /dev/null (set SB_MPI_VERBOSE=1 to keep them).
#include <mpi.h>

#include <cstdio>
#include <cstdlib>

#include "cli/commands.h"
#include "landscape/backend.h"
#include "landscape/mpi_backend.h"

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  int rc;
  {
    sb::landscape::MpiBackend backend;
    const char* verbose = std::getenv("SB_MPI_VERBOSE");
    if (backend.rank() != 0 && !(verbose && *verbose && *verbose != '0')) {
      if (!std::freopen("/dev/null", "w", stdout) || !std::freopen("/dev/null", "w", stderr)) {
        // Keep going; output just is not silenced.
      }
    }
    sb::landscape::SetDefaultBackend(&backend);
    rc = sb::cli::Main(argc, argv);
    sb::landscape::SetDefaultBackend(nullptr);
  }
  MPI_Finalize();
  return rc;
}
