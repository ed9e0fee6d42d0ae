#pragma once
// The live view's numbers as JSON (GET /state.json and GET /map.json, docs/hardware.md).

#include <nlohmann/json.hpp>

#include "algo/map/marker_map.hpp"
#include "firmware/live/live_snapshot.hpp"

namespace irloc::firmware {

// The attempt of `snapshot`: pose and covariance, each source's outcome, strobe verdict, counters,
// frame rate, stage times, the last minute's track and the warnings it gives.
nlohmann::json live_state_json(const LiveSnapshot& snapshot);

// The map's landmarks in the x-y plane of W, for the page's top view.
nlohmann::json live_map_json(const MarkerMap& map);

}  // namespace irloc::firmware
