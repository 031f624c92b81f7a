#include "landscape/backend.h"

namespace sb::landscape {

namespace {

class Local final : public ScanBackend {
 public:
  Result<LandscapeMap> Scan(const ScanParams& params, const Region& region,
                            const ScanOptions& options) override {
    return landscape::Scan(params, region, options);
  }
  bool IsRoot() const override { return true; }
  int Processes() const override { return 1; }
  const char* Name() const override { return "threads"; }
};

ScanBackend* g_backend = nullptr;

}  // namespace

ScanBackend& LocalBackend() {
  static Local local;
  return local;
}

void SetDefaultBackend(ScanBackend* backend) { g_backend = backend; }

ScanBackend& DefaultBackend() { return g_backend ? *g_backend : LocalBackend(); }

}  // namespace sb::landscape
