// The LED landmark source's goal (issue 26, docs/led_landmarks.md "Goal benchmark") on the scene
// family irloc-sim draws from a seed (host_sim/scenario/led_scene_family.hpp): per class, drives of
// 10 pose attempts through one LedLandmarkSource each (so the search, the tracking and the
// recovery of a lost track all run), every strobe pair rendered with the sensor's noise.
//
// Counted per class, over the LED-on frames whose LEDs in view determine the pose ("eligible": at
// least 3 visible under dof 6, 2 under dof 3 and 4; not ambiguous by nature: no other plausible
// pose explains as many of the bright points the frame shows (the visible LEDs and the spurious
// always-on points, which by position are LEDs to any source) as the truth does while predicting
// no more unseen mapped LEDs (AmbiguityOracle, led_ambiguity_oracle.hpp, decides it from the true
// image positions); and not weak by nature: the least-squares fit of the true association, at the
// truth and the config's centre noise pixel_sigma, determines x, y and yaw as well as the robot
// needs (the source's max_position_sigma and max_yaw_sigma); and not a minimal set by nature: the
// truth explains exactly a minimal set of the bright points and, in the room as installed (the
// LEDs' true axes, a dead LED dark), a pose the robot may have explains one fewer, the rest being a
// stray light, and the renderer with the robot there shows those LEDs and no other
// (AmbiguityOracle::stray_light_rival, RivalAxes::installed). The frames of the eligibility
// without that last test ("the points decide") are counted too, with their pose rate, and so are
// those of the stricter test of a rival for every axis the map allows (RivalAxes::every, which
// leaves out the rivals the room's own axes give) and the eligible frames
// less those with a rival for some axes the map allows (RivalAxes::some: frames the map cannot
// decide, though the room does); each miss printed says which it is:
// - the pose rate;
// - the position (3-D) and yaw RMS, and the same of a least-squares fit told the true association
//   (the baseline: refine_pose from the truth on the detections nearest every lit LED's true
//   projection, sim::true_association), over the frames where both have a pose;
// - over every frame: gross errors (a pose further from the truth than 0.1 m and 5 x the
//   baseline's error, or 1 degree and 5 x the baseline's yaw error) and wrong associations (an
//   observation naming an LED whose true projection is more than 3 px from the measured centre);
// - time per attempt from the source's stage times: detection, an attempt that searched, one that
//   tracked (means, wall clock); and the CPU time of this thread per attempt that searched and per
//   attempt that tracked, detection included (means): less inflated than wall clock by a shared
//   machine's load, though not free of it (caches and cores are shared too).
// A missed goal is reported (goal_met 0), not an error; every miss, gross error and wrong
// association is printed to stderr (the first 20 misses per class), and the misses are counted by
// outcome and by how long before them the drive's last pose was given (none yet, <= 0.25, 0.5,
// 1 s, older): whether a track's evidence was at hand.
//
//   bench_led_goal [--scenes=N] [--seed=S] [Google Benchmark flags]
//   (N scenes per class, default 400; S the family's seed, default 2026)

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/markers/led/led_landmark_source.hpp"
#include "host_sim/render/led_family_frames.hpp"
#include "host_sim/scenario/led_scene_family.hpp"
#include "tests/led/led_ambiguity_oracle.hpp"
#include "tests/support/goal_arguments.hpp"
#include "tests/support/thread_cpu_time.hpp"

