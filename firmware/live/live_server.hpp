#pragma once
// irlocd's live view (--http ADDR:PORT): an HTTP server on threads of its own, beside the frame
// loop and never in it. It reads the frame loop's LiveSlot, draws and encodes the picture
// (live_drawing.hpp, jpeg_encoder.hpp) and serves one offline page from the binary:
//
//   GET  /                 the page (live_page.html)
//   GET  /frame.jpg        the picture; ?image=on|difference (default on), ?width=64..1920 (480)
//   GET  /state.json       pose, outcomes, strobe, counters, stage times, track, warnings, controls
//   GET  /map.json         the map's landmarks, for the page's top view
//   POST /controls         {"exposure_us": 3000, "analogue_gain": 2, "frame_duration_us": 33333,
//                          "leds": false}: any of them, applied from the next frame
//   POST /controls/save    writes the controls in effect to the camera settings file
//
// Controls need write access: not with read_only, and on an address other than loopback the
// token (X-Irloc-Token header or ?token=). Bad requests get 400 (malformed, out of range), 403
// (no write access), 404, 405, 409 (nothing to save to, or a control the camera lacks), 413
// (body over 4 KiB) or 503 (too many connections at once, or no picture yet), each with a one-line
// plain-text reason.

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "firmware/live/live_drawing.hpp"
#include "firmware/live/live_snapshot.hpp"
#include "hal/camera_controls.hpp"

namespace irloc::firmware {

struct LiveServerSettings {
  std::string host = "127.0.0.1";
  int port = 0;                       // 0: any free port (printed at start)
  bool read_only = false;             // --http-read-only
  std::optional<std::string> token;   // controls need it when set
  std::optional<std::filesystem::path> camera_settings;  // where "save" writes (--camera-settings)
  int max_connections = 16;           // at once; more get 503
  int jpeg_quality = 70;
};

// The devices the controls act on; either may be absent.
struct LiveControlTargets {
  hal::CameraControls* camera = nullptr;
  std::atomic<bool>* leds_enabled = nullptr;  // LiveStrobing::leds_enabled, with live strobing
};

// "ADDR:PORT" or "[IPV6]:PORT"; throws InputError naming --http.
std::pair<std::string, int> parse_http_address(const std::string& spec);
bool is_loopback_address(const std::string& host);

class LiveServer {
 public:
  // Binds the address and starts serving. Throws InputError naming --http when it cannot bind.
  LiveServer(LiveServerSettings settings, LiveSlot& slot, LiveViewGeometry geometry, LiveControlTargets targets);
  ~LiveServer();  // stops serving and joins its threads
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace irloc::firmware
