#include "firmware/live/live_server.hpp"

#include <arpa/inet.h>

#include <chrono>
#include <mutex>
#include <thread>
#include <utility>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "firmware/live/jpeg_encoder.hpp"
#include "firmware/live/live_page.hpp"
#include "firmware/live/live_state_json.hpp"
#include "io/config/camera_settings_file.hpp"
#include "io/config/yaml_reader.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

using nlohmann::json;

constexpr int kWorkerThreads = 8;
constexpr std::size_t kMaxBodyBytes = 4096;
constexpr int kDefaultImageWidth = 480;
constexpr int kMinImageWidth = 64, kMaxImageWidth = 1920;

// This worker thread serves a connection over the limit: every request on it gets 503.
thread_local bool t_over_limit = false;

// TaskQueue::enqueue returns void in cpp-httplib 0.11 (Debian 12) and, from 0.15 on (Debian 13's
// 0.18), bool: whether the connection was taken.
using EnqueueResult = decltype(std::declval<httplib::TaskQueue&>().enqueue(std::function<void()>()));

// httplib's thread pool, with at most `limit` connections in it at once; a connection over the
// limit is answered 503 by a thread of its own (and closed), never queued without bound.
class BoundedTaskQueue final : public httplib::TaskQueue {
 public:
  explicit BoundedTaskQueue(int limit) : limit_(limit), workers_(kWorkerThreads), refuser_(1) {}
  EnqueueResult enqueue(std::function<void()> connection) override {
    if (in_flight_.fetch_add(1) >= limit_) {
      in_flight_.fetch_sub(1);
      refuser_.enqueue([connection = std::move(connection)] {
        t_over_limit = true;
        connection();
        t_over_limit = false;
      });
    } else {
      workers_.enqueue([this, connection = std::move(connection)] {
        connection();
        in_flight_.fetch_sub(1);
      });
    }
    return static_cast<EnqueueResult>(true);  // taken: answered by a worker or refused with 503
  }
  void shutdown() override {
    workers_.shutdown();
    refuser_.shutdown();
  }

 private:
  int limit_;
  std::atomic<int> in_flight_{0};
  httplib::ThreadPool workers_;
  httplib::ThreadPool refuser_;
};

void plain(httplib::Response& res, int status, const std::string& reason) {
  res.status = status;
  res.set_content(reason + "\n", "text/plain; charset=utf-8");
}

bool equal_in_constant_time(const std::string& a, const std::string& b) {
  unsigned char difference = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) difference |= static_cast<unsigned char>(a[i] ^ b[i % std::max<std::size_t>(b.size(), 1)]);
  return difference == 0;
}

}  // namespace

std::pair<std::string, int> parse_http_address(const std::string& spec) {
  const auto bad = [&] { return io::InputError("--http " + spec + ": expected ADDRESS:PORT, e.g. 127.0.0.1:8080 or [::1]:8080"); };
  const std::size_t colon = spec.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == spec.size()) throw bad();
  std::string host = spec.substr(0, colon);
  const std::string port_text = spec.substr(colon + 1);
  if (host.front() == '[') {
    if (host.size() < 3 || host.back() != ']') throw bad();
    host = host.substr(1, host.size() - 2);
  } else if (host.find(':') != std::string::npos) {
    throw bad();  // an IPv6 address needs its brackets
  }
  if (port_text.size() > 5 || port_text.find_first_not_of("0123456789") != std::string::npos) throw bad();
  const int port = std::stoi(port_text);
  if (port > 65535) throw bad();
  unsigned char address[16];
  if (host != "localhost" && inet_pton(AF_INET, host.c_str(), address) != 1 && inet_pton(AF_INET6, host.c_str(), address) != 1) {
    throw io::InputError("--http " + spec + ": " + host + " is not an IP address (or localhost)");
  }
  return {host, port};
}

bool is_loopback_address(const std::string& host) {
  unsigned char address[4];
  if (inet_pton(AF_INET, host.c_str(), address) == 1) return address[0] == 127;
  return host == "localhost" || host == "::1";
}

struct LiveServer::Impl {
  Impl(LiveServerSettings s, LiveSlot& live_slot, LiveViewGeometry g, LiveControlTargets t)
      : settings(std::move(s)), slot(live_slot), geometry(std::move(g)), targets(t) {}

  LiveServerSettings settings;
  LiveSlot& slot;
  LiveViewGeometry geometry;
  LiveControlTargets targets;
  httplib::Server server;
  std::thread thread;
  int port = 0;

  // One picture is drawn at a time; a picture already drawn of the same attempt is served again.
  std::mutex render_mutex;
  LiveSnapshot snapshot;
  JpegEncoder encoder;
  BgrxImage picture;
  struct Cached {
    std::uint64_t publication = 0;
    LiveImage image = LiveImage::on;
    int width = 0;
    std::string jpeg;
  } cached;

