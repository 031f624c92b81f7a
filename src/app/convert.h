// The one place where the store's rows become the app's view types
// (app/types.h) and back (issue 21, "Domain types first"). Internal to app:
// services convert at their boundary; web and CLI never include this file.
// Every conversion copies every field of the same name. Pure.
#ifndef SB_APP_CONVERT_H_
#define SB_APP_CONVERT_H_

#include <utility>
#include <vector>

#include "app/gyms.h"
#include "app/types.h"
#include "store/gym_store.h"
#include "store/store.h"
#include "store/tick_store.h"

namespace sb::app {

RouteSetter ToView(const store::RouteSetter& r);
store::RouteSetter ToRecord(const RouteSetter& v);
VariationInput ToView(const store::VariationInput& r);
store::VariationInput ToRecord(const VariationInput& v);
SourceRoute ToView(const store::SourceRoute& r);
store::SourceRoute ToRecord(const SourceRoute& v);
RouteView ToView(const store::RouteRecord& r);
store::RouteRecord ToRecord(const RouteView& v);
User ToView(const store::User& r);
store::User ToRecord(const User& v);
Session ToView(const store::Session& r);
store::Session ToRecord(const Session& v);
Feedback ToView(const store::FeedbackRecord& r);
store::FeedbackRecord ToRecord(const Feedback& v);
StudyRoute ToView(const store::StudyRoute& r);
store::StudyRoute ToRecord(const StudyRoute& v);
Study ToView(const store::StudyRecord& r);
store::StudyRecord ToRecord(const Study& v);
Tick ToView(const store::TickRecord& r);
store::TickRecord ToRecord(const Tick& v);
// A wall (app/gyms.h); its name is stored trimmed.
Wall ToView(const store::WallRecord& r);
store::WallRecord ToRecord(const Wall& v);

// The same for every row of a list, in order.
template <typename Row>
auto ToViews(const std::vector<Row>& rows) {
  std::vector<decltype(ToView(std::declval<const Row&>()))> out;
  out.reserve(rows.size());
  for (const Row& r : rows) out.push_back(ToView(r));
  return out;
}
template <typename View>
auto ToRecords(const std::vector<View>& views) {
  std::vector<decltype(ToRecord(std::declval<const View&>()))> out;
  out.reserve(views.size());
  for (const View& v : views) out.push_back(ToRecord(v));
  return out;
}

}  // namespace sb::app

#endif  // SB_APP_CONVERT_H_