namespace irloc::test {
namespace {

using sim::LedFamilyClass;
using sim::LedFamilyScene;

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kGrossPosition = 0.10, kGrossYaw = 1 * kDegree, kGrossOverBaseline = 5;
constexpr double kWrongAssociationPx = 3;
constexpr double kBaselineMatchPx = 2;  // a lit LED's detection lies this close to its true projection
constexpr int kMissesPrinted = 20;

int scenes_per_class = 400;
int family_seed = 2026;

int min_leds(Dof dof) { return dof == Dof::full6 ? 3 : 2; }

// refine_pose of mapped points seen at pixels, from the true pose, with the source's loss and
// centre noise.
PoseFit fit_from_truth(const LedFamilyScene& scene, const sim::LedFamilyPair& pair,
                       const std::vector<Eigen::Vector3d>& world, const std::vector<Eigen::Vector2d>& pixels,
                       const led::LedSourceConfig& config) {
  RefinementOptions options;
  options.dof = scene.dof;
  options.loss_scale_px = config.loss_scale_px;
  options.pixel_sigma = config.pixel_sigma;
  return refine_pose(world, pixels, CameraModel(scene.camera), scene.mount, pair.world_from_base, options);
}

// The least-squares fit told the true association (sim::true_association: every lit LED's
// detection, whether the renderer vouches for its visibility or not), refined from the truth.
bool baseline_fit(const LedFamilyScene& scene, const sim::LedFamilyPair& pair, const led::LedDetectionList& detections,
                  const led::LedSourceConfig& config, RigidTransform& pose) {
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  for (const led::LedMatch& match : sim::true_association(pair, detections, kBaselineMatchPx)) {
    world.push_back(scene.map.led_landmarks[static_cast<std::size_t>(match.landmark)].position);
    pixels.push_back(detections[static_cast<std::size_t>(match.detection)].pixel);
  }
  if (static_cast<int>(world.size()) < min_leds(scene.dof)) return false;
  const PoseFit fit = fit_from_truth(scene, pair, world, pixels, config);
  pose = fit.world_from_base;
  return fit.ok;
}

// The layout is weak by nature: the least-squares fit of the visible LEDs' true projections, from
// the truth, leaves the horizontal position or the yaw less certain (at the config's pixel_sigma)
// than the source's max_position_sigma or max_yaw_sigma. A real camera's centre noise makes such a
// frame's pose that uncertain whatever the association; the source says `too uncertain`.
bool weak_by_nature(const LedFamilyScene& scene, const sim::LedFamilyPair& pair, const led::LedSourceConfig& config) {
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  for (const sim::VisibleLed& led : pair.visible) {
    world.push_back(scene.map.led_landmarks[static_cast<std::size_t>(led.landmark)].position);
    pixels.push_back(led.pixel);
  }
  const PoseFit fit = fit_from_truth(scene, pair, world, pixels, config);
  return !fit.ok || std::sqrt(fit.covariance(0, 0) + fit.covariance(1, 1)) > config.max_position_sigma ||
         std::sqrt(fit.covariance(5, 5)) > config.max_yaw_sigma;
}

struct Tally {
  int frames = 0, eligible = 0, posed = 0, posed_not_eligible = 0, ambiguous_by_nature = 0, gross = 0, wrong = 0;
  int weak_by_nature = 0, posed_weak = 0;  // frames weak by nature, and the poses given on them
  // Frames that are a minimal set by nature (a stray light's rival in the room as installed, which
  // the renderer shows: RivalAxes::installed), and the poses given on them.
  int minimal_by_nature = 0, posed_minimal = 0;
  int rivals_not_shown = 0;  // rivals in the room by the geometry that the renderer does not show
  // The same with a rival for every axis the map allows (RivalAxes::every: the test of sessions 20
  // to 22, which leaves out rivals that the room's own axes give).
  int minimal_every_axes = 0, posed_minimal_every_axes = 0;
  // Eligible frames with a stray light's rival for some axes the map allows (RivalAxes::some): the
  // map cannot decide them, though the room does; and the poses given on them.
  int minimal_given_map = 0, posed_minimal_given_map = 0;
  int compared = 0;  // eligible posed frames with a baseline too
  double squared_position = 0, squared_yaw = 0, baseline_squared_position = 0, baseline_squared_yaw = 0;
  double detect_ms = 0, search_ms = 0, track_ms = 0;
  double search_attempt_cpu_ms = 0, track_attempt_cpu_ms = 0;  // whole attempts, detection included
  int searches = 0, tracks = 0, printed = 0;
  std::map<std::string, int> misses;  // eligible frames without a pose, by outcome
  // The same misses by outcome and by the age of the scene's last pose (the track's evidence).
  std::map<std::string, int> misses_by_recency;
  std::map<std::string, int> minimal_misses;  // frames minimal by nature without a pose, by outcome
  // Searched poses by the winner's margin (LEDs explained beyond the runner-up), right and wrong.
  std::map<int, int> right_margins, wrong_margins;