  // Copies the slot's snapshot (under render_mutex) when it changed.
  void refresh_snapshot() {
    slot.mark_viewed(LiveSlot::Clock::now());
    if (slot.publication() != snapshot.publication) slot.read(snapshot);
  }

  bool may_write(const httplib::Request& req, std::string& why_not) const {
    if (settings.read_only) {
      why_not = "read-only (--http-read-only)";
      return false;
    }
    if (settings.token) {
      const std::string given = req.has_header("X-Irloc-Token") ? req.get_header_value("X-Irloc-Token") : req.get_param_value("token");
      if (given.empty() || !equal_in_constant_time(given, *settings.token)) {
        why_not = "controls need the token on this address (docs/hardware.md)";
        return false;
      }
    }
    return true;
  }

  json controls_json(const httplib::Request& req) const {
    std::string why_not;
    json controls = {{"writable", may_write(req, why_not)}, {"why_read_only", why_not},
                     {"can_save", settings.camera_settings.has_value()}};
    if (targets.camera) {
      for (const hal::CameraControl control : hal::kCameraControls) {
        if (const std::optional<hal::ControlRange> range = targets.camera->range(control)) {
          controls[std::string(hal::to_string(control))] = {
              {"value", targets.camera->current(control)}, {"min", range->min}, {"max", range->max}};
        }
      }
    }
    if (targets.leds_enabled) controls["leds"] = {{"value", targets.leds_enabled->load()}};
    return controls;
  }

  void frame(const httplib::Request& req, httplib::Response& res) {
    const std::string image_name = req.has_param("image") ? req.get_param_value("image") : "on";
    const std::optional<LiveImage> image = live_image_named(image_name);
    if (!image) return plain(res, 400, "image: expected on or difference, got '" + image_name + "'");
    int width = kDefaultImageWidth;
    if (req.has_param("width")) {
      const std::string text = req.get_param_value("width");
      if (text.empty() || text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos ||
          std::stoi(text) < kMinImageWidth || std::stoi(text) > kMaxImageWidth) {
        return plain(res, 400, "width: expected a whole number of pixels in [64, 1920], got '" + text + "'");
      }
      width = std::stoi(text);
    }
    const std::lock_guard lock(render_mutex);
    refresh_snapshot();
    if (snapshot.publication == 0) {
      res.set_header("Retry-After", "1");
      return plain(res, 503, "no picture yet: no pose attempt since the view was opened");
    }
    if (cached.publication != snapshot.publication || cached.image != *image || cached.width != width) {
      draw_live_view(snapshot, geometry, *image, width, picture);
      cached = {snapshot.publication, *image, width, encoder.encode(picture, settings.jpeg_quality)};
    }
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Irloc-Seq", std::to_string(snapshot.estimate.seq));
    res.set_header("X-Irloc-Publication", std::to_string(snapshot.publication));
    res.set_content(cached.jpeg, "image/jpeg");
  }

  void state(const httplib::Request& req, httplib::Response& res) {
    json body;
    {
      const std::lock_guard lock(render_mutex);
      refresh_snapshot();
      body = live_state_json(snapshot);
    }
    body["controls"] = controls_json(req);
    if (targets.leds_enabled && !targets.leds_enabled->load()) body["warnings"].push_back("LEDs switched off from the live view");
    res.set_header("Cache-Control", "no-store");
    res.set_content(body.dump(), "application/json");
  }

  void set_controls(const httplib::Request& req, httplib::Response& res) {
    std::string why_not;
    if (!may_write(req, why_not)) return plain(res, 403, "controls: " + why_not);
    const json body = json::parse(req.body, nullptr, false);
    if (body.is_discarded() || !body.is_object()) return plain(res, 400, "body: expected a JSON object such as {\"exposure_us\": 3000}");
    // Every value is checked before any is applied.
    std::array<std::optional<double>, hal::kCameraControls.size()> values;
    std::optional<bool> leds;
    for (const auto& [key, value] : body.items()) {
      if (key == "leds") {
        if (!value.is_boolean()) return plain(res, 400, "leds: expected true or false");
        if (!targets.leds_enabled) return plain(res, 409, "leds: this camera's LEDs are not strobed by irlocd");
        leds = value.get<bool>();
        continue;
      }
      const std::optional<hal::CameraControl> control = hal::camera_control_named(key);
      if (!control) return plain(res, 400, key + ": unknown control (expected exposure_us, analogue_gain, frame_duration_us or leds)");
      if (!value.is_number()) return plain(res, 400, key + ": expected a number");
      const std::optional<hal::ControlRange> range = targets.camera ? targets.camera->range(*control) : std::nullopt;
      if (!range) return plain(res, 409, key + ": this camera has no such control");
      const double number = value.get<double>();
      if (!(number >= range->min && number <= range->max)) {
        return plain(res, 400, key + ": must be in " + io::range_text(range->min, range->max) + ", got " + io::number_text(number));
      }
      values[static_cast<std::size_t>(*control)] = number;
    }
    for (const hal::CameraControl control : hal::kCameraControls) {
      if (const std::optional<double> value = values[static_cast<std::size_t>(control)]) targets.camera->request(control, *value);
    }
    if (leds) targets.leds_enabled->store(*leds);
    res.set_content(controls_json(req).dump(), "application/json");
  }

