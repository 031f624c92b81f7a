// The MPI scan backend (library sb_landscape_mpi, built only when MPI is
// found). Splits a region's ICs into one contiguous block per rank; each rank
// scans its block with threads (landscape::ScanRange) and rank 0 gathers the
// blocks in order, so the map is byte-identical to a threaded scan.
#ifndef SB_LANDSCAPE_MPI_BACKEND_H_
#define SB_LANDSCAPE_MPI_BACKEND_H_

#include <vector>

#include "landscape/backend.h"

namespace sb::landscape {

class MpiBackend final : public ScanBackend {
 public:
  // Requires MPI to be initialised (MPI_Init) and not yet finalised for the
  // object's whole life. Uses MPI_COMM_WORLD.
  MpiBackend();
  // Collective over MPI_COMM_WORLD. Threads per rank: options.threads, or
  // when 0 the hardware threads divided by the ranks on this node. Errors on
  // any rank are reported on every rank (the lowest failing rank's message).
  Result<LandscapeMap> Scan(const ScanParams& params, const Region& region,
                            const ScanOptions& options) override;
  bool IsRoot() const override { return rank_ == 0; }
  int Processes() const override { return size_; }
  const char* Name() const override { return "mpi"; }
  std::vector<double> LastShareSeconds() const override { return share_seconds_; }
  int rank() const { return rank_; }

 private:
  int rank_ = 0;
  int size_ = 1;
  int local_size_ = 1;
  std::vector<double> share_seconds_;  // root only
};

}  // namespace sb::landscape

#endif  // SB_LANDSCAPE_MPI_BACKEND_H_