  static double rms(double squared, int n) { return std::sqrt(squared / std::max(n, 1)); }
};

void describe(const char* what, LedFamilyClass family_class, int index, int attempt, const LedFamilyScene& scene,
              const sim::LedFamilyPair& pair, std::size_t detections, const SourceResult& result) {
  const Eigen::Vector3d& t = pair.world_from_base.translation;
  const bool spurious = std::any_of(scene.clutter.begin(), scene.clutter.end(), [](const sim::LedClutter& clutter) {
    return clutter.kind == sim::LedClutter::Kind::spurious;
  });
  std::fprintf(stderr,
               "led_goal %s: %s scene %d attempt %d (%zu LEDs, %zu visible, %zu lit, %zu stray, %zu detections, %s, f %.0f, "
               "%d-bit, sigma %.2f px%s%s%s): "
               "truth (%.3f, %.3f, %.3f) yaw %.1f deg: %s",
               std::string(to_string(family_class)).c_str(), what, index, attempt, scene.map.led_landmarks.size(),
               pair.visible.size(), pair.lit.size(), pair.stray.size(), detections,
               scene.camera.model == LensModel::plumb_bob ? "pinhole" : "fisheye", scene.camera.fx, scene.bit_depth,
               scene.psf_sigma, scene.strided ? ", strided" : "",
               std::any_of(scene.dead.begin(), scene.dead.end(), [](bool d) { return d; }) ? ", dead LED" : "",
               spurious ? ", spurious point" : "", t.x(),
               t.y(), t.z(), rpy_from_rotation(pair.world_from_base.rotation).yaw / kDegree, result.outcome);
  if (result.ok) {
    const Eigen::Vector3d& p = result.world_from_base.translation;
    std::fprintf(stderr, " at (%.3f, %.3f, %.3f) yaw %.1f deg, %zu LEDs", p.x(), p.y(), p.z(),
                 rpy_from_rotation(result.world_from_base.rotation).yaw / kDegree, result.observations.size());
  }
  std::fprintf(stderr, "\n");
}

// How long before `now` the scene's last pose was given (seconds; negative: none yet).
const char* recency(double last_posed_s, double now) {
  if (last_posed_s < 0) return "no pose before";
  const double age = now - last_posed_s;
  return age <= 0.25 ? "last pose <= 0.25 s before" : age <= 0.5 ? "last pose <= 0.5 s before"
                     : age <= 1.0 ? "last pose <= 1 s before" : "last pose > 1 s before";
}

double stage_ms(const SourceResult& result, std::string_view name) {
  for (const StageTime& stage : result.times) {
    if (name == stage.name) return stage.milliseconds;
  }
  return 0;
}

void run_class(benchmark::State& state, LedFamilyClass family_class) {
  const led::LedSourceConfig config;
  Tally tally;
  for (auto _ : state) {
    tally = Tally{};
    sim::LedFamilyPair pair, at_rival;
    for (int index = 0; index < scenes_per_class; ++index) {
      const LedFamilyScene scene = sim::draw_led_family_scene(static_cast<std::uint64_t>(family_seed), family_class, index);
      const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
      led::LedLandmarkSource source(setup, config);
      const AmbiguityOracle oracle(scene, config);
      const CameraModel camera(scene.camera);
      SourceResult result;
      double last_posed_s = -1;  // the time of the scene's last pose; -1: none yet
      for (int attempt = 0; attempt < static_cast<int>(scene.attempt_times.size()); ++attempt) {
        sim::render_led_family_pair(scene, attempt, config.threshold, pair);
        const double cpu_start = thread_cpu_seconds();
        source.process(SourceInput{pair.on, &pair.off}, result);
        const double attempt_cpu_ms = 1000 * (thread_cpu_seconds() - cpu_start);
        const led::LedDiagnostics seen = source.last_diagnostics();
        ++tally.frames;
        (seen.hypotheses > 0 ? tally.search_attempt_cpu_ms : tally.track_attempt_cpu_ms) += attempt_cpu_ms;
        tally.detect_ms += stage_ms(result, "led detect");
        (seen.hypotheses > 0 ? tally.search_ms : tally.track_ms) += stage_ms(result, "led pose");
        ++(seen.hypotheses > 0 ? tally.searches : tally.tracks);

        bool eligible = static_cast<int>(pair.visible.size()) >= min_leds(scene.dof);
        bool weak = false;
        if (eligible && oracle.ambiguous(pair.world_from_base, pair)) {
          eligible = false;
          ++tally.ambiguous_by_nature;
        } else if (eligible && weak_by_nature(scene, pair, config)) {
          eligible = false;
          weak = true;
          ++tally.weak_by_nature;
        }
        const bool minimal_every_axes = eligible && oracle.stray_light_rival(pair.world_from_base, pair).has_value();
        tally.minimal_every_axes += minimal_every_axes;
        int rivals_tried = 0;
        const std::optional<RigidTransform> stray_light_rival =
            eligible ? oracle.stray_light_rival(pair.world_from_base, pair, AmbiguityOracle::RivalAxes::installed,
                                                [&](const RigidTransform& rival) {
                                                  ++rivals_tried;
                                                  return renderer_shows_stray_light_rival(scene, attempt, rival, pair,
                                                                              config.threshold, at_rival);
                                                })
                     : std::nullopt;
        const bool minimal = stray_light_rival.has_value();
        tally.rivals_not_shown += rivals_tried - minimal;
        if (minimal) {
          eligible = false;
          ++tally.minimal_by_nature;
        }
        const bool minimal_given_map =
            eligible && oracle.stray_light_rival(pair.world_from_base, pair, AmbiguityOracle::RivalAxes::some);
        tally.minimal_given_map += minimal_given_map;
        tally.eligible += eligible;
        if (!result.ok) {
          if (minimal) ++tally.minimal_misses[result.outcome];
          if ((eligible || minimal) && tally.printed++ < kMissesPrinted) {
            describe(minimal             ? "miss, minimal by nature"
                     : minimal_given_map ? "miss, minimal given the map"
                                         : "miss",
                     family_class, index, attempt, scene, pair,
                     seen.detections.size(), result);
            if (minimal) {
              const Eigen::Vector3d& r = stray_light_rival->translation;
              std::fprintf(stderr, "  a stray light's rival at (%.3f, %.3f, %.3f) yaw %.1f deg\n", r.x(), r.y(), r.z(),
                           rpy_from_rotation(stray_light_rival->rotation).yaw / kDegree);
            }
          }
          if (eligible) {
            ++tally.misses[result.outcome];
            ++tally.misses_by_recency[std::string(result.outcome) + ", " +
                                      recency(last_posed_s, scene.attempt_times[static_cast<std::size_t>(attempt)])];
          }
          continue;
        }
        last_posed_s = scene.attempt_times[static_cast<std::size_t>(attempt)];
        eligible ? ++tally.posed : ++tally.posed_not_eligible;
        tally.posed_weak += weak;
        tally.posed_minimal += minimal;
        tally.posed_minimal_given_map += minimal_given_map;
        tally.posed_minimal_every_axes += minimal_every_axes;
        const RigidTransform camera_from_world = (pair.world_from_base * scene.mount).inverse();
        const bool wrong = std::any_of(result.observations.begin(), result.observations.end(),
                                       [&](const PointObservation& observation) {
                                         Eigen::Vector2d pixel;
                                         return !camera.project(camera_from_world * observation.world, pixel) ||
                                                (pixel - observation.pixel).norm() > kWrongAssociationPx;
                                       });
        RigidTransform baseline;
        const bool has_baseline = baseline_fit(scene, pair, seen.detections, config, baseline);
        const double error = (result.world_from_base.translation - pair.world_from_base.translation).norm();
        const double yaw_error = std::abs(wrap_angle(rpy_from_rotation(result.world_from_base.rotation).yaw -
                                                     rpy_from_rotation(pair.world_from_base.rotation).yaw));
        const double baseline_error =
            has_baseline ? (baseline.translation - pair.world_from_base.translation).norm() : 0;
        const double baseline_yaw_error =
            has_baseline ? std::abs(wrap_angle(rpy_from_rotation(baseline.rotation).yaw -
                                               rpy_from_rotation(pair.world_from_base.rotation).yaw))
                         : 0;
        const bool gross = error > std::max(kGrossPosition, kGrossOverBaseline * baseline_error) ||
                           yaw_error > std::max(kGrossYaw, kGrossOverBaseline * baseline_yaw_error);
        if (seen.hypotheses > 0) ++(wrong ? tally.wrong_margins : tally.right_margins)[seen.association.margin];
        if (wrong) {
          ++tally.wrong;
          describe("wrong association", family_class, index, attempt, scene, pair, seen.detections.size(), result);
        }
        if (gross) {
          ++tally.gross;
          describe("gross", family_class, index, attempt, scene, pair, seen.detections.size(), result);
        }
        if (eligible && has_baseline && !gross) {
          ++tally.compared;
          tally.squared_position += error * error;
          tally.squared_yaw += yaw_error * yaw_error;
          tally.baseline_squared_position += baseline_error * baseline_error;
          tally.baseline_squared_yaw += baseline_yaw_error * baseline_yaw_error;
        }
      }
    }
  }
  const double pose_rate = static_cast<double>(tally.posed) / std::max(tally.eligible, 1);
  const double position_mm = 1000 * Tally::rms(tally.squared_position, tally.compared);
  const double baseline_mm = 1000 * Tally::rms(tally.baseline_squared_position, tally.compared);
  const double detect_ms = tally.detect_ms / std::max(tally.frames, 1);
  const double search_ms = tally.search_ms / std::max(tally.searches, 1);
  const double track_ms = tally.track_ms / std::max(tally.tracks, 1);
  state.counters["frames"] = tally.frames;
  state.counters["eligible"] = tally.eligible;
  state.counters["ambiguous_by_nature"] = tally.ambiguous_by_nature;
  state.counters["weak_by_nature"] = tally.weak_by_nature;
  state.counters["posed_weak"] = tally.posed_weak;
  state.counters["minimal_by_nature"] = tally.minimal_by_nature;
  state.counters["posed_minimal"] = tally.posed_minimal;
  state.counters["rivals_not_shown"] = tally.rivals_not_shown;
  // The eligibility before the minimal-set test: the frames the bright points decide.
  const int points_decide = tally.eligible + tally.minimal_by_nature;
  // The eligibility of sessions 20 to 22: less the frames with a rival for every axis the map allows.
  const int decided_every_axes = points_decide - tally.minimal_every_axes;
  state.counters["minimal_every_axes"] = tally.minimal_every_axes;
  state.counters["eligible_every_axes"] = decided_every_axes;
  state.counters["pose_rate_every_axes"] =
      static_cast<double>(tally.posed + tally.posed_minimal - tally.posed_minimal_every_axes) /
      std::max(decided_every_axes, 1);
  state.counters["eligible_points_decide"] = points_decide;
  state.counters["pose_rate_points_decide"] =
      static_cast<double>(tally.posed + tally.posed_minimal) / std::max(points_decide, 1);
  // The eligible frames less those the map cannot decide (minimal_given_map).
  const int decided_given_map = tally.eligible - tally.minimal_given_map;
  state.counters["minimal_given_map"] = tally.minimal_given_map;
  state.counters["eligible_given_map"] = decided_given_map;
  state.counters["pose_rate_given_map"] =
      static_cast<double>(tally.posed - tally.posed_minimal_given_map) / std::max(decided_given_map, 1);
  state.counters["posed"] = tally.posed;
  state.counters["pose_rate"] = pose_rate;
  state.counters["posed_not_eligible"] = tally.posed_not_eligible;
  state.counters["position_rms_mm"] = position_mm;
  state.counters["baseline_rms_mm"] = baseline_mm;
  state.counters["yaw_rms_deg"] = Tally::rms(tally.squared_yaw, tally.compared) / kDegree;
  state.counters["baseline_yaw_deg"] = Tally::rms(tally.baseline_squared_yaw, tally.compared) / kDegree;
  state.counters["gross"] = tally.gross;
  state.counters["wrong_association"] = tally.wrong;
  state.counters["detect_ms"] = detect_ms;
  state.counters["search_ms"] = search_ms;
  state.counters["track_ms"] = track_ms;
  state.counters["searches"] = tally.searches;
  state.counters["search_attempt_cpu_ms"] = tally.search_attempt_cpu_ms / std::max(tally.searches, 1);
  state.counters["track_attempt_cpu_ms"] = tally.track_attempt_cpu_ms / std::max(tally.tracks, 1);
  for (const auto& [outcome, count] : tally.misses) state.counters["miss_" + outcome] = count;
  for (const auto& [outcome, count] : tally.minimal_misses) {
    std::fprintf(stderr, "led_goal %s: minimal by nature, no pose: %s %d\n", std::string(to_string(family_class)).c_str(),
                 outcome.c_str(), count);
  }
  for (const auto& [what, count] : tally.misses_by_recency) {
    std::fprintf(stderr, "led_goal %s: misses %s: %d\n", std::string(to_string(family_class)).c_str(), what.c_str(), count);
  }
  std::string margins;
  for (const auto* histogram : {&tally.right_margins, &tally.wrong_margins}) {
    margins += histogram == &tally.right_margins ? " right:" : "; wrong:";
    for (const auto& [margin, count] : *histogram) {
      char entry[32];
      std::snprintf(entry, sizeof entry, " %dx%d", margin, count);
      margins += entry;
    }
  }
  std::fprintf(stderr, "led_goal %s: searched poses by margin (LEDs x poses)%s\n",
               std::string(to_string(family_class)).c_str(), margins.c_str());
  state.counters["goal_met"] = pose_rate >= 0.95 && tally.gross == 0 && tally.wrong == 0 &&
                               position_mm <= 1.5 * baseline_mm && detect_ms <= 0.1 && search_ms <= 0.5 &&
                               track_ms <= 0.05;
}

void BM_LedGoalWallDof6(benchmark::State& state) { run_class(state, LedFamilyClass::wall_dof6); }
void BM_LedGoalWallDof4(benchmark::State& state) { run_class(state, LedFamilyClass::wall_dof4); }
void BM_LedGoalTwoWallsDof3(benchmark::State& state) { run_class(state, LedFamilyClass::two_walls_dof3); }
void BM_LedGoalCeilingDof3(benchmark::State& state) { run_class(state, LedFamilyClass::ceiling_dof3); }
void BM_LedGoalClusterDof6(benchmark::State& state) { run_class(state, LedFamilyClass::clustered_dof6); }
BENCHMARK(BM_LedGoalWallDof6)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LedGoalWallDof4)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LedGoalTwoWallsDof3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LedGoalCeilingDof3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_LedGoalClusterDof6)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace irloc::test

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  using irloc::test::family_seed, irloc::test::scenes_per_class;
  if (!irloc::test::read_goal_arguments("bench_led_goal", argc, argv, scenes_per_class, family_seed)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