  void save_controls(const httplib::Request& req, httplib::Response& res) {
    std::string why_not;
    if (!may_write(req, why_not)) return plain(res, 403, "controls: " + why_not);
    if (!settings.camera_settings) return plain(res, 409, "save: irlocd was started without --camera-settings FILE");
    io::CameraSettings saved;
    if (targets.camera) {
      for (const hal::CameraControl control : hal::kCameraControls) {
        if (targets.camera->range(control)) saved[control] = targets.camera->current(control);
      }
    }
    if (targets.leds_enabled) saved.leds = targets.leds_enabled->load();
    try {
      io::write_camera_settings(*settings.camera_settings, saved);
    } catch (const io::InputError& e) {
      return plain(res, 500, e.what());
    }
    plain(res, 200, "saved to " + settings.camera_settings->string());
  }

  void route() {
    server.new_task_queue = [limit = settings.max_connections] { return new BoundedTaskQueue(limit); };
    server.set_payload_max_length(kMaxBodyBytes);
    server.set_read_timeout(5, 0);
    server.set_write_timeout(5, 0);
    server.set_keep_alive_timeout(2);
    server.set_keep_alive_max_count(100);
    server.set_pre_routing_handler([](const httplib::Request&, httplib::Response& res) {
      if (!t_over_limit) return httplib::Server::HandlerResponse::Unhandled;
      res.set_header("Connection", "close");
      res.set_header("Retry-After", "1");
      plain(res, 503, "too many connections at once: try again");
      return httplib::Server::HandlerResponse::Handled;
    });
    server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;
      if (res.status == 413) plain(res, 413, "body: larger than 4096 bytes");
      else if (res.status == 404) plain(res, 404, req.path + ": no such page (/, /frame.jpg, /state.json, /map.json, /controls)");
      else plain(res, res.status, "bad request");
    });
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
      try {
        std::rethrow_exception(error);
      } catch (const std::exception& e) {
        plain(res, 500, std::string("internal error: ") + e.what());
      } catch (...) {
        plain(res, 500, "internal error");
      }
    });
    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(std::string(kLivePageHtml), "text/html; charset=utf-8");
    });
    server.Get("/frame.jpg", [this](const httplib::Request& req, httplib::Response& res) { frame(req, res); });
    server.Get("/state.json", [this](const httplib::Request& req, httplib::Response& res) { state(req, res); });
    const json map = live_map_json(geometry.map);
    server.Get("/map.json", [map](const httplib::Request&, httplib::Response& res) { res.set_content(map.dump(), "application/json"); });
    server.Post("/controls", [this](const httplib::Request& req, httplib::Response& res) { set_controls(req, res); });
    server.Post("/controls/save", [this](const httplib::Request& req, httplib::Response& res) { save_controls(req, res); });
    // Known paths with another method: 405; the rest: 404 (the error handler).
    const auto wrong_method = [](const httplib::Request& req, httplib::Response& res) {
      static const char* const kPaths[] = {"/", "/frame.jpg", "/state.json", "/map.json", "/controls", "/controls/save"};
      for (const char* path : kPaths) {
        if (req.path == path) {
          const bool post = req.path.starts_with("/controls");
          res.set_header("Allow", post ? "POST" : "GET");
          return plain(res, 405, req.method + " " + req.path + ": method not allowed (use " + (post ? "POST" : "GET") + ")");
        }
      }
      plain(res, 404, req.path + ": no such page (/, /frame.jpg, /state.json, /map.json, /controls)");
    };
    server.Get(".*", wrong_method);
    server.Post(".*", wrong_method);
    server.Put(".*", wrong_method);
    server.Delete(".*", wrong_method);
    server.Patch(".*", wrong_method);
  }
};

LiveServer::LiveServer(LiveServerSettings settings, LiveSlot& slot, LiveViewGeometry geometry, LiveControlTargets targets)
    : impl_(std::make_unique<Impl>(std::move(settings), slot, std::move(geometry), targets)) {
  Impl& impl = *impl_;
  impl.route();
  const std::string address = impl.settings.host + ":" + std::to_string(impl.settings.port);
  if (impl.settings.host.find(':') != std::string::npos) impl.server.set_address_family(AF_INET6);
  const bool bound = impl.settings.port == 0 ? (impl.port = impl.server.bind_to_any_port(impl.settings.host)) > 0
                                              : impl.server.bind_to_port(impl.settings.host, impl.port = impl.settings.port);
  if (!bound) throw io::InputError("--http " + address + ": cannot listen there (address in use, or not this machine's)");
  impl.thread = std::thread([&impl] { impl.server.listen_after_bind(); });
}

LiveServer::~LiveServer() {
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

int LiveServer::port() const { return impl_->port; }

}  // namespace irloc::firmware
