// Issue 28's goals on families of rendered survey drives (docs/survey.md, "Goal evaluation"):
// scenes drawn from a seed in four classes, each rendered at 1280 x 960 (the camera, LEDs and
// ceiling of host_sim/scenarios/survey_corridor_new_markers.yaml) and surveyed by irlocd from a
// drawing that has one marker fixed, some markers 5-25 cm and up to 5 degrees off and some not at
// all; the robot at 0.3 m/s, one on/off pair in 4 of 10 frames per second kept.
//   corridor  two rows 1.6-2.0 m apart, out, back and out again; the far 2-4 markers not drawn
//   room      a 3 x 3 grid, a lawn-mower sweep; 2-3 markers not drawn
//   loop      8 markers on a ring, two laps of a loop inside it; 2-3 not drawn
//   edges     a corridor whose rows are 1.3-1.6 m to each side of the path: seen near the image's
//             edges only
// and a `moved` class: a corridor surveyed once, then two markers moved 0.3-0.9 m and driven once
// more out and back from the first survey's map; and a `weave` class: the corridor driven zig-zag
// 0.15 m to each side of the middle (a curved path: see docs/survey.md, "Straight drives").
// Per scene: markers whole in view in >= 8 LED-on frames that are missing from MAP_OUT (or that it
// keeps unknown, at the weak prior's sigma), markers invented, the largest error of the markers
// MAP_OUT claims to know (an unknown one keeps its drawing and says so), the normalized errors per axis, the pose rate over the attempts with
// a marker whole in view (and over those with only undrawn markers in view), gross errors, and the
// added / moved lines on stderr. Every miss is printed; the totals per class and goal_met at the end
// (a class meets the goal when none is missing or invented, every marker is within 5 mm and 0.2
// degrees, the normalized errors' RMS per axis is within 0.5-1.5, the poses reach 95 % without a
// gross error, and every move and addition is reported).
//
// Then per class and over every class the normalized errors' RMS per axis with its 95 % interval
// over the installations surveyed (the scene is the unit: its markers share their errors).
//
//   survey_goal [--scenes=N] [--seed=S | --seeds=S,S,...] [--out=DIR] [--supersampling=N] [--class=NAME] [--reuse]
// N scenes per class (default 2), seed S (default 28); --seeds pools several seeds' families, each
// in DIR/seed_S.
// --supersampling=N renders with N x N rays per pixel (default: the renderer's 3).
// --class=NAME runs one class's scenes alone (the same scenes, folders and seeds as in the full run).
// --reuse surveys the datasets an earlier run of the same seed rendered under DIR again instead of
// rendering them anew (after a change to the estimator: seconds per scene instead of minutes).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "host_sim/run/pipeline_process.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "host_sim/tools/survey_drive.hpp"
#include "tests/survey/scene_interval.hpp"

namespace irloc::test {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kSpeed = 0.3;     // m/s
constexpr int kPairStride = 4;     // one on/off pair in 4 of the 10 frames per second
constexpr double kWeave = 0.15;    // m: the weaving corridor's path zig-zags this far to each side
constexpr double kMaxError = 0.005;
constexpr double kMaxYawError = 0.2 * kDegree;
constexpr double kPoseRate = 0.95;

int marker_id(int index) { return 1000 + 37 * index; }

struct DrawnScene {
  std::string name;
  sim::Scenario scenario;  // its map: the truth
  MarkerMap drawing;
  std::vector<int> moved;  // markers the drawing (an earlier survey) has where they were before
};

DotMarker ceiling_marker(int index, double x, double y) {
  DotMarker marker;
  marker.id = marker_id(index);
  marker.origin = {x, y, 2.6};
  return marker;
}

// The truth from the drawn places: marker 0 exact and fixed, `off` others off by 5-25 cm and up
// to 5 degrees, `absent` others left out of the drawing.
void install(const std::vector<DotMarker>& drawn, int absent, std::mt19937& random, DrawnScene& scene) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<int> order(drawn.size() - 1);
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i) + 1;
  std::shuffle(order.begin(), order.end(), random);
  std::vector<bool> left_out(drawn.size(), false);
  for (int k = 0; k < absent; ++k) left_out[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])] = true;
  scene.scenario.map.dot_markers.clear();
  scene.drawing.dot_markers.clear();
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    DotMarker real = drawn[i];
    if (i > 0) {
      const double angle = 2 * std::numbers::pi * unit(random), distance = 0.05 + 0.2 * unit(random);
      real.origin += Eigen::Vector3d(distance * std::cos(angle), distance * std::sin(angle), 0.0);
      real.yaw = (2 * unit(random) - 1) * 5 * kDegree;
    }
    scene.scenario.map.dot_markers.push_back(real);
    if (left_out[i]) continue;
    DotMarker drawing = drawn[i];
    drawing.fixed = i == 0;
    scene.drawing.dot_markers.push_back(drawing);
  }
}

