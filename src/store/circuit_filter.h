// Issue 31: a route list filtered by a gym circuit's id (GET
// /api/routes?circuit=<id>), not by its colour. store::RouteFilter has no
// field for it (store/store.h is being moved into src/gym meanwhile): the
// filter's `colour` carries the id in this form, which no colour of
// plan/colour.h has, and the SQL layer (sql_store.cc FilterWhere) matches
// routes.circuit_id for it. To become a field of its own with the move.
#ifndef SB_STORE_CIRCUIT_FILTER_H_
#define SB_STORE_CIRCUIT_FILTER_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sb::store {

inline constexpr std::string_view kCircuitIdPrefix = "circuit-id:";

// The RouteFilter::colour that matches the routes set in circuit `id`.
inline std::string CircuitIdFilter(int64_t id) {
  return std::string(kCircuitIdPrefix) + std::to_string(id);
}

// The circuit id of a RouteFilter::colour made by CircuitIdFilter; nullopt
// for a colour.
inline std::optional<int64_t> CircuitIdOfFilter(std::string_view colour) {
  if (colour.substr(0, kCircuitIdPrefix.size()) != kCircuitIdPrefix) return std::nullopt;
  std::string_view digits = colour.substr(kCircuitIdPrefix.size());
  if (digits.empty() || digits.size() > 18) return std::nullopt;
  int64_t id = 0;
  for (char c : digits) {
    if (c < '0' || c > '9') return std::nullopt;
    id = id * 10 + (c - '0');
  }
  return id;
}

}  // namespace sb::store

#endif  // SB_STORE_CIRCUIT_FILTER_H_
