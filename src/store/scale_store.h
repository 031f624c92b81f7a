// Issue 32: a gym's own grade scales and the scale a wall's grades are read
// in (schema 17). A separate interface over the same SQL layer (store/
// sql_store.cc implements it in the same object as Store and GymStore), so
// the wall record of store/gym_store.h stays as it is.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_SCALE_STORE_H_
#define SB_STORE_SCALE_STORE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

// One gym scale: its labels one per line, "label<TAB>from<TAB>to" (the
// API's {"label","from","to"}; grades/gym_scale.h reads them).
struct ScaleRecord {
  int64_t id = 0;
  int64_t gym_id = 0;
  std::string name;
  std::string labels;
};

class ScaleStore {
 public:
  virtual ~ScaleStore() = default;
  // kConflict when the gym has a scale of that name (ignoring ASCII case).
  virtual Result<int64_t> InsertScale(const ScaleRecord& s) = 0;
  // The gym's scales, oldest first.
  virtual Result<std::vector<ScaleRecord>> ListScales(int64_t gym_id) = 0;
  // The scale a wall's grades are read in ("" = none given: read as before).
  virtual Result<std::string> WallScale(int64_t wall_id) = 0;
  // kNotFound for an unknown wall.
  virtual Status SetWallScale(int64_t wall_id, const std::string& scale) = 0;
};

// The ScaleStore of a store opened by store::OpenStore (both backends);
// nullptr for a Store that does not implement it. Not owned.
ScaleStore* ScaleStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_SCALE_STORE_H_