void drive(sim::Scenario& scenario, const std::vector<Eigen::Vector2d>& points, double extra_seconds = 0) {
  scenario.trajectory = {};
  scenario.trajectory.kind = sim::TrajectoryKind::waypoints;
  scenario.trajectory.points = points;
  scenario.trajectory.speeds.assign(points.size() - 1, kSpeed);
  double length = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) length += (points[i + 1] - points[i]).norm();
  scenario.frames = static_cast<int>(std::ceil((length / kSpeed + extra_seconds) * scenario.camera.frame_rate));
}

DrawnScene corridor(const sim::Scenario& base, std::mt19937& random, double half_width, const std::string& name,
                    double weave = 0) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  DrawnScene scene{name, base, {}, {}};
  const int rows = 5 + static_cast<int>(unit(random) * 2);  // 5 or 6 along
  const double spacing = 1.6 + 0.4 * unit(random);
  std::vector<DotMarker> drawn;
  for (int k = 0; k < 2 * rows; ++k) {
    drawn.push_back(ceiling_marker(k, 0.9 + (k % 2 == 0 ? -half_width : half_width), spacing * (k / 2)));
  }
  // The far markers are the undrawn ones: there only new markers are in view.
  const int absent = 2 + static_cast<int>(unit(random) * 3);
  install(drawn, 0, random, scene);
  scene.drawing.dot_markers.resize(drawn.size() - static_cast<std::size_t>(absent));
  const double end = spacing * (rows - 1) + 0.1;
  if (weave == 0) {
    drive(scene.scenario, {{0.9, -0.3}, {0.9, end}, {0.9, -0.3}, {0.9, end}}, 5);
    return scene;
  }
  std::vector<Eigen::Vector2d> points;
  for (int pass = 0; pass < 3; ++pass) {
    const int steps = static_cast<int>(std::ceil((end + 0.3) / 0.7));
    for (int k = pass == 0 ? 0 : 1; k <= steps; ++k) {  // a pass starts where the last one ended
      const double along = -0.3 + (end + 0.3) * k / steps;
      points.push_back({0.9 + (k % 2 == 0 ? -weave : weave), pass % 2 == 0 ? along : end - 0.3 - along});
    }
  }
  drive(scene.scenario, points, 5);
  return scene;
}

DrawnScene room(const sim::Scenario& base, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double spacing = 1.5 + 0.4 * unit(random), far = 2 * spacing;
  std::vector<DotMarker> drawn;
  for (int k = 0; k < 9; ++k) drawn.push_back(ceiling_marker(k, spacing * (k % 3), spacing * (k / 3)));
  DrawnScene scene{"room", base, {}, {}};
  install(drawn, 2 + static_cast<int>(unit(random) * 2), random, scene);
  drive(scene.scenario, {{0, -0.3}, {0, far + 0.3}, {spacing, far + 0.3}, {spacing, -0.3}, {far, -0.3}, {far, far + 0.3},
                         {0, far + 0.3}, {0, -0.3}}, 10);
  return scene;
}

