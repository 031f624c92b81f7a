// Where scans run: in this process (threads), or spread over processes (the
// MPI driver, strangebeta-mpi, installs its backend at start-up). The CLI and
// the web app scan through DefaultBackend(), so the same commands run on a
// laptop or a cluster. No MPI types here.
#ifndef SB_LANDSCAPE_BACKEND_H_
#define SB_LANDSCAPE_BACKEND_H_

#include <vector>

#include "base/status.h"
#include "landscape/landscape.h"

namespace sb::landscape {

class ScanBackend {
 public:
  virtual ~ScanBackend() = default;
  // Scans the whole region. Every process of a multi-process backend must
  // call this collectively with the same arguments; the root process gets
  // the full map (identical to landscape::Scan), the others an empty map
  // (size() == 0). Errors: as landscape::Scan, reported on every process.
  virtual Result<LandscapeMap> Scan(const ScanParams& params, const Region& region,
                                    const ScanOptions& options) = 0;
  // Whether this process writes results (always true for the local backend).
  virtual bool IsRoot() const = 0;
  // Number of processes taking part (1 for the local backend).
  virtual int Processes() const = 0;
  // "threads" or "mpi".
  virtual const char* Name() const = 0;
  // On the root after a Scan: each process's wall-clock seconds for its own
  // share of the ICs (index = process), to show how work divides; empty when
  // the backend does not measure it. Not thread-safe.
  virtual std::vector<double> LastShareSeconds() const { return {}; }
};

// The in-process backend: landscape::Scan with threads. Thread-safe.
ScanBackend& LocalBackend();

// The process-wide backend used by the CLI: LocalBackend() unless one was
// installed. SetDefaultBackend(nullptr) restores the local one. Not owned.
// Set it once at start-up, before other threads run.
void SetDefaultBackend(ScanBackend* backend);
ScanBackend& DefaultBackend();

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_BACKEND_H_
