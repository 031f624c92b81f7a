#include "landscape/mpi_backend.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <new>
#include <string>
#include <thread>
#include <vector>

namespace sb::landscape {

namespace {

// Elements per message: well under INT_MAX for any element type.
constexpr uint64_t kMsg = uint64_t{1} << 26;

// Block [lo, hi) of rank r out of p over `total` ICs.
void Block(uint64_t total, int p, int r, uint64_t* lo, uint64_t* hi) {
  uint64_t base = total / p, extra = total % p;
  *lo = r * base + std::min<uint64_t>(r, extra);
  *hi = *lo + base + (static_cast<uint64_t>(r) < extra ? 1 : 0);
}

template <typename T>
void SendChunks(const T* data, uint64_t count, MPI_Datatype type, int tag) {
  for (uint64_t off = 0; off < count; off += kMsg) {
    int len = static_cast<int>(std::min(kMsg, count - off));
    MPI_Send(data + off, len, type, 0, tag, MPI_COMM_WORLD);
  }
}

template <typename T>
void RecvChunks(T* data, uint64_t count, MPI_Datatype type, int src, int tag) {
  for (uint64_t off = 0; off < count; off += kMsg) {
    int len = static_cast<int>(std::min(kMsg, count - off));
    MPI_Recv(data + off, len, type, src, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  }
}

}  // namespace

MpiBackend::MpiBackend() {
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &local_size_);
  MPI_Comm_free(&node);
}

Result<LandscapeMap> MpiBackend::Scan(const ScanParams& params, const Region& region,
                                      const ScanOptions& options) {
  // Validation is deterministic, so every rank agrees without talking.
  SB_RETURN_IF_ERROR(ValidateScan(params, region));
  const uint64_t total = region.size();
  uint64_t lo, hi;
  Block(total, size_, rank_, &lo, &hi);

  ScanOptions local = options;
  if (local.threads <= 0) {
    int hw = static_cast<int>(std::thread::hardware_concurrency());
    local.threads = std::max(1, hw / std::max(1, local_size_));
  }
  if (rank_ != 0) local.progress = nullptr;

  LandscapeMap map;
  std::vector<uint16_t> effect;
  std::vector<uint32_t> disp;
  uint16_t* e = nullptr;
  uint32_t* d = nullptr;
  Status st;
  try {
    if (rank_ == 0) {
      map.params = params;
      map.region = region;
      map.effect.resize(total);
      map.displacement.resize(total);
      e = map.effect.data() + lo;
      d = map.displacement.data() + lo;
    } else {
      effect.resize(hi - lo);
      disp.resize(hi - lo);
      e = effect.data();
      d = disp.data();
    }
  } catch (const std::bad_alloc&) {
    st = Status::InvalidInput("grid: rank " + std::to_string(rank_) +
                              " has not enough memory for its ICs (6 bytes per IC; rank 0 holds "
                              "the whole map)");
  }
  auto t0 = std::chrono::steady_clock::now();
  if (st.ok()) st = ScanRange(params, region, lo, hi - lo, e, d, local);
  double mine = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  share_seconds_.assign(rank_ == 0 ? size_ : 0, 0.0);
  MPI_Gather(&mine, 1, MPI_DOUBLE, rank_ == 0 ? share_seconds_.data() : nullptr, 1, MPI_DOUBLE, 0,
             MPI_COMM_WORLD);

  // Agree on failure: the lowest failing rank's message goes to everyone.
  int failed_rank = st.ok() ? size_ : rank_, first_failed = size_;
  MPI_Allreduce(&failed_rank, &first_failed, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first_failed < size_) {
    std::string msg = st.message();
    int len = static_cast<int>(msg.size());
    MPI_Bcast(&len, 1, MPI_INT, first_failed, MPI_COMM_WORLD);
    msg.resize(len);
    MPI_Bcast(msg.data(), len, MPI_CHAR, first_failed, MPI_COMM_WORLD);
    return Status::InvalidInput(msg);
  }

  // Gather the blocks, in rank order, at rank 0.
  if (rank_ == 0) {
    for (int r = 1; r < size_; ++r) {
      uint64_t rlo, rhi;
      Block(total, size_, r, &rlo, &rhi);
      RecvChunks(map.effect.data() + rlo, rhi - rlo, MPI_UINT16_T, r, 1);
      RecvChunks(map.displacement.data() + rlo, rhi - rlo, MPI_UINT32_T, r, 2);
    }
    if (options.progress) options.progress(total, total);
    return map;
  }
  SendChunks(effect.data(), effect.size(), MPI_UINT16_T, 1);
  SendChunks(disp.data(), disp.size(), MPI_UINT32_T, 2);
  return LandscapeMap{};
}

}  // namespace sb::landscape