// Two laps of a loop 0.6 m inside a ring of 8 markers.
DrawnScene loop(const sim::Scenario& base, std::mt19937& random) {
  const double radius = 2.0 + 0.5 * std::uniform_real_distribution<double>(0.0, 1.0)(random);
  std::vector<DotMarker> drawn;
  for (int k = 0; k < 8; ++k) {
    const double angle = 2 * std::numbers::pi * k / 8;
    drawn.push_back(ceiling_marker(k, radius * std::cos(angle), radius * std::sin(angle)));
  }
  DrawnScene scene{"loop", base, {}, {}};
  install(drawn, 2 + static_cast<int>(std::uniform_real_distribution<double>(0.0, 2.0)(random)), random, scene);
  sim::TrajectorySpec& path = scene.scenario.trajectory;
  path = {};
  path.kind = sim::TrajectoryKind::loop;
  path.centre = {0, 0};
  path.radius = radius - 0.6;
  path.speed = kSpeed;
  scene.scenario.frames = static_cast<int>(std::ceil(2 * 2 * std::numbers::pi * path.radius / kSpeed * scene.scenario.camera.frame_rate));
  return scene;
}

// A corridor surveyed once; then two drawn markers moved 0.3-0.9 m and a pass out and back.
std::array<DrawnScene, 2> moved(const sim::Scenario& base, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  DrawnScene first = corridor(base, random, 0.9, "moved (first survey)");
  DrawnScene second = first;
  second.name = "moved";
  const int drawn = static_cast<int>(first.drawing.dot_markers.size());
  for (int k = 0; k < 2; ++k) {
    const int index = 1 + (k * (drawn - 1)) / 2 + static_cast<int>(unit(random) * ((drawn - 1) / 2));
    DotMarker& real = second.scenario.map.dot_markers[static_cast<std::size_t>(index)];
    const double angle = 2 * std::numbers::pi * unit(random), distance = 0.3 + 0.6 * unit(random);
    real.origin += Eigen::Vector3d(distance * std::cos(angle), distance * std::sin(angle), 0.0);
    second.moved.push_back(real.id);
  }
  const auto& points = first.scenario.trajectory.points;
  drive(second.scenario, {points[0], points[1], points[0]}, 3);
  second.scenario.seed += 1;
  return {first, second};
}

struct ClassTotals {
  int scenes = 0, required = 0, missing = 0, invented = 0, eligible = 0, posed = 0, gross = 0;
  int new_only_eligible = 0, new_only_posed = 0, moves = 0, moves_reported = 0, added_unreported = 0;
  double max_error = 0, max_yaw = 0;
  std::vector<SceneSquares> installations;  // per installation: a `moved` scene's two surveys are one
};

