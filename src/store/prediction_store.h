// Issue 33 (the setting day): the grade predicted for a variation when its
// candidate was accepted (schema 21, routes.predicted_grade), kept so the
// report compares the prediction made that day with the ascent grade after
// N ticks. The text is the app's (app::PredictionText); the store keeps it
// as given. A separate interface over the same SQL layer (store/sql_store.cc
// implements it in the same object as Store, as store/import_store.h), so
// the route record of store/store.h stays as it is.
//
// No SQLite or libpq types appear in this header.
#ifndef SB_STORE_PREDICTION_STORE_H_
#define SB_STORE_PREDICTION_STORE_H_

#include <cstdint>
#include <string>

#include "base/status.h"
#include "store/store.h"

namespace sb::store {

class PredictionStore {
 public:
  virtual ~PredictionStore() = default;
  // Sets route `route_id`'s predicted grade ("" removes it). kNotFound for
  // an unknown route.
  virtual Status SetPredictedGrade(int64_t route_id, const std::string& text) = 0;
  // Route `route_id`'s predicted grade ("" when none was stored). kNotFound
  // for an unknown route.
  virtual Result<std::string> PredictedGrade(int64_t route_id) = 0;
};

// The PredictionStore of a store opened by store::OpenStore (both
// backends); nullptr for a Store that does not implement it. Not owned.
PredictionStore* PredictionStoreOf(Store* store);

}  // namespace sb::store

#endif  // SB_STORE_PREDICTION_STORE_H_