// Scores one run, prints it and every miss, and adds it to the totals; `resurvey`: a survey of the
// installation the class's last run surveyed (its normalized errors share that run's).
void account(const DrawnScene& scene, const sim::SurveyDriveScore& score, bool resurvey, ClassTotals& totals) {
  ++totals.scenes;
  totals.required += static_cast<int>(score.required.size());
  totals.missing += static_cast<int>(score.required_missing.size());
  totals.invented += static_cast<int>(score.map.invented.size());
  totals.eligible += score.eligible;
  totals.posed += score.posed;
  totals.gross += score.gross;
  totals.new_only_eligible += score.new_only_eligible;
  totals.new_only_posed += score.new_only_posed;
  totals.max_error = std::max(totals.max_error, score.map.max_position_m);
  totals.max_yaw = std::max(totals.max_yaw, score.map.max_yaw_rad);
  if (!resurvey || totals.installations.empty()) totals.installations.emplace_back();
  SceneSquares& installation = totals.installations.back();
  for (std::size_t axis = 0; axis < 4; ++axis) {
    installation.squares[axis] += score.normalized_rms[axis] * score.normalized_rms[axis] * score.normalized_count;
  }
  installation.markers += score.normalized_count;
  for (const int id : scene.moved) {
    ++totals.moves;
    const bool found = std::count(score.moved_reported.begin(), score.moved_reported.end(), id) > 0;
    totals.moves_reported += found ? 1 : 0;
    if (!found) std::fprintf(stderr, "  %s: the move of marker %d not reported\n", scene.name.c_str(), id);
  }
  for (const DotMarker& marker : scene.scenario.map.dot_markers) {
    const bool drawn = scene.drawing.find_dot_marker(marker.id) != nullptr;
    const bool learned = std::count(score.map.missing.begin(), score.map.missing.end(), marker.id) == 0;
    if (drawn || !learned) continue;
    if (std::count(score.added_reported.begin(), score.added_reported.end(), marker.id) != 1) {
      ++totals.added_unreported;
      std::fprintf(stderr, "  %s: marker %d learned without one `added` line\n", scene.name.c_str(), marker.id);
    }
  }
  for (const int id : score.required_missing) {
    std::fprintf(stderr, "  %s: marker %d not in MAP_OUT or unknown there\n", scene.name.c_str(), id);
  }
  for (const int id : score.map.unknown) std::fprintf(stderr, "  %s: marker %d kept unknown (sigma 1 m)\n", scene.name.c_str(), id);
  for (const int id : score.map.invented) std::fprintf(stderr, "  %s: marker %d invented\n", scene.name.c_str(), id);
  for (const sim::SurveyMarkerError& error : score.map.markers) {
    if (error.position_m > kMaxError || error.yaw_rad > kMaxYawError) {
      std::fprintf(stderr, "  %s: marker %d off by %.2f mm, %.3f deg\n", scene.name.c_str(), error.id,
                   1e3 * error.position_m, error.yaw_rad / kDegree);
    }
  }
  std::printf("%-22s required %2zu missing %zu invented %zu unknown %zu  max %.2f mm %.3f deg  NE rms %.2f %.2f %.2f %.2f  "
              "poses %3d/%3d (new-only %d/%d) gross %d  rmse %.2f mm max %.2f mm  added %zu moved %zu\n",
              scene.name.c_str(), score.required.size(), score.required_missing.size(), score.map.invented.size(),
              score.map.unknown.size(), 1e3 * score.map.max_position_m, score.map.max_yaw_rad / kDegree, score.normalized_rms[0],
              score.normalized_rms[1], score.normalized_rms[2], score.normalized_rms[3], score.posed, score.eligible,
              score.new_only_posed, score.new_only_eligible, score.gross, 1e3 * score.pose_rmse_m, 1e3 * score.pose_max_m,
              score.added_reported.size(), score.moved_reported.size());
  std::fflush(stdout);
}

bool report(const char* name, const ClassTotals& t) {
  const double rate = t.eligible > 0 ? static_cast<double>(t.posed) / t.eligible : 0;
  const std::array<double, 4> ne = rms_over_scenes(t.installations);
  const bool sigmas_right = std::all_of(ne.begin(), ne.end(), [](double rms) {
    return rms >= sim::kMinNormalizedRms && rms <= sim::kMaxNormalizedRms;
  });
  const bool met = t.missing == 0 && t.invented == 0 && t.max_error <= kMaxError && t.max_yaw <= kMaxYawError &&
                   sigmas_right && rate >= kPoseRate && t.gross == 0 && t.moves_reported == t.moves &&
                   t.added_unreported == 0;
  std::printf("class %-8s scenes %d: missing %d of %d, invented %d, max %.2f mm %.3f deg, NE rms x %.2f y %.2f z %.2f "
              "yaw %.2f, poses %.1f %% of %d (new-only %d of %d), gross %d, moves reported %d of %d, goal_met %d\n",
              name, t.scenes, t.missing, t.required, t.invented, 1e3 * t.max_error, t.max_yaw / kDegree, ne[0], ne[1],
              ne[2], ne[3], 100 * rate, t.eligible, t.new_only_posed, t.new_only_eligible, t.gross, t.moves_reported,
              t.moves, met ? 1 : 0);
  return met;
}

void print_pooled(const char* name, const PooledRms& pooled) {
  std::printf("sigmas %-11s installations %3d markers %4d  NE rms", name, pooled.scenes, pooled.markers);
  const std::array<const char*, 4> axes = {"x", "y", "z", "yaw"};
  for (std::size_t axis = 0; axis < 4; ++axis) {
    std::printf("  %s %.2f [%.2f-%.2f]", axes[axis], pooled.rms[axis], pooled.low[axis], pooled.high[axis]);
  }
  std::printf("  interval holds 1: %d %d %d %d\n", pooled.interval_includes_one(0), pooled.interval_includes_one(1),
              pooled.interval_includes_one(2), pooled.interval_includes_one(3));
}

// The normalized errors' RMS per axis per class and over every class, each with its 95 % interval
// over the installations surveyed (scene_interval.hpp): one scene's markers share most of their
// error along the chain from the fixed marker, so a class's RMS over one or two scenes scatters
// widely even with exact sigmas (docs/survey.md, "How far one drive's RMS scatters").
void report_pooled_sigmas(const std::array<const char*, 6>& names, const std::array<ClassTotals, 6>& totals) {
  std::vector<SceneSquares> every;
  for (std::size_t c = 0; c < totals.size(); ++c) {
    if (totals[c].installations.empty()) continue;
    print_pooled(names[c], pooled_rms_over_scenes(totals[c].installations));
    every.insert(every.end(), totals[c].installations.begin(), totals[c].installations.end());
  }
  if (!every.empty()) print_pooled("every class", pooled_rms_over_scenes(every));
}

bool parse_flag(std::string_view argument, std::string_view flag, long minimum, long& value) {
  if (argument.substr(0, flag.size()) != flag) return false;
  const std::string digits(argument.substr(flag.size()));
  char* end = nullptr;
  value = std::strtol(digits.c_str(), &end, 10);
  if (digits.empty() || *end != '\0' || value < minimum) {
    std::fprintf(stderr, "survey_goal: %.*s needs an integer >= %ld\n", static_cast<int>(flag.size()), flag.data(), minimum);
    std::exit(2);
  }
  return true;
}

// Seeds as a comma-separated list ("--seeds=28,11,41").
bool parse_seeds(std::string_view argument, std::vector<long>& seeds) {
  constexpr std::string_view flag = "--seeds=";
  if (argument.substr(0, flag.size()) != flag) return false;
  std::string_view rest = argument.substr(flag.size());
  seeds.clear();
  while (true) {
    const std::size_t comma = rest.find(',');
    long seed = 0;
    parse_flag(std::string(flag).append(rest.substr(0, comma)), flag, 0, seed);  // exits naming --seeds= if not a seed
    seeds.push_back(seed);
    if (comma == std::string_view::npos) return true;
    rest = rest.substr(comma + 1);
  }
}

constexpr std::array<const char*, 6> kClassNames = {"corridor", "room", "loop", "edges", "moved", "weave"};

struct GoalRun {
  sim::Scenario base;
  std::filesystem::path irlocd;
  sim::DatasetReuse reuse = sim::DatasetReuse::render;
  std::string only;  // one class's name: only its scenes
  std::array<ClassTotals, 6> totals;
};

// Draws `scenes` scenes per class from `seed`, surveys them in folders under `out` and adds them to
// the run's totals.
void survey_family(long seed, long scenes, const std::filesystem::path& out, GoalRun& run) {
  std::mt19937 random(static_cast<unsigned>(seed));
  int index = 0;
  const auto survey = [&](DrawnScene scene, std::size_t which, const MarkerMap& start, bool resurvey = false) {
    if (!run.only.empty() && run.only != kClassNames[which]) {
      ++index;  // every scene keeps its folder and seed whichever classes run
      return MarkerMap{};
    }
    scene.drawing = start;  // what the run started from: markers not in it are new to it
    scene.scenario.seed = static_cast<std::uint64_t>(seed) * 1000 + static_cast<std::uint64_t>(index);
    const std::filesystem::path dir = out / (std::string(kClassNames[which]) + "_" + std::to_string(index++));
    if (run.reuse == sim::DatasetReuse::render) std::filesystem::remove_all(dir);
    const sim::SurveyDriveScore score = sim::run_survey_drive(scene.scenario, start, dir, run.irlocd, run.reuse);
    account(scene, score, resurvey, run.totals[which]);
    return sim::surveyed_map(dir);
  };
  for (long k = 0; k < scenes; ++k) {
    const DrawnScene straight = corridor(run.base, random, 0.9, "corridor");
    survey(straight, 0, straight.drawing);
    const DrawnScene grid = room(run.base, random);
    survey(grid, 1, grid.drawing);
    const DrawnScene ring = loop(run.base, random);
    survey(ring, 2, ring.drawing);
    const double half_width = 1.3 + 0.3 * std::uniform_real_distribution<double>(0, 1)(random);
    const DrawnScene edges = corridor(run.base, random, half_width, "edges");
    survey(edges, 3, edges.drawing);
    const std::array<DrawnScene, 2> twice = moved(run.base, random);
    const MarkerMap first = survey(twice[0], 4, twice[0].drawing);
    survey(twice[1], 4, first, true);
  }
  // Drawn from a stream of their own, after the others: adding the class changed none of theirs.
  std::mt19937 weave_random(static_cast<unsigned>(seed) + 1);
  for (long k = 0; k < scenes; ++k) {
    const DrawnScene weave = corridor(run.base, weave_random, 0.9, "weave", kWeave);
    survey(weave, 5, weave.drawing);
  }
}

}  // namespace
}  // namespace irloc::test

int main(int argc, char** argv) {
  using namespace irloc;
  // Pixels integrate light over their area: one ray per pixel gives every dot a centroid error that
  // is a fixed function of where it falls on the pixel grid, and a straight drive repeats it in
  // every sighting (docs/survey.md, "Rendered drives"). The renderer's default samples each pixel
  // 3 x 3.
  long scenes = 2, seed = 28, supersampling = sim::Scenario{}.supersampling;
  std::vector<long> seeds;  // --seeds: each seed's scenes in a folder of its own
  std::filesystem::path out = "survey_goal";
  test::GoalRun run;
  for (int k = 1; k < argc; ++k) {
    const std::string_view argument(argv[k]);
    if (test::parse_flag(argument, "--scenes=", 1, scenes) || test::parse_flag(argument, "--seed=", 0, seed) ||
        test::parse_flag(argument, "--supersampling=", 1, supersampling) || test::parse_seeds(argument, seeds)) {
      continue;
    }
    if (argument.rfind("--class=", 0) == 0) {
      run.only = std::string(argument.substr(8));
      continue;
    }
    if (argument == "--reuse") {
      run.reuse = sim::DatasetReuse::reuse_rendered;
      continue;
    }
    if (argument.rfind("--out=", 0) == 0) {
      out = std::string(argument.substr(6));  // made absolute below: irlocd reads the start map from the dataset's folder
      continue;
    }
    std::fprintf(stderr, "survey_goal: unknown argument '%s' (--scenes=N, --seed=S, --seeds=S,S,..., --out=DIR, --reuse, "
                 "--class=NAME, --supersampling=N)\n", argv[k]);
    return 2;
  }
  try {
    out = std::filesystem::absolute(out);
    run.base = sim::load_scenario(IRLOC_SOURCE_DIR "/host_sim/scenarios/survey_corridor_new_markers.yaml");
    run.base.pair_stride = test::kPairStride;
    run.base.supersampling = static_cast<int>(supersampling);
    run.irlocd = sim::irlocd_beside_this_program();
    if (seeds.empty()) {
      test::survey_family(seed, scenes, out, run);
    } else {
      for (const long each : seeds) test::survey_family(each, scenes, out / ("seed_" + std::to_string(each)), run);
    }
    bool met = true;
    for (std::size_t c = 0; c < run.totals.size(); ++c) {
      if (run.only.empty() || run.only == test::kClassNames[c]) met = test::report(test::kClassNames[c], run.totals[c]) && met;
    }
    test::report_pooled_sigmas(test::kClassNames, run.totals);
    std::printf("goal_met %d\n", met ? 1 : 0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "survey_goal: %s\n", e.what());
    return 1;
  }
  return 0;
}
